// A growable array of trivially copyable values that is never
// value-initialised: every decoder array is written in full before it is
// read, so zeroing it first would only cost a pass over fresh memory.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <type_traits>

namespace dbss::detail {

template <class T>
class Buffer {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  // Makes size() == n.  The contents are unspecified afterwards (old values
  // are not kept when the storage grows): callers overwrite all of it.
  void resize_for_overwrite(size_t n) {
    if (n > capacity_) {
      data_.reset();  // free first: peak memory stays at the new size
      data_.reset(new T[n]);  // default-initialised: no zeroing
      capacity_ = n;
    }
    size_ = n;
  }
  void release() {
    data_.reset();
    size_ = capacity_ = 0;
  }
  T* data() noexcept { return data_.get(); }
  const T* data() const noexcept { return data_.get(); }
  size_t size() const noexcept { return size_; }
  T& operator[](size_t i) noexcept { return data_[i]; }
  const T& operator[](size_t i) const noexcept { return data_[i]; }
  std::span<const T> span() const noexcept { return {data_.get(), size_}; }
  void swap(Buffer& o) noexcept {
    data_.swap(o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
  }

 private:
  std::unique_ptr<T[]> data_;
  size_t size_ = 0, capacity_ = 0;
};

}  // namespace dbss::detail
