#pragma once
// An OpenMP loop over [0, n) whose body may throw. An exception leaving an OpenMP region ends the
// program (std::terminate), and the body may call a user's checker (OMPL's StateValidityChecker) or
// meet a bad input; so each iteration's exception is caught, every iteration still runs, and the
// lowest index's exception is rethrown after the region: the same error whatever the threads.
#include <algorithm>
#include <exception>
#include <mutex>

namespace svmp::cspace {

template <class Body>
void parallelFor(int n, int threads, int chunk, Body&& body) {
  std::exception_ptr first;
  int first_index = n;
  std::mutex mutex;
#pragma omp parallel for schedule(dynamic, chunk) num_threads(std::max(threads, 1))
  for (int i = 0; i < n; ++i) {
    try {
      body(i);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex);
      if (i < first_index) first_index = i, first = std::current_exception();
    }
  }
  if (first) std::rethrow_exception(first);
}

}  // namespace svmp::cspace
