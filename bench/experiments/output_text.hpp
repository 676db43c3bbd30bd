#pragma once
// Text that goes into output files: JSON string escaping and file-name components that cannot leave
// their directory.
#include <string>
#include <vector>

namespace svmp::experiments {

// The JSON string literal of `text`, quotes included (RFC 8259: ", \ and control characters escaped).
std::string jsonString(const std::string& text);

// `text` with every character outside [A-Za-z0-9._-] replaced by '_' and leading dots removed, so
// "../../x" cannot name a file outside the directory it is joined to; past 120 characters, the first
// 100 and a hash of the whole. Never empty.
std::string safeFileName(const std::string& text);

// A coordinate or length in SVG output: two decimals.
std::string svgNumber(double v);
// `text` with &, < and > escaped for XML character data, and what XML 1.0 cannot hold (control
// characters, U+FFFE, U+FFFF) as '?'.
std::string escapeXml(const std::string& text);

// Mean, sample standard deviation and median of a set of numbers (all 0 when empty).
struct Stats {
  double mean = 0, std = 0, median = 0;
  int count = 0;
};
Stats statsOf(std::vector<double> v);
// {"mean": .., "std": .., "median": .., "n": ..}
std::string jsonStats(const Stats& s);
// "mean ± std" with `precision` decimals; "-" when empty.
std::string meanStd(const Stats& s, int precision);
// `text` padded to `width` code points (std::setw counts bytes, and "±" is two).
std::string pad(const std::string& text, size_t width);

}  // namespace svmp::experiments
