// A growable array of trivially copyable values that is never
// value-initialised: every decoder array is written in full before it is
// read, so zeroing it first would only cost a pass over fresh memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

namespace dbss::detail {

// Storage for large arrays: 2 MiB aligned and, on Linux, backed by
// transparent huge pages when the system allows it, so filling a fresh
// 10 MB array takes a handful of page faults instead of thousands (the
// kernel's per-fault cost was a third of a large level's decode time).
void* allocate_large(size_t bytes);  // throws std::bad_alloc
void free_large(void* p) noexcept;

// Storage a decoder keeps from one stream for the next
// (ProgressiveDecoder::reset): decoding a file of the same shape again
// finds its arrays already mapped, so the kernel neither faults them in nor
// clears them.  A block serves a request of at least half its size only, so
// that the small arrays of coarse levels do not take the large blocks the
// finest level needs.
class BlockPool {
 public:
  BlockPool() = default;
  BlockPool(const BlockPool&) = delete;
  BlockPool& operator=(const BlockPool&) = delete;
  ~BlockPool() { clear(); }

  void put(void* p, size_t bytes) {
    if (!p) return;
    try {
      blocks_.push_back({p, bytes});
    } catch (...) {
      free_large(p);  // no room to remember it: give it back instead
    }
  }
  // The smallest block of `bytes` to 2 * `bytes`, removed from the pool; or
  // {nullptr, 0}.
  std::pair<void*, size_t> take(size_t bytes) noexcept {
    size_t best = blocks_.size();
    for (size_t i = 0; i < blocks_.size(); ++i)
      if (blocks_[i].second >= bytes && blocks_[i].second / 2 <= bytes &&
          (best == blocks_.size() || blocks_[i].second < blocks_[best].second))
        best = i;
    if (best == blocks_.size()) return {nullptr, 0};
    const auto b = blocks_[best];
    blocks_[best] = blocks_.back();
    blocks_.pop_back();
    return b;
  }
  void clear() noexcept {
    for (const auto& b : blocks_) free_large(b.first);
    blocks_.clear();
  }

 private:
  std::vector<std::pair<void*, size_t>> blocks_;
};

template <class T>
class Buffer {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  // Makes size() == n.  The contents are unspecified afterwards (old values
  // are not kept when the storage grows): callers overwrite all of it.
  Buffer() = default;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  ~Buffer() { free_large(data_); }

  // With a pool, a block kept there is used when one fits.
  void resize_for_overwrite(size_t n, BlockPool* pool = nullptr) {
    if (n > capacity_) {
      if (n > SIZE_MAX / sizeof(T)) throw std::bad_alloc();
      free_large(data_);  // free first: peak memory stays at the new size
      data_ = nullptr;
      capacity_ = 0;
      if (const auto kept = pool ? pool->take(n * sizeof(T)) : std::pair<void*, size_t>{}; kept.first) {
        data_ = static_cast<T*>(kept.first);
        capacity_ = kept.second / sizeof(T);
      } else {
        data_ = static_cast<T*>(allocate_large(n * sizeof(T)));  // uninitialised: no zeroing
        capacity_ = n;
      }
    }
    size_ = n;
  }
  // The storage as n uninitialised U (n * sizeof(U) must fit the capacity):
  // lets one large array serve as scratch before it receives its own
  // contents.  The T values end; call resize_for_overwrite (or reuse_as<T>)
  // before using the buffer as T again.
  template <class U>
  U* reuse_as(size_t n) noexcept {
    static_assert(std::is_trivially_copyable_v<U> && alignof(U) <= alignof(std::max_align_t));
    return ::new (static_cast<void*>(data_)) U[n];  // trivial U: no initialisation, no cookie
  }
  // Empties the buffer: its storage goes to `pool` if given, else back to
  // the system.
  void release(BlockPool* pool = nullptr) noexcept {
    if (pool) pool->put(data_, capacity_ * sizeof(T));
    else free_large(data_);
    data_ = nullptr;
    size_ = capacity_ = 0;
  }

  T* data() noexcept { return data_; }
  const T* data() const noexcept { return data_; }
  size_t size() const noexcept { return size_; }
  T& operator[](size_t i) noexcept { return data_[i]; }
  const T& operator[](size_t i) const noexcept { return data_[i]; }
  std::span<const T> span() const noexcept { return {data_, size_}; }
  void swap(Buffer& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
  }

 private:
  T* data_ = nullptr;
  size_t size_ = 0, capacity_ = 0;
};

}  // namespace dbss::detail
