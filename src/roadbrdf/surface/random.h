// Random numbers of the virtual gonioreflectometer (render.h): xoshiro256** (Blackman & Vigna,
// "Scrambled linear pseudorandom number generators", 2018) seeded by splitmix64, written from the
// published recurrences. Every block of paths of every geometry has its own stream derived from
// (seed, geometry, block), so an estimate does not depend on which thread ran which block.
#pragma once

#include <cstdint>

namespace roadbrdf::surface {

inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    for (auto& s : s_) s = splitmix64(seed);
  }
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
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

// Seed of the stream of block `block` of geometry `stream` (splitmix64 mixing of the three numbers).
inline std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream, std::uint64_t block) {
  std::uint64_t s = seed;
  std::uint64_t a = splitmix64(s);
  s = a ^ (stream * 0xd1b54a32d192ed03ull + 0x8cb92ba72f3d8dd7ull);
  a = splitmix64(s);
  s = a ^ (block * 0xaef17502108ef2d9ull + 0x3c6ef372fe94f82bull);
  return splitmix64(s);
}

}  // namespace roadbrdf::surface
