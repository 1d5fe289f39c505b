// The outlier check of `check` (io/quality.h, "Outlier geometries"): each geometry's log spectral mean
// against a local prediction from its angular neighbours.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/io/quality.h"

namespace roadbrdf {

namespace {

double angle_between(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(dot(a, b), -1.0, 1.0)); }

// Isotropic angular coordinates of a geometry [deg]: incidence zenith, and the viewing direction
// in polar projection relative to the incidence plane (theta_r cos dphi, theta_r |sin dphi|).
std::array<double, 3> angular_coordinates(const Geometry& g) {
  const double ti = rad_to_deg(g.theta_i), tr = rad_to_deg(g.theta_r);
  const double dphi = (g.theta_i == 0.0 || g.theta_r == 0.0) ? 0.0 : g.phi_r - g.phi_i;
  return {ti, tr * std::cos(dphi), tr * std::fabs(std::sin(dphi))};
}

// Solve the small system A x = b of size q (Gaussian elimination with partial pivoting).
bool solve_small(std::vector<std::vector<double>> A, std::vector<double> b, std::vector<double>& x) {
  const std::size_t q = b.size();
  for (std::size_t c = 0; c < q; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < q; ++r) {
      if (std::fabs(A[r][c]) > std::fabs(A[p][c])) p = r;
    }
    if (std::fabs(A[p][c]) < 1e-12) return false;
    std::swap(A[p], A[c]);
    std::swap(b[p], b[c]);
    for (std::size_t r = c + 1; r < q; ++r) {
      const double f = A[r][c] / A[c][c];
      for (std::size_t k = c; k < q; ++k) A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  x.assign(q, 0.0);
  for (std::size_t c = q; c-- > 0;) {
    double v = b[c];
    for (std::size_t k = c + 1; k < q; ++k) v -= A[c][k] * x[k];
    x[c] = v / A[c][c];
  }
  return true;
}

// Per-geometry inputs of the outlier check: the log of the spectral mean (NaN unless the mean is
// positive), the isotropic angular coordinates, and whether the view lies in the specular cone.
struct OutlierInputs {
  std::vector<double> level;
  std::vector<std::array<double, 3>> coord;
  std::vector<bool> specular;
  // ln cos theta_i, ln cos theta_r, the cosines floored at cos 89.9 deg (finite at 90 deg rows).
  std::vector<double> log_cos_i, log_cos_r;
};

OutlierInputs outlier_inputs(const SpectralDataset& d, const QualityOptions& o) {
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size();
  OutlierInputs in{
      std::vector<double>(n, std::nan("")), std::vector<std::array<double, 3>>(n), std::vector<bool>(n, false), {}, {}};
  for (std::size_t g = 0; g < n; ++g) {
    in.coord[g] = angular_coordinates(d.geometries[g]);
    const double floor = std::cos(89.9 * kDegree);
    in.log_cos_i.push_back(std::log(std::max(d.geometries[g].cos_theta_i(), floor)));
    in.log_cos_r.push_back(std::log(std::max(d.geometries[g].cos_theta_r(), floor)));
    in.specular[g] =
        rad_to_deg(angle_between(d.geometries[g].wr, mirror_direction(d.geometries[g].wi))) < o.specular_cone_deg;
    double s = 0.0;
    std::size_t c = 0;
    for (std::size_t j = 0; j < m; ++j) {
      if (std::isfinite(d.brdf[g * m + j])) {
        s += d.brdf[g * m + j];
        ++c;
      }
    }
    if (c && s > 0.0) in.level[g] = std::log(s / static_cast<double>(c));
  }
  return in;
}

// The angular neighbours of geometry g (within the maximum distance, specular views left out for a
// non-specular g), nearest first in cand[0, k); returns k, 0 when fewer than two qualify.
std::size_t nearest_neighbours(const OutlierInputs& in, std::size_t g, const QualityOptions& o,
                               std::vector<std::pair<double, std::size_t>>& cand) {
  const std::size_t n = in.level.size();
  const auto& coord = in.coord;
  cand.clear();
  for (std::size_t k = 0; k < n; ++k) {
    if (k == g || !std::isfinite(in.level[k])) continue;
    if (in.specular[k] && !in.specular[g]) continue;  // a physical specular peak would bias the prediction
    const double dist =
        std::sqrt(sqr(coord[g][0] - coord[k][0]) + sqr(coord[g][1] - coord[k][1]) + sqr(coord[g][2] - coord[k][2]));
    if (dist > 1e-9 && dist <= o.neighbour_max_distance_deg) cand.emplace_back(dist, k);
  }
  if (cand.size() < 2) return 0;
  const std::size_t k = std::min(cand.size(), static_cast<std::size_t>(o.neighbours));
  std::partial_sort(cand.begin(), cand.begin() + static_cast<long>(k), cand.end());
  return k;
}

// Prediction of geometry g's log spectral mean from its k nearest neighbours: a local least-squares
// fit in the angular coordinates (offsets in units of the neighbourhood's radius, small ridge on all
// but the constant) whose constant term is the value at g, else the neighbours' median. Terms: the
// offsets and their squares, or (`minnaert`) the offsets and the offsets of ln cos theta_i and
// ln cos theta_r: Minnaert's law f ~ (cos theta_i cos theta_r)^(k - 1) (Minnaert 1941, ApJ 93:403) is
// linear in them, the form of BRDFs steepening towards grazing, whose log curves faster than any
// quadratic in the angles there.
double neighbour_prediction(const OutlierInputs& in, std::size_t g,
                            const std::vector<std::pair<double, std::size_t>>& cand, std::size_t k, bool minnaert) {
  const auto& coord = in.coord;
  // Quadratic (or Minnaert) terms when the neighbourhood supports them, else linear.
  const std::size_t terms = k >= 12 ? (minnaert ? 6 : 7) : (k >= 5 ? 4 : 0);
  if (terms > 0) {
    std::vector<std::vector<double>> A(terms, std::vector<double>(terms, 0.0));
    std::vector<double> b(terms, 0.0), x;
    const double unit = cand[k - 1].first;  // the neighbourhood's radius [deg]
    for (std::size_t q = 0; q < k; ++q) {
      const std::size_t n = cand[q].second;
      const auto& c = coord[n];
      const double u0 = (c[0] - coord[g][0]) / unit, u1 = (c[1] - coord[g][1]) / unit, u2 = (c[2] - coord[g][2]) / unit;
      const double row[7] = {1.0,
                             u0,
                             u1,
                             u2,
                             minnaert ? in.log_cos_i[n] - in.log_cos_i[g] : u0 * u0,
                             minnaert ? in.log_cos_r[n] - in.log_cos_r[g] : u1 * u1,
                             u2 * u2};
      for (std::size_t i = 0; i < terms; ++i) {
        for (std::size_t j = 0; j < terms; ++j) A[i][j] += row[i] * row[j];
        b[i] += row[i] * in.level[n];
      }
    }
    for (std::size_t i = 1; i < terms; ++i) A[i][i] += 1e-3;
    if (solve_small(A, b, x)) return x[0];
  }
  std::vector<double> vals;
  for (std::size_t q = 0; q < k; ++q) vals.push_back(in.level[cand[q].second]);
  return median_of(vals);
}

// Robust centre and spread (1.4826 MAD, floored at 0.02 in log) of some residuals.
std::pair<double, double> robust_centre_and_spread(std::vector<double> v) {
  std::vector<double> tmp = v;
  const double center = median_of(tmp);
  for (auto& x : v) x = std::fabs(x - center);
  return {center, std::max(1.4826 * median_of(v), 0.02)};
}

// Residuals far from their neighbours' residuals in units of the neighbours' robust spread (local in
// angle and scale-aware: a smooth ramp whose residuals grow where its signal falls into the noise is
// judged against its own neighbourhood, not against the quiet part of the data), and large as a ratio,
// are outliers; a bright one within the specular window is a physical peak. Fewer than 5 neighbours
// with a residual: the spread of all residuals.
void flag_outliers(const std::vector<double>& residual, const std::vector<std::vector<std::size_t>>& neighbours,
                   const OutlierInputs& in, const SpectralDataset& d, const QualityOptions& o, QualityReport& r) {
  std::vector<double> finite;
  for (double v : residual) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  if (finite.size() < 3) return;
  const auto [global_center, global_scale] = robust_centre_and_spread(finite);
  std::vector<double> local;
  for (std::size_t g = 0; g < residual.size(); ++g) {
    if (!std::isfinite(residual[g])) continue;
    local.clear();
    for (std::size_t k : neighbours[g]) {
      if (std::isfinite(residual[k])) local.push_back(residual[k]);
    }
    const auto [center, scale] =
        local.size() >= 5 ? robust_centre_and_spread(local) : std::pair<double, double>{global_center, global_scale};
    const double score = std::fabs(residual[g] - center) / scale;
    if (score > o.outlier_threshold && std::exp(std::fabs(residual[g])) > o.outlier_min_ratio) {
      const double from_mirror = rad_to_deg(angle_between(d.geometries[g].wr, mirror_direction(d.geometries[g].wi)));
      if (in.specular[g] && residual[g] > 0.0) {
        r.specular_peaks.push_back({g, std::exp(residual[g]), score, from_mirror});
      } else {
        r.outliers.push_back({g, std::exp(residual[g]), score, from_mirror});
      }
    }
  }
}

}  // namespace

void check_outliers(const SpectralDataset& d, const QualityOptions& o, QualityReport& r) {
  const OutlierInputs in = outlier_inputs(d, o);
  const std::size_t n = in.level.size();
  // Prediction of each geometry's log spectral mean from its angular neighbours: a local linear
  // fit (plane in the 3 angular coordinates, least squares with a small ridge) when there are
  // enough neighbours, else their median. A linear fit follows smooth angular gradients, also at
  // the edge of the grid where every neighbour lies on one side.
  std::vector<double> residual(n, std::nan(""));
  std::vector<std::vector<std::size_t>> neighbours(n);
  std::vector<std::pair<double, std::size_t>> cand;
  for (std::size_t g = 0; g < n; ++g) {
    if (!std::isfinite(in.level[g])) continue;
    const std::size_t k = nearest_neighbours(in, g, o, cand);
    if (k == 0) continue;
    for (std::size_t q = 0; q < k; ++q) neighbours[g].push_back(cand[q].second);
    // The residual from the quadratic fit, or from the Minnaert fit when that is closer: a value both
    // miss is an outlier. A smooth ramp steepening towards grazing is missed by the quadratic at the
    // edge of the grid (every neighbour on one side, a 1 deg series 0-89 deg: 2-3 x at 89 deg) but
    // followed by the Minnaert terms.
    const double quadratic = in.level[g] - neighbour_prediction(in, g, cand, k, false);
    const double minnaert = in.level[g] - neighbour_prediction(in, g, cand, k, true);
    residual[g] = std::fabs(minnaert) < std::fabs(quadratic) ? minnaert : quadratic;
  }
  flag_outliers(residual, neighbours, in, d, o, r);
}

}  // namespace roadbrdf
