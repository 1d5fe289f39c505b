// Solid-angle weights of the geometries (nearest-neighbour disc estimate, see fit.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "roadbrdf/core/math.h"
#include "roadbrdf/fitting/fit.h"

namespace roadbrdf {

std::vector<double> solid_angle_weights(const std::vector<Geometry>& geometries) {
  const std::size_t n = geometries.size();
  std::vector<double> w(n, 1.0);
  if (n == 0) return w;
  auto chord = [](const Vec3& a, const Vec3& b) { return length(a - b); };
  constexpr double kSame = 1e-9;
  // Distinct incidence directions.
  std::vector<Vec3> incid;
  std::vector<std::size_t> group(n);
  for (std::size_t g = 0; g < n; ++g) {
    std::size_t k = 0;
    for (; k < incid.size(); ++k) {
      if (chord(incid[k], geometries[g].wi) < kSame) break;
    }
    if (k == incid.size()) incid.push_back(geometries[g].wi);
    group[g] = k;
  }
  // Cell of a direction among a set: pi (d/2)^2 with d the nearest distinct neighbour, shared
  // between duplicates.
  auto cells = [&](const std::vector<Vec3>& dirs) {
    const std::size_t m = dirs.size();
    std::vector<double> area(m, 1.0);
    if (m < 2) return area;
    for (std::size_t a = 0; a < m; ++a) {
      double dmin = std::numeric_limits<double>::infinity();
      std::size_t dup = 1;
      for (std::size_t b = 0; b < m; ++b) {
        if (a == b) continue;
        const double d = chord(dirs[a], dirs[b]);
        if (d < kSame) {
          ++dup;
        } else {
          dmin = std::min(dmin, d);
        }
      }
      area[a] =
          std::isfinite(dmin) ? kPi * 0.25 * dmin * dmin / static_cast<double>(dup) : 1.0 / static_cast<double>(dup);
    }
    return area;
  };
  const std::vector<double> incid_area = cells(incid);
  for (std::size_t k = 0; k < incid.size(); ++k) {
    std::vector<std::size_t> members;
    std::vector<Vec3> dirs;
    for (std::size_t g = 0; g < n; ++g) {
      if (group[g] == k) {
        members.push_back(g);
        dirs.push_back(geometries[g].wr);
      }
    }
    const std::vector<double> refl_area = cells(dirs);
    for (std::size_t i = 0; i < members.size(); ++i) w[members[i]] = incid_area[k] * refl_area[i];
  }
  const double mean = std::accumulate(w.begin(), w.end(), 0.0) / static_cast<double>(n);
  if (mean > 0.0) {
    for (double& v : w) v /= mean;
  }
  return w;
}

}  // namespace roadbrdf
