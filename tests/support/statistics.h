// Sample statistics for the tests that check a linearised uncertainty against brute-force sampling.
#pragma once

#include <cmath>
#include <vector>

namespace roadbrdf::test {

// The sample standard deviation (n - 1 in the denominator).
inline double sample_standard_deviation(const std::vector<double>& v) {
  double mean = 0.0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double sum = 0.0;
  for (double x : v) sum += (x - mean) * (x - mean);
  return std::sqrt(sum / static_cast<double>(v.size() - 1));
}

}  // namespace roadbrdf::test
