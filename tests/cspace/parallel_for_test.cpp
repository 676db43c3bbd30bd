// cspace::parallelFor: every iteration runs, and the exception of the lowest index that threw leaves
// the loop whatever the threads (an exception leaving an OpenMP region would end the program).
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "cspace/parallel_for.hpp"

namespace svmp::cspace {
namespace {

TEST(ParallelFor, RethrowsTheLowestIndexsExceptionAfterEveryIterationRan) {
  for (int threads : {1, 2, 4}) {
    std::vector<std::atomic<int>> ran(1000);
    try {
      parallelFor(1000, threads, 7, [&](int i) {
        ++ran[i];
        if (i % 300 == 299) throw std::runtime_error("index " + std::to_string(i));
      });
      ADD_FAILURE() << "nothing thrown, " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "index 299") << threads << " threads";
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
