#include "roadbrdf/core/huge_pages.h"

#include <cstdint>
#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace roadbrdf {

namespace {

void advise(void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // The result is deliberately ignored: EINVAL (no THP in this kernel) leaves ordinary pages.
  (void)::madvise(data, bytes, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

}  // namespace

void advise_huge_pages(const void* data, std::size_t bytes) {
  constexpr std::uintptr_t kPage = kHugePageBytes;
  if (data == nullptr || bytes < 2 * kPage) return;
  // The page boundaries are found on the address as an integer, but the advised pointer is derived
  // from `data` by an offset (pointer arithmetic keeps its provenance; an integer turned back into a
  // pointer would not).
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kPage - 1) & ~(kPage - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kPage - 1);
  if (last <= first) return;
  // madvise takes a non-const pointer but changes no byte of the range.
  auto* bytes_begin = static_cast<unsigned char*>(const_cast<void*>(data));
  advise(bytes_begin + (first - begin), last - first);
}

void reserve_on_huge_pages(std::vector<double>& v, std::size_t count) {
  v.reserve(count);
  advise_huge_pages(v.data(), v.capacity() * sizeof(double));
}

void* allocate_huge(std::size_t bytes) {
  if (bytes < kHugePageBytes) return ::operator new(bytes);
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  void* p = std::aligned_alloc(kHugePageBytes, rounded);
  if (p == nullptr) throw std::bad_alloc();
  advise(p, rounded);
  return p;
}

void deallocate_huge(void* p, std::size_t bytes) noexcept {
  if (bytes < kHugePageBytes) {
    ::operator delete(p);
  } else {
    std::free(p);
  }
}

}  // namespace roadbrdf
