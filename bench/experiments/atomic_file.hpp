#pragma once
// Output files are written whole or not at all: the text goes to FILE.tmp.PID, which is renamed over FILE
// only when every byte was written (and removed when SIGINT, SIGTERM or SIGHUP ends the program while
// it is written). A symbolic link is followed, so the file it names is replaced, not the link; an
// existing file that is not a regular one (/dev/null, a FIFO) is written to directly. Throws
// std::runtime_error naming the file and the OS reason.
#include <string>
#include <utility>
#include <vector>

namespace svmp::experiments {

void writeFileAtomically(const std::string& file, const std::string& text);

// Makes `file`'s folder, then throws std::runtime_error (naming `flag`, the file and the OS reason)
// when `file` could not be created there; run before the work so a bad path fails at once, not after
// the whole run.
void checkWritable(const std::string& flag, const std::string& file);
// Throws std::runtime_error when two of the (flag, file) pairs name one file (after links; empty
// names and devices such as /dev/null aside): an output over the scenario it reads, or over another;
// when an output directory of `flag_dirs` is one of the files; or when a file or directory lies inside
// one of the files that is not a directory yet (--ompl-log x.json/y.log with --json x.json). Run
// before anything is written.
void checkDistinct(const std::vector<std::pair<std::string, std::string>>& flag_files,
                   const std::vector<std::pair<std::string, std::string>>& flag_dirs = {});
// Makes the folder `dir` (with its parents) for `flag` and tries a file in it; throws
// std::runtime_error naming both and the OS reason when either fails.
void makeDirectory(const std::string& flag, const std::string& dir);

}  // namespace svmp::experiments
