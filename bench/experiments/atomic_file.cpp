#include "bench/experiments/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <signal.h>
#include <unistd.h>

namespace svmp::experiments {
namespace {

// A name beside `file` that no other process writes (shards of one sweep may share an output name).
std::string temporaryBeside(const std::string& file) { return file + ".tmp." + std::to_string(::getpid()); }

// `file` with its symbolic links followed (the rename then replaces the file a link names, not the
// link), at most 40 of them, as the kernel allows.
std::string followLinks(std::string file) {
  std::error_code error;
  for (int hop = 0; hop < 40 && std::filesystem::is_symlink(file, error); ++hop) {
    const std::filesystem::path target = std::filesystem::read_symlink(file, error);
    if (error) break;
    file = (target.is_absolute() ? target : std::filesystem::path(file).parent_path() / target).string();
  }
  return file;
}

// An existing file that is not a regular one (/dev/null, a FIFO): written to directly, as a rename
// over it would replace the device node with a file.
bool isSpecial(const std::string& file) {
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  return !error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
         !std::filesystem::is_directory(status);
}

// The temporary file being written, removed by a signal that ends the program (SIGINT, SIGTERM,
// SIGHUP) so a killed run leaves no FILE.tmp.PID behind; only async-signal-safe calls in the handler.
char in_flight[4096] = "";
extern "C" void removeInFlight(int sig) {
  if (in_flight[0]) ::unlink(in_flight);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}
void watchSignals() {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP})
      if (::signal(sig, SIG_IGN) != SIG_IGN) ::signal(sig, removeInFlight);  // keep an ignored signal ignored
    return true;
  }();
  (void)installed;
}

// Creates and removes `probe`; throws naming `flag` and `what` when it cannot be created.
void probeWrite(const std::string& flag, const std::string& what, const std::string& probe) {
  errno = 0;
  std::ofstream out(probe, std::ios::binary | std::ios::trunc);
  if (!out) {
    const std::string reason = errno ? std::strerror(errno) : "cannot open";
    throw std::runtime_error("flag " + flag + ": cannot write " + what + ": " + reason);
  }
  out.close();
  std::remove(probe.c_str());
}

void createDirectories(const std::string& flag, const std::string& dir) {
  std::error_code error;
  if (!std::filesystem::create_directories(dir, error) && error)
    throw std::runtime_error("flag " + flag + ": cannot create directory '" + dir + "': " + error.message());
}

}  // namespace

void writeFileAtomically(const std::string& given, const std::string& text) {
  const std::string file = followLinks(given);
  errno = 0;
  if (isSpecial(file)) {
    std::ofstream out(file, std::ios::binary | std::ios::app);
    if (out) out << text;
    if (out) out.close();
    if (!out) throw std::runtime_error(given + ": cannot write: " + (errno ? std::strerror(errno) : "write failed"));
    return;
  }
  const std::string tmp = temporaryBeside(file);
  watchSignals();
  if (tmp.size() < sizeof in_flight) std::memcpy(in_flight, tmp.c_str(), tmp.size() + 1);
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  if (out) out << text;
  if (out) out.close();
  const bool done = out && std::rename(tmp.c_str(), file.c_str()) == 0;
  const int reason = errno;
  if (!done) std::remove(tmp.c_str());
  in_flight[0] = '\0';
  if (!done) throw std::runtime_error(given + ": cannot write: " + (reason ? std::strerror(reason) : "write failed"));
}

void checkWritable(const std::string& flag, const std::string& given) {
  const std::string file = followLinks(given);
  if (std::filesystem::is_directory(file))
    throw std::runtime_error("flag " + flag + ": cannot write '" + given + "': it is a directory");
  if (isSpecial(file)) {  // written to directly; asked, not opened (opening a FIFO waits for a reader)
    if (::access(file.c_str(), W_OK) != 0)
      throw std::runtime_error("flag " + flag + ": cannot write '" + given + "': " + std::strerror(errno));
    return;
  }
  // Its folder is made, as --svg's is (the docs write into results/ subfolders); the file's own
  // probe below tries the folder too.
  if (const std::filesystem::path parent = std::filesystem::path(file).parent_path(); !parent.empty())
    createDirectories(flag, parent.string());
  probeWrite(flag, "'" + file + "'", temporaryBeside(file));
}

void checkDistinct(const std::vector<std::pair<std::string, std::string>>& flag_files,
                   const std::vector<std::pair<std::string, std::string>>& flag_dirs) {
  std::vector<std::pair<std::string, std::string>> all = flag_files;
  all.insert(all.end(), flag_dirs.begin(), flag_dirs.end());
  std::vector<std::string> resolved;
  for (const auto& [flag, file] : all) {
    std::error_code error;
    // Absolute first: weakly_canonical leaves a relative name whose head does not exist as it is, and
    // z.json would not meet ./z.json or /dir/z.json.
    const std::string path =
        file.empty() ? "" : std::filesystem::weakly_canonical(std::filesystem::absolute(followLinks(file)), error).string();
    resolved.push_back(error ? file : path);
  }
  const auto fail = [&](size_t j, const std::string& what, size_t i) {
    throw std::runtime_error("flag " + all[j].first + ": '" + all[j].second + "' " + what + " " + all[i].first +
                             "'s file");
  };
  for (size_t j = 0; j < all.size(); ++j)
    for (size_t i = 0; i < all.size(); ++i) {
      if (i == j || resolved[j].empty() || resolved[i].empty() || isSpecial(resolved[i])) continue;
      const bool i_is_file = i < flag_files.size();
      if (i < j && i_is_file && resolved[j] == resolved[i]) fail(j, "is also", i);  // files come first
      // A file that is already a directory (--json /tmp) is checkWritable's to refuse, and what lies in
      // it (the scenario) is no clash.
      if (i_is_file && resolved[j].size() > resolved[i].size() && resolved[j].rfind(resolved[i] + "/", 0) == 0 &&
          !std::filesystem::is_directory(resolved[i]))
        fail(j, "lies inside", i);
    }
}

void makeDirectory(const std::string& flag, const std::string& dir) {
  createDirectories(flag, dir);
  probeWrite(flag, "into directory '" + dir + "'", (std::filesystem::path(dir) / temporaryBeside(".svmp-probe")).string());
}

}  // namespace svmp::experiments
