// Small numerical helpers usable with double and with ceres::Jet (automatic differentiation).
#pragma once

#include <cmath>
#include <numbers>

namespace roadbrdf {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kInvPi = 1.0 / std::numbers::pi;
inline constexpr double kDegree = std::numbers::pi / 180.0;

template <typename T>
inline T sqr(const T& x) {
  return x * x;
}

inline double deg_to_rad(double degrees) { return degrees * kDegree; }
inline double rad_to_deg(double radians) { return radians / kDegree; }

// Value of a (possibly automatic-differentiation) scalar, for branching.
inline double scalar_value(double x) { return x; }
template <typename Jet>
inline double scalar_value(const Jet& x) {
  return x.a;
}

// sqrt that returns 0 for tiny negative arguments produced by rounding.
template <typename T>
inline T safe_sqrt(const T& x) {
  using std::sqrt;
  return scalar_value(x) > 0.0 ? T(sqrt(x)) : T(0.0);
}

template <typename T>
inline T clamp_value(const T& x, double lo, double hi) {
  if (scalar_value(x) < lo) return T(lo);
  if (scalar_value(x) > hi) return T(hi);
  return x;
}

// Integer power by repeated squaring (works for Jets).
template <typename T>
inline T ipow(T x, int n) {
  T result(1.0);
  while (n > 0) {
    if (n & 1) result *= x;
    x *= x;
    n >>= 1;
  }
  return result;
}

}  // namespace roadbrdf
