#include "bench/experiments/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

namespace svmp::experiments {
namespace {

// A name beside `file` that no other process writes (shards of one sweep may share an output name).
std::string temporaryBeside(const std::string& file) { return file + ".tmp." + std::to_string(::getpid()); }

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

void writeFileAtomically(const std::string& file, const std::string& text) {
  const std::string tmp = temporaryBeside(file);
  errno = 0;
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  if (out) out << text;
  if (out) out.close();
  if (!out || std::rename(tmp.c_str(), file.c_str()) != 0) {
    const std::string reason = errno ? std::strerror(errno) : "write failed";
    std::remove(tmp.c_str());
    throw std::runtime_error(file + ": cannot write: " + reason);
  }
}

void checkWritable(const std::string& flag, const std::string& file) {
  if (std::filesystem::is_directory(file))
    throw std::runtime_error("flag " + flag + ": cannot write '" + file + "': it is a directory");
  // Its folder is made, as --svg's is (the docs write into results/ subfolders); the file's own
  // probe below tries the folder too.
  if (const std::filesystem::path parent = std::filesystem::path(file).parent_path(); !parent.empty())
    createDirectories(flag, parent.string());
  probeWrite(flag, "'" + file + "'", temporaryBeside(file));
}

void makeDirectory(const std::string& flag, const std::string& dir) {
  createDirectories(flag, dir);
  probeWrite(flag, "into directory '" + dir + "'", (std::filesystem::path(dir) / temporaryBeside(".svmp-probe")).string());
}

}  // namespace svmp::experiments
