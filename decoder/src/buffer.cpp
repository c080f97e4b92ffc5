#include "buffer.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace dbss::detail {

namespace {
constexpr size_t kHuge = size_t{2} << 20;
}

void* allocate_large(size_t bytes) {
#if defined(__EMSCRIPTEN__)
  // WebAssembly has no huge pages, and linear memory only grows: rounding
  // up to 2 MiB there would only waste it (up to 2 MiB per array).
  constexpr bool kRound = false;
#else
  constexpr bool kRound = true;
#endif
  if (!kRound || bytes < kHuge) {
    void* p = std::malloc(bytes ? bytes : 1);
    if (!p) throw std::bad_alloc();
    return p;
  }
  const size_t rounded = (bytes + kHuge - 1) / kHuge * kHuge;
  void* p = std::aligned_alloc(kHuge, rounded);
  if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(p, rounded, MADV_HUGEPAGE);  // a hint: failure only costs speed
#endif
  return p;
}

void free_large(void* p) noexcept { std::free(p); }

}  // namespace dbss::detail
