#include "svm/kernel_cache.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

namespace svmp::svm {

KernelCache::KernelCache(int n, double size_mb) : columns_(n) {
  // Capped at 2^60 floats, far beyond any memory: a size_mb past 2^63 floats had overflowed the
  // conversion and left the least cache.
  const long long floats = static_cast<long long>(std::min(size_mb * 1024.0 * 1024.0 / sizeof(float), 0x1p60));
  capacity_ = std::max(floats, 2LL * n);
  free_ = capacity_;
}

void KernelCache::unlink(int i) {
  Column& c = columns_[i];
  if (c.prev >= 0)
    columns_[c.prev].next = c.next;
  else
    oldest_ = c.next;
  if (c.next >= 0)
    columns_[c.next].prev = c.prev;
  else
    newest_ = c.prev;
  c.prev = c.next = -1;
}

void KernelCache::linkNewest(int i) {
  Column& c = columns_[i];
  c.prev = newest_;
  c.next = -1;
  if (newest_ >= 0)
    columns_[newest_].next = i;
  else
    oldest_ = i;
  newest_ = i;
}

void KernelCache::evict(int i) {
  unlink(i);
  Column& c = columns_[i];
  keepSpare(std::move(c.data), c.capacity);
  c.len = c.capacity = 0;
}

void KernelCache::keepSpare(std::unique_ptr<float[]> data, int capacity) {
  if (capacity > 0) spares_.emplace(capacity, std::move(data));
}

KernelCache::Buffer KernelCache::takeBuffer(int len, int own_capacity) {
  while (true) {
    if (auto fit = spares_.lower_bound(len); fit != spares_.end()) {
      Buffer out{std::move(fit->second), fit->first, false};
      spares_.erase(fit);
      return out;
    }
    // The caller frees its own buffer after copying from it, so that memory counts as free.
    if (free_ + own_capacity >= len) break;
    if (!spares_.empty()) {  // too small for this column; a live column is worth more
      free_ += spares_.begin()->first;
      spares_.erase(spares_.begin());
    } else if (oldest_ >= 0) {
      evict(oldest_);  // its buffer may fit: look again
    } else {
      break;  // capacity_ >= 2n makes this unreachable for the solver's two columns
    }
  }
  free_ -= len;
  return {std::unique_ptr<float[]>(new float[len]), len, true};
}

float* KernelCache::request(int i, int len, int* filled) {
  Column& c = columns_[i];
  if (c.len > 0) unlink(i);
  if (len > c.len) {
    ++misses_;
    if (len > c.capacity) {
      Buffer grown = takeBuffer(len, c.capacity);
      if (c.len > 0) std::memcpy(grown.data.get(), c.data.get(), sizeof(float) * c.len);
      if (grown.fresh)
        free_ += c.capacity;  // released below
      else
        keepSpare(std::move(c.data), c.capacity);
      c.data = std::move(grown.data);
      c.capacity = grown.capacity;
    }
    *filled = c.len;
    c.len = len;
  } else {
    ++hits_;
    *filled = len;
  }
  linkNewest(i);
  return c.data.get();
}

void KernelCache::resize(int n) {
  for (int i = n; i < size(); ++i) evictColumn(i);
  for (int i = 0; i < std::min(n, size()); ++i) columns_[i].len = std::min(columns_[i].len, n);
  columns_.resize(n);
  const long long at_least = 2LL * n;  // the solver's two columns, as in the constructor
  if (capacity_ < at_least) {
    free_ += at_least - capacity_;
    capacity_ = at_least;
  }
}

void KernelCache::evictColumn(int i) {
  if (columns_[i].len > 0) evict(i);
}

void KernelCache::clear() {
  while (oldest_ >= 0) evict(oldest_);
}

float* KernelCache::cached(int i, int* len) {
  *len = columns_[i].len;
  return columns_[i].data.get();
}

void KernelCache::swapIndex(int i, int j) { swapIndices({{i, j}}); }

void KernelCache::swapIndices(const std::vector<std::pair<int, int>>& swaps) {
  for (auto [i, j] : swaps) {
    if (i == j) continue;
    const bool i_cached = columns_[i].len > 0;
    const bool j_cached = columns_[j].len > 0;
    if (i_cached) unlink(i);
    if (j_cached) unlink(j);
    std::swap(columns_[i].data, columns_[j].data);
    std::swap(columns_[i].len, columns_[j].len);
    std::swap(columns_[i].capacity, columns_[j].capacity);
    if (columns_[i].len > 0) linkNewest(i);
    if (columns_[j].len > 0) linkNewest(j);
  }
  for (int h = oldest_; h >= 0;) {
    const int next = columns_[h].next;
    Column& c = columns_[h];
    float* data = c.data.get();
    for (auto [i, j] : swaps) {
      const int lo = std::min(i, j), hi = std::max(i, j);
      if (c.len <= lo || lo == hi) continue;
      if (c.len > hi) {
        std::swap(data[lo], data[hi]);
      } else if (lo > 0) {
        c.len = lo;  // entry hi is not cached: keep the prefix (libsvm drops the whole column)
      } else {
        evict(h);
        break;
      }
    }
    h = next;
  }
}

}  // namespace svmp::svm
