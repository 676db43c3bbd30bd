#include "bench/experiments/provenance.hpp"

#include <ctime>
#include <fstream>

#include <unistd.h>

#include "svm/simd_loops.hpp"

namespace svmp::experiments {

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%Y-%m-%d %H:%M:%S", &utc);
  return buffer;
}

std::string hostName() {
  char buffer[256] = {};
  return gethostname(buffer, sizeof(buffer) - 1) == 0 && buffer[0] ? buffer : "UNKNOWN";
}

std::string cpuInfo() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model;
  int processors = 0;
  while (std::getline(in, line)) {
    if (line.rfind("processor", 0) == 0) ++processors;
    if (model.empty() && line.rfind("model name", 0) == 0) model = line.substr(line.find(':') + 2);
  }
  return (model.empty() ? "unknown processor" : model) + ", " + std::to_string(processors) + " logical processors";
}

Provenance Provenance::now() {
  return {SVMP_VERSION,
          sourceRevision(),
          utcNow(),
          hostName(),
          cpuInfo(),
          svm::loops::usingAvx512() ? "avx512" : svm::loops::usingAvx2() ? "avx2" : "sse2"};
}

}  // namespace svmp::experiments
