// The one random-number family (core/random.h): the engine and its seeding against the outputs of
// the reference C implementations, and every derived draw against its distribution. The statistical
// checks use fixed seeds, so they are deterministic; their tolerances are 5 standard errors of the
// statistic under the exact distribution, so a correct generator passes them for any seed with
// probability above 0.9999, while the defects they target (bias, a wrong scale, correlation) move
// the statistic by many standard errors at these sample sizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <set>
#include <vector>

#include "roadbrdf/core/random.h"

namespace roadbrdf {
namespace {

// Outputs of the reference implementation splitmix64.c (S. Vigna, prng.di.unimi.it) for the seed
// 1477776061723855037, as published with the test suite of the Rust crate rand_xoshiro.
constexpr std::array<std::uint64_t, 10> kSplitmixReference = {
    1985237415132408290ull,  2979275885539914483ull,  13511426838097143398ull, 8488337342461049707ull,
    15141737807933549159ull, 17093170987380407015ull, 16389528042912955399ull, 13177319091862933652ull,
    10841969400225389492ull, 17094824097954834098ull};

TEST(Random, Splitmix64MatchesTheReferenceImplementation) {
  std::uint64_t state = 1477776061723855037ull;
  for (std::uint64_t expected : kSplitmixReference) EXPECT_EQ(splitmix64(state), expected);
}

TEST(Random, Xoshiro256StarStarMatchesTheReferenceImplementation) {
  // Outputs of xoshiro256starstar.c (Blackman and Vigna) from the state {1, 2, 3, 4}, as published
  // with the test suite of the Rust crate rand_xoshiro.
  Rng rng = Rng::from_state({1, 2, 3, 4});
  const std::array<std::uint64_t, 10> expected = {11520ull,
                                                  0ull,
                                                  1509978240ull,
                                                  1215971899390074240ull,
                                                  1216172134540287360ull,
                                                  607988272756665600ull,
                                                  16172922978634559625ull,
                                                  8476171486693032832ull,
                                                  10595114339597558777ull,
                                                  2904607092377533576ull};
  for (std::uint64_t e : expected) EXPECT_EQ(rng.next(), e);
}

TEST(Random, TheSeedFillsTheStateWithFourSplitmixOutputs) {
  Rng seeded(1477776061723855037ull);
  Rng explicit_state =
      Rng::from_state({kSplitmixReference[0], kSplitmixReference[1], kSplitmixReference[2], kSplitmixReference[3]});
  for (int i = 0; i < 100; ++i) ASSERT_EQ(seeded.next(), explicit_state.next()) << "output " << i;
}

TEST(Random, UniformIsTheTop53BitsTimesTwoToTheMinus53) {
  // From the reference outputs above: 11520 >> 11 = 5, then 0, then 1509978240 >> 11 = 737294.
  Rng rng = Rng::from_state({1, 2, 3, 4});
  EXPECT_EQ(rng.uniform(), 5.0 * 0x1.0p-53);
  EXPECT_EQ(rng.uniform(), 0.0);
  EXPECT_EQ(rng.uniform(), 737294.0 * 0x1.0p-53);
  // All 53 bits are used: the lowest one is set about half the time, and no value reaches 1.
  Rng r(7);
  int odd = 0;
  for (int i = 0; i < 1000; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    const double k = u * 0x1.0p53;
    ASSERT_EQ(k, std::floor(k));
    odd += std::fmod(k, 2.0) == 1.0;
  }
  EXPECT_NEAR(odd, 500, 5 * std::sqrt(1000 * 0.25));
}

TEST(Random, SameSeedSameStreamOtherSeedOtherStream) {
  Rng a(42), b(42), c(43);
  int differ = 0;
  for (int i = 0; i < 100; ++i) {
    const std::uint64_t x = a.next();
    EXPECT_EQ(x, b.next());
    differ += x != c.next();
  }
  EXPECT_EQ(differ, 100);
}

TEST(Random, UniformHasTheMomentsAndHistogramOfU01) {
  Rng rng(20180503);
  const int n = 1'000'000, bins = 100;
  std::vector<int> count(bins, 0);
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform();
    sum += u;
    sum_sq += (u - 0.5) * (u - 0.5);
    ++count[static_cast<std::size_t>(u * bins)];
  }
  // Mean 1/2 with variance 1/12; (U - 1/2)^2 has mean 1/12 and variance 1/80 - 1/144 = 1/180.
  EXPECT_NEAR(sum / n, 0.5, 5 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(sum_sq / n, 1.0 / 12.0, 5 * std::sqrt(1.0 / 180.0 / n));
  // Pearson chi-square over equal bins: 99 degrees of freedom, mean 99, standard deviation sqrt(198).
  const double expected = double(n) / bins;
  double chi2 = 0.0;
  for (int c : count) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_LT(std::fabs(chi2 - 99.0), 5 * std::sqrt(198.0));
}

TEST(Random, BelowCoversItsRangeWithoutBias) {
  Rng rng(5);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(rng.below(1), 0u);
  // Small ranges: Pearson chi-square with n - 1 degrees of freedom within 5 standard deviations.
  for (std::uint64_t range : {2u, 3u, 7u, 10u, 62u}) {
    const int draws = 200'000;
    std::vector<int> count(range, 0);
    for (int i = 0; i < draws; ++i) {
      const std::uint64_t k = rng.below(range);
      ASSERT_LT(k, range);
      ++count[k];
    }
    const double expected = double(draws) / double(range), dof = double(range - 1);
    double chi2 = 0.0;
    for (int c : count) chi2 += (c - expected) * (c - expected) / expected;
    EXPECT_LT(std::fabs(chi2 - dof), 5 * std::sqrt(2 * dof)) << "range " << range;
  }
  // A range of 3 * 2^62: a bare remainder of 64 random bits would land in [0, 2^62) with
  // probability 1/2 (those values are reached twice); without bias it is 1/3.
  const std::uint64_t range = 3ull << 62;
  const int draws = 100'000;
  int low = 0;
  for (int i = 0; i < draws; ++i) {
    const std::uint64_t k = rng.below(range);
    ASSERT_LT(k, range);
    low += k < (1ull << 62);
  }
  EXPECT_NEAR(double(low) / draws, 1.0 / 3.0, 5 * std::sqrt((1.0 / 3.0) * (2.0 / 3.0) / draws));
}

TEST(Random, NormalDeviatesHaveTheMomentsAndTailsOfTheStandardNormal) {
  NormalStream normal(1958);
  const int n = 1'000'000;
  double sum = 0.0, sum_sq = 0.0, sum_cube = 0.0, sum_fourth = 0.0, lag = 0.0, previous = 0.0;
  int within_one = 0, beyond_three = 0;
  for (int i = 0; i < n; ++i) {
    const double z = normal.next();
    ASSERT_TRUE(std::isfinite(z));
    sum += z;
    sum_sq += z * z;
    sum_cube += z * z * z;
    sum_fourth += z * z * z * z;
    lag += z * previous;
    previous = z;
    within_one += std::fabs(z) < 1.0;
    beyond_three += std::fabs(z) > 3.0;
  }
  // Standard errors from the moments of N(0, 1): Var z = 1, Var z^2 = 2, Var z^3 = 15,
  // Var z^4 = 105 - 9 = 96, and the product of successive deviates has variance 1.
  EXPECT_NEAR(sum / n, 0.0, 5 / std::sqrt(double(n)));
  EXPECT_NEAR(sum_sq / n, 1.0, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(sum_cube / n, 0.0, 5 * std::sqrt(15.0 / n));
  EXPECT_NEAR(sum_fourth / n, 3.0, 5 * std::sqrt(96.0 / n));
  EXPECT_NEAR(lag / (n - 1), 0.0, 5 / std::sqrt(double(n - 1)));
  // P(|z| < 1) = erf(1/sqrt 2) = 0.682689492..., P(|z| > 3) = erfc(3/sqrt 2) = 0.002699796...
  const double p1 = 0.682689492137086, p3 = 0.00269979606326019;
  EXPECT_NEAR(double(within_one) / n, p1, 5 * std::sqrt(p1 * (1 - p1) / n));
  EXPECT_NEAR(double(beyond_three) / n, p3, 5 * std::sqrt(p3 * (1 - p3) / n));
}

TEST(Random, ShuffleGivesEveryPermutationWithEqualFrequency) {
  Rng rng(1964);
  std::map<std::vector<int>, int> count;
  const int per_permutation = 1000, permutations = 120;  // 5! orderings of 5 elements
  for (int i = 0; i < per_permutation * permutations; ++i) {
    std::vector<int> v = {0, 1, 2, 3, 4};
    shuffle(v, rng);
    std::vector<int> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(sorted, (std::vector<int>{0, 1, 2, 3, 4}));
    ++count[v];
  }
  ASSERT_EQ(count.size(), std::size_t(permutations));
  // Pearson chi-square with 119 degrees of freedom.
  double chi2 = 0.0;
  for (const auto& [perm, c] : count) chi2 += (c - per_permutation) * double(c - per_permutation) / per_permutation;
  EXPECT_LT(std::fabs(chi2 - 119.0), 5 * std::sqrt(2 * 119.0));
}

TEST(Random, ShuffleOfAnyLengthIsAPermutation) {
  Rng rng(3);
  for (std::size_t n : {0u, 1u, 2u, 17u, 1000u}) {
    std::vector<std::size_t> v(n);
    std::iota(v.begin(), v.end(), std::size_t(0));
    shuffle(v, rng);
    std::vector<std::size_t> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i);
    if (n == 1000) {
      EXPECT_NE(v, sorted);  // an identity shuffle of 1000 elements has probability 1/1000!
    }
  }
}

TEST(Random, StreamSeedsAreDistinctAndTheirStreamsUncorrelated) {
  std::set<std::uint64_t> seeds;
  for (std::uint64_t stream = 0; stream < 64; ++stream) {
    for (std::uint64_t block = 0; block < 64; ++block) seeds.insert(stream_seed(1, stream, block));
  }
  EXPECT_EQ(seeds.size(), 64u * 64u);
  EXPECT_NE(stream_seed(1, 2, 3), stream_seed(1, 3, 2));
  EXPECT_NE(stream_seed(1, 2, 3), stream_seed(2, 2, 3));
  // Neighbouring streams: the correlation of their uniforms is within 5 standard errors of 0
  // (the product of two independent centred uniforms has variance 1/144).
  Rng a(stream_seed(1, 0, 0)), b(stream_seed(1, 1, 0)), c(stream_seed(1, 0, 1));
  const int n = 100'000;
  double ab = 0.0, ac = 0.0;
  for (int i = 0; i < n; ++i) {
    const double ua = a.uniform() - 0.5;
    ab += ua * (b.uniform() - 0.5);
    ac += ua * (c.uniform() - 0.5);
  }
  EXPECT_NEAR(ab / n, 0.0, 5 * std::sqrt(1.0 / 144.0 / n));
  EXPECT_NEAR(ac / n, 0.0, 5 * std::sqrt(1.0 / 144.0 / n));
}

}  // namespace
}  // namespace roadbrdf
