// Transparent huge pages for the large arrays a command fills once (datasets, the fitter's
// wavelength x geometry arrays).
//
// The first write to each 4 kB page of a fresh allocation is a page fault: on the virtual machines
// users and CI run on, about 5 us each, so filling a 7 MB array costs 1700 faults (~9 ms, as much
// as parsing a third of its CSV). Asking the kernel to back the array with 2 MB pages (madvise
// MADV_HUGEPAGE, honoured in Debian's default THP mode "madvise") turns them into a handful. The
// advice changes no value and is ignored where unsupported (THP "never", other kernels).
#pragma once

#include <cstddef>
#include <new>
#include <utility>
#include <vector>

namespace roadbrdf {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// Advises the whole 2 MB pages inside [data, data + bytes) (buffers under 4 MB are left alone).
// For storage that must stay a std::vector<double> (SpectralDataset): call it after reserve() and
// before the first write.
void advise_huge_pages(const void* data, std::size_t bytes);
// Reserves `count` elements of the empty `v` and advises their pages, before anything is written.
void reserve_on_huge_pages(std::vector<double>& v, std::size_t count);

// Storage on 2 MB-aligned huge pages for arrays of 2 MB and more (operator new below that).
void* allocate_huge(std::size_t bytes);
void deallocate_huge(void* p, std::size_t bytes) noexcept;

// A std::vector allocator on that storage whose resize() leaves new elements default-initialised
// (uninitialised doubles): an array that the caller fills completely is not zeroed first.
template <class T>
struct HugePageAllocator {
  using value_type = T;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>& /*other*/) {}  // NOLINT(google-explicit-constructor)

  T* allocate(std::size_t count) { return static_cast<T*>(allocate_huge(count * sizeof(T))); }
  void deallocate(T* p, std::size_t count) noexcept { deallocate_huge(p, count * sizeof(T)); }

  // Default-initialisation for resize(n); assign(n, v) and push_back still construct from values.
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>& /*other*/) const {
    return true;
  }
};

// An array a command fills completely after resize() (its elements start uninitialised).
template <class T>
using LargeArray = std::vector<T, HugePageAllocator<T>>;

}  // namespace roadbrdf
