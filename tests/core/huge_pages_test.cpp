// core/huge_pages.h: the storage of the large arrays. Advice changes no value; LargeArray keeps
// every value written, copies and assigns like a std::vector, and aligns arrays of 2 MB and more
// on 2 MB (the condition for the kernel to back them with huge pages).
#include "roadbrdf/core/huge_pages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace roadbrdf {
namespace {

TEST(HugePages, LargeArrayKeepsWhatIsWritten) {
  for (const std::size_t n : {std::size_t{0}, std::size_t{10}, std::size_t{3} << 20}) {
    LargeArray<double> a;
    a.resize(n);
    for (std::size_t k = 0; k < n; ++k) a[k] = 0.5 * static_cast<double>(k);
    const LargeArray<double> copy = a;
    ASSERT_EQ(copy.size(), n);
    for (std::size_t k = 0; k < n; k += 997) EXPECT_EQ(copy[k], 0.5 * static_cast<double>(k));
    if (n * sizeof(double) >= kHugePageBytes) {
      EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.data()) % kHugePageBytes, 0u);
    }
  }
}

TEST(HugePages, AssignAndPushBackStillInitialise) {
  LargeArray<unsigned char> m;
  m.assign(std::size_t{5} << 20, 1);
  for (std::size_t k = 0; k < m.size(); k += 4093) ASSERT_EQ(m[k], 1);
  LargeArray<double> v;
  for (int k = 0; k < 1000; ++k) v.push_back(k);
  EXPECT_EQ(v[999], 999.0);
}

TEST(HugePages, AdviceChangesNoValue) {
  std::vector<double> v;
  v.reserve(std::size_t{1} << 20);  // 8 MB
  advise_huge_pages(v.data(), v.capacity() * sizeof(double));
  advise_huge_pages(nullptr, 0);
  advise_huge_pages(v.data(), 16);
  for (std::size_t k = 0; k < v.capacity(); ++k) v.push_back(static_cast<double>(k) + 0.25);
  for (std::size_t k = 0; k < v.size(); k += 1009) ASSERT_EQ(v[k], static_cast<double>(k) + 0.25);
}

}  // namespace
}  // namespace roadbrdf
