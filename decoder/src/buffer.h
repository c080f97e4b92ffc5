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

namespace dbss::detail {

// Storage for large arrays: 2 MiB aligned and, on Linux, backed by
// transparent huge pages when the system allows it, so filling a fresh
// 10 MB array takes a handful of page faults instead of thousands (the
// kernel's per-fault cost was a third of a large level's decode time).
void* allocate_large(size_t bytes);  // throws std::bad_alloc
void free_large(void* p) noexcept;

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

  void resize_for_overwrite(size_t n) {
    if (n > capacity_) {
      if (n > SIZE_MAX / sizeof(T)) throw std::bad_alloc();
      free_large(data_);  // free first: peak memory stays at the new size
      data_ = nullptr;
      capacity_ = 0;
      data_ = static_cast<T*>(allocate_large(n * sizeof(T)));  // uninitialised: no zeroing
      capacity_ = n;
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
  void release() noexcept {
    free_large(data_);
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
