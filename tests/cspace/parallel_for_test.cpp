// cspace::parallelFor: every iteration runs, and the exception of the lowest index that threw leaves
// the loop whatever the threads (an exception leaving an OpenMP region would end the program).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cspace/parallel_for.hpp"

namespace svmp::cspace {
namespace {

TEST(ParallelFor, RethrowsTheLowestIndexsExceptionAfterEveryIterationRan) {
  for (int threads : {1, 2, 4}) {
    std::vector<std::atomic<int>> ran(1000);
    std::atomic<bool> last_threw{false};
    try {
      parallelFor(1000, threads, 7, [&](int i) {
        ++ran[i];
        // On several threads index 0 throws last in time (when it may wait no longer: 2 s), so a loop
        // that kept the first exception caught would report another.
        if (i == 0 && threads > 1) {
          const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
          while (!last_threw && std::chrono::steady_clock::now() < until) std::this_thread::yield();
        }
        if (i % 300 == 0 || i == 999) {
          if (i == 999) last_threw = true;
          throw std::runtime_error("index " + std::to_string(i));
        }
      });
      ADD_FAILURE() << "nothing thrown, " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "index 0") << threads << " threads";
    }
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(ran[i].load(), 1) << i << ", " << threads << " threads";
  }
}

TEST(ParallelFor, NoIterationsNoCalls) {
  int calls = 0;
  parallelFor(0, 2, 1, [&](int) { ++calls; });
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace svmp::cspace
