// The one family of pseudo-random numbers of the library: every random draw (the path tracer's
// paths, the noise of simulated measurements, the grains of virtual samples, multistart points,
// cross-validation folds, temporary file names) comes from here.
//
// Engine: xoshiro256** (D. Blackman and S. Vigna, "Scrambled linear pseudorandom number
// generators", ACM Trans. Math. Softw. 47(4), 2021; preprint 2018), a 256-bit linear engine with a
// nonlinear "**" scrambler, period 2^256 - 1. Its state is filled from a 64-bit seed by splitmix64
// (G. L. Steele, D. Lea and C. H. Flood, "Fast splittable pseudorandom number generators", OOPSLA
// 2014), as its authors recommend; both are written here from the published recurrences.
//
// Every transformation of the 64-bit outputs (uniform reals, bounded integers, normal deviates,
// shuffles) is written here too rather than taken from <random>, whose distributions are
// implementation-defined (libstdc++ and libc++ give different numbers for the same engine): the
// same seed gives the same draws with every compiler and standard library. The normal deviates
// also call std::log, std::sin and std::cos, which IEEE 754 does not require to be correctly
// rounded, so a different math library may change their last bits (not the stream they come from).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace roadbrdf {

// One step of splitmix64: advances `state` by the golden-ratio increment and returns the mixed
// value. Used to seed Rng and to derive stream seeds (stream_seed).
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// xoshiro256** with the draws the library needs. Cheap to construct and copy (32 bytes of state).
class Rng {
 public:
  // The state is four successive splitmix64 outputs from `seed` (never all zero: splitmix64 is a
  // bijection of its counter, so four successive outputs cannot all vanish).
  explicit Rng(std::uint64_t seed) {
    for (auto& s : s_) s = splitmix64(seed);
  }
  // An engine with an explicit state (reference tests); the state must not be all zero.
  static Rng from_state(const std::array<std::uint64_t, 4>& state) {
    Rng r(0);
    r.s_ = state;
    return r;
  }

  // The next 64 random bits.
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  // Uniform in [0, 1): the top 53 bits as a multiple of 2^-53 (every value exactly representable).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  // Uniform integer in [0, n), n >= 1, without bias: outputs below 2^64 mod n are rejected, so the
  // accepted outputs are a whole number of copies of [0, n) and their remainder modulo n is uniform
  // (the rejection method of OpenBSD's arc4random_uniform, analysed by D. Lemire, "Fast random
  // integer generation in an interval", ACM Trans. Model. Comput. Simul. 29(1), 2019). Fewer than
  // one draw in two is rejected, almost none for small n.
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    for (;;) {
      const std::uint64_t x = next();
      if (x >= threshold) return x % n;
    }
  }

  // A pair of independent standard normal deviates from two uniforms by the Box-Muller transform
  // (G. E. P. Box and M. E. Muller, Ann. Math. Statist. 29(2):610-611, 1958):
  //   r = sqrt(-2 ln u1), (r cos 2 pi u2, r sin 2 pi u2),  u1 in (0, 1], u2 in [0, 1).
  std::pair<double, double> normal_pair() {
    const double u1 = 1.0 - uniform();  // exact, in (0, 1]: the logarithm stays finite
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * 3.14159265358979323846 * u2;
    return {r * std::cos(angle), r * std::sin(angle)};
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::array<std::uint64_t, 4> s_{};
};

// Standard normal deviates one at a time: the Box-Muller pairs of an Rng, the second of each pair
// kept for the next call.
class NormalStream {
 public:
  explicit NormalStream(std::uint64_t seed) : rng_(seed) {}
  double next() {
    if (has_cached_) {
      has_cached_ = false;
      return cached_;
    }
    const auto [z0, z1] = rng_.normal_pair();
    cached_ = z1;
    has_cached_ = true;
    return z0;
  }

 private:
  Rng rng_;
  double cached_ = 0.0;
  bool has_cached_ = false;
};

// Uniform random permutation of [first, first + n) in place (Fisher-Yates, in R. Durstenfeld's
// form, Comm. ACM 7(7):420, 1964; Knuth, TAOCP vol. 2, Algorithm 3.4.2 P): element i, from the
// last down, is swapped with a uniformly chosen one of elements 0..i.
template <class RandomIt>
void shuffle(RandomIt first, std::size_t n, Rng& rng) {
  for (std::size_t i = n; i > 1; --i) {
    const std::size_t j = static_cast<std::size_t>(rng.below(i));
    using std::swap;
    swap(first[i - 1], first[j]);
  }
}

template <class Container>
void shuffle(Container& c, Rng& rng) {
  shuffle(c.begin(), c.size(), rng);
}

// Seed of sub-stream `block` of stream `stream` of the run seeded with `seed`: the three numbers
// mixed by splitmix64 (each of stream and block first spread by an odd multiplier and offset), so
// that nearby (stream, block) give unrelated engines. A computation split into independent pieces
// (the path tracer: one stream per geometry, one block per group of paths) draws each piece from
// its own Rng(stream_seed(...)), and its result does not depend on which thread ran which piece.
inline std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream, std::uint64_t block) {
  std::uint64_t s = seed;
  std::uint64_t a = splitmix64(s);
  s = a ^ (stream * 0xd1b54a32d192ed03ull + 0x8cb92ba72f3d8dd7ull);
  a = splitmix64(s);
  s = a ^ (block * 0xaef17502108ef2d9ull + 0x3c6ef372fe94f82bull);
  return splitmix64(s);
}

}  // namespace roadbrdf
