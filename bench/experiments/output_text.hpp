#pragma once
// Text that goes into output files: JSON string escaping and file-name components that cannot leave
// their directory.
#include <string>

namespace svmp::experiments {

// The JSON string literal of `text`, quotes included (RFC 8259: ", \ and control characters escaped).
std::string jsonString(const std::string& text);

// `text` with every character outside [A-Za-z0-9._-] replaced by '_' and leading dots removed, so
// "../../x" cannot name a file outside the directory it is joined to. Never empty.
std::string safeFileName(const std::string& text);

}  // namespace svmp::experiments
