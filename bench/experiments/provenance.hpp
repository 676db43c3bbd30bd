#pragma once
// What produced a result file: the code's version and git revision, the machine and when it ran.
// svmp-plan's --json and --ompl-log carry it, so a number can be traced to the code and hardware that
// made it (counts move with the code, times with the machine; docs/reproduction.md).
#include <string>

namespace svmp::experiments {

// `git describe --always --dirty` of the source tree when the drivers were last built ("unknown"
// outside a git checkout); generated at build time by cmake/revision.cmake.
const char* sourceRevision();

struct Provenance {
  std::string version;   // the project's version (CMakeLists.txt)
  std::string revision;  // sourceRevision()
  std::string started;   // "YYYY-MM-DD HH:MM:SS" (UTC)
  std::string host;
  std::string cpu;       // the processor's model name and logical processor count
  std::string simd;      // the SVM loops' instruction set: avx512, avx2 or sse2 (SVMP_SIMD caps it)
  static Provenance now();
};

// The current UTC time as Provenance::started has it.
std::string utcNow();
std::string hostName();
// The processor model and count, from /proc/cpuinfo (as OMPL's machine::getCPUInfo reads it).
std::string cpuInfo();

}  // namespace svmp::experiments
