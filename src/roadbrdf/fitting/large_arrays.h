// Storage of the fitter's wavelength x geometry arrays (several MB each) on transparent huge pages.
// Internal to fitting/.
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

namespace roadbrdf::fitting {

// An allocator that asks the kernel for 2 MB pages (madvise MADV_HUGEPAGE, honoured where
// transparent huge pages are in "madvise" mode, Debian's default) for arrays of 2 MB and more.
// The first touch of a 4 kB page costs a page fault: filling the 2151 x 400 arrays of a 9 MB
// dataset took ~5000 faults, a third of the whole `roadbrdf fit` command's CPU; with 2 MB pages it
// takes a few. Smaller arrays use operator new as usual.
template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>& /*other*/) {}  // NOLINT(google-explicit-constructor)

  T* allocate(std::size_t count) {
    const std::size_t bytes = count * sizeof(T);
    if (bytes < kHugePage) return static_cast<T*>(::operator new(bytes));
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (p == nullptr) throw std::bad_alloc();
    madvise(p, rounded, MADV_HUGEPAGE);  // advice only: without it the memory is still valid
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t count) {
    if (count * sizeof(T) < kHugePage) {
      ::operator delete(p);
    } else {
      std::free(p);
    }
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>& /*other*/) const {
    return true;
  }
};

template <class T>
using LargeArray = std::vector<T, HugePageAllocator<T>>;

}  // namespace roadbrdf::fitting
