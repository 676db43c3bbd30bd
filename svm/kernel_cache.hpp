// Least-recently-used cache of kernel columns in float storage, with a size limit in MB.
//
// Same policy as libsvm's Cache (Chang & Lin, "LIBSVM: a library for support vector machines",
// ACM TIST 2011, sec. 5.1): a column is kept with the length it was last requested at (the active
// set size under shrinking) and extended on demand; swapIndex() follows the solver's permutation,
// cutting a column short of the first swapped entry it does not hold (libsvm evicts it).
// Float halves the memory per entry, so twice as many columns fit; the solver accumulates in
// double. Evicted and outgrown buffers are kept as spares and reused before new memory is taken:
// freeing them returned pages to the OS and the next column faulted them in again (a quarter of a
// warm retrain's time went to the kernel zeroing pages). Memory counts buffer capacities, spares
// included. Not thread-safe: one cache per solver.
#pragma once

#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace svmp::svm {

class KernelCache {
 public:
  // Holds at least two full columns whatever size_mb says (SMO needs columns i and j together).
  KernelCache(int n, double size_mb);

  // Column i with at least len entries. Entries [*filled, len) are not yet computed: the caller
  // fills them. The pointer stays valid until the next request() or swapIndex().
  float* request(int i, int len, int* filled);

  void swapIndex(int i, int j);
  // Same as swapIndex for each pair in order, but visits each cached column once: shrinking swaps
  // thousands of pairs at a time, and a column-major pass keeps each column in cache.
  void swapIndices(const std::vector<std::pair<int, int>>& swaps);

  // A retained cache follows its solver to a new problem (SolverWorkspace): n slots, columns at
  // slots >= n dropped and the others cut to n entries; evictColumn drops one; cached() is a column
  // and its length (0 when absent) without counting a hit or touching the LRU order.
  void resize(int n);
  void evictColumn(int i);
  void clear();
  float* cached(int i, int* len);

  int size() const { return static_cast<int>(columns_.size()); }
  long long capacityFloats() const { return capacity_; }
  long long hits() const { return hits_; }
  long long misses() const { return misses_; }

 private:
  struct Column {
    std::unique_ptr<float[]> data;
    int len = 0;
    int capacity = 0;  // floats allocated for data (>= len)
    int prev = -1;
    int next = -1;
  };
  void unlink(int i);
  void linkNewest(int i);
  void evict(int i);
  struct Buffer {
    std::unique_ptr<float[]> data;
    int capacity;
    bool fresh;  // new memory, counted against free_
  };
  // A buffer of at least len floats: the smallest fitting spare, else new memory (releasing
  // spares, then evicting the least recently used columns, until it fits). own_capacity: the
  // requesting column's buffer, freed by the caller once copied.
  Buffer takeBuffer(int len, int own_capacity);
  void keepSpare(std::unique_ptr<float[]> data, int capacity);

  std::vector<Column> columns_;
  int oldest_ = -1;  // LRU list head
  int newest_ = -1;  // LRU list tail
  long long capacity_;
  long long free_;  // capacity_ minus the capacities of all buffers held (columns and spares)
  std::multimap<int, std::unique_ptr<float[]>> spares_;  // by capacity
  long long hits_ = 0;
  long long misses_ = 0;
};

}  // namespace svmp::svm
