#include "roadbrdf/surface/brdf_sampler.h"

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::surface {

namespace {

// Index of the interval [cdf[k], cdf[k+1]) holding u (cdf[0] = 0, cdf[n] = 1, non-decreasing); never
// an empty interval, since u < 1 and the first value above u ends a non-empty interval.
int find_interval(const double* cdf, int n, double u) {
  const double* it = std::upper_bound(cdf + 1, cdf + n + 1, u);
  return std::min(static_cast<int>(it - cdf) - 1, n - 1);
}

// Unit vector of the azimuth of w (cos, sin); (1, 0) when w is along the normal.
void azimuth(const Vec3& w, double& c, double& s) {
  const double r = std::sqrt(w.x * w.x + w.y * w.y);
  if (r > 1e-12) {
    c = w.x / r;
    s = w.y / r;
  } else {
    c = 1.0;
    s = 0.0;
  }
}

}  // namespace

BrdfSampler::BrdfSampler(const Model& model, const std::vector<double>& parameters, std::size_t wavelength_count,
                         const BrdfSamplerSettings& settings)
    : settings_(settings) {
  const int no = settings.theta_o_bins, nu = settings.cos_theta_bins, np = settings.delta_phi_bins;
  if (no < 1 || nu < 1 || np < 1 || settings.max_wavelengths < 1)
    throw InputError("BRDF sampler: bin counts must be >= 1");
  const std::size_t pc = model.parameter_count();
  if (wavelength_count == 0 || parameters.size() != wavelength_count * pc) {
    throw InputError("BRDF sampler: parameter table size does not match the wavelength count");
  }
  // Parameter sets of at most max_wavelengths evenly spread wavelengths.
  const std::size_t n_sets =
      std::min<std::size_t>(wavelength_count, static_cast<std::size_t>(settings.max_wavelengths));
  std::vector<double> sets;
  for (std::size_t k = 0; k < n_sets; ++k) {
    const std::size_t w = n_sets == 1 ? wavelength_count / 2 : k * (wavelength_count - 1) / (n_sets - 1);
    sets.insert(sets.end(), parameters.begin() + static_cast<long>(w * pc),
                parameters.begin() + static_cast<long>((w + 1) * pc));
  }
  const std::size_t cells = static_cast<std::size_t>(nu) * np;
  row_cdf_.assign(static_cast<std::size_t>(no) * (nu + 1), 0.0);
  column_cdf_.assign(static_cast<std::size_t>(no) * nu * (np + 1), 0.0);
  cell_probability_.assign(static_cast<std::size_t>(no) * cells, 0.0);
  std::vector<Geometry> geometries(cells);
  std::vector<double> values(cells * n_sets), g(cells);
  for (int b = 0; b < no; ++b) {
    const double theta_o = (b + 0.5) * (0.5 * kPi) / no;
    for (int r = 0; r < nu; ++r) {
      const double theta = std::acos((r + 0.5) / nu);
      for (int c = 0; c < np; ++c) {
        geometries[static_cast<std::size_t>(r) * np + c] =
            geometry_from_radians(theta, (c + 0.5) * kPi / np, theta_o, 0.0);
      }
    }
    model.evaluate_batch(geometries.data(), cells, sets.data(), n_sets, values.data());
    double total = 0.0;
    for (std::size_t k = 0; k < cells; ++k) {
      double sum = 0.0;
      for (std::size_t s = 0; s < n_sets; ++s) sum += values[k * n_sets + s];
      if (!std::isfinite(sum))
        throw InputError("BRDF sampler: model '" + model.name() + "' returned a non-finite value");
      g[k] = std::max(0.0, sum) * geometries[k].wi.z;  // f cos(theta); negative values carry no probability
      total += g[k];
    }
    if (!(total > 0.0)) {  // black material: uniform table
      std::fill(g.begin(), g.end(), 1.0);
      total = static_cast<double>(cells);
    }
    double* rc = row_cdf_.data() + static_cast<std::size_t>(b) * (nu + 1);
    double* prob = cell_probability_.data() + static_cast<std::size_t>(b) * cells;
    for (int r = 0; r < nu; ++r) {
      double* cc = column_cdf_.data() + (static_cast<std::size_t>(b) * nu + r) * (np + 1);
      double row = 0.0;
      for (int c = 0; c < np; ++c) {
        const double v = g[static_cast<std::size_t>(r) * np + c];
        prob[static_cast<std::size_t>(r) * np + c] = v / total;
        row += v;
        cc[c + 1] = row;
      }
      for (int c = 1; c <= np; ++c) cc[c] = row > 0.0 ? cc[c] / row : static_cast<double>(c) / np;
      cc[np] = 1.0;
      rc[r + 1] = rc[r] + row;
    }
    for (int r = 1; r <= nu; ++r) rc[r] /= total;
    rc[nu] = 1.0;
  }
}

int BrdfSampler::theta_o_bin(const Vec3& w_o) const {
  const double theta_o = std::acos(std::clamp(w_o.z, 0.0, 1.0));
  return std::min(static_cast<int>(theta_o / (0.5 * kPi) * settings_.theta_o_bins), settings_.theta_o_bins - 1);
}

Vec3 BrdfSampler::sample(const Vec3& w_o, double u1, double u2, double u3, double& pdf) const {
  const int nu = settings_.cos_theta_bins, np = settings_.delta_phi_bins;
  const int b = theta_o_bin(w_o);
  const double* rc = row_cdf_.data() + static_cast<std::size_t>(b) * (nu + 1);
  const int r = find_interval(rc, nu, u1);
  const double tr = std::clamp((u1 - rc[r]) / (rc[r + 1] - rc[r]), 0.0, 1.0);
  const double* cc = column_cdf_.data() + (static_cast<std::size_t>(b) * nu + r) * (np + 1);
  const int c = find_interval(cc, np, u2);
  const double tc = std::clamp((u2 - cc[c]) / (cc[c + 1] - cc[c]), 0.0, 1.0);
  const double cos_theta = std::min(1.0, (r + tr) / nu);
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const double dphi = (c + tc) * kPi / np;
  const double cd = std::cos(dphi), sd = (u3 < 0.5 ? -1.0 : 1.0) * std::sin(dphi);
  double co, so;
  azimuth(w_o, co, so);
  pdf = cell_probability_[static_cast<std::size_t>(b) * nu * np + static_cast<std::size_t>(r) * np + c] * nu * np /
        (2.0 * kPi);
  return {sin_theta * (co * cd - so * sd), sin_theta * (so * cd + co * sd), cos_theta};
}

double BrdfSampler::pdf(const Vec3& w_o, const Vec3& w) const {
  if (!(w.z > 0.0)) return 0.0;
  const int nu = settings_.cos_theta_bins, np = settings_.delta_phi_bins;
  const int b = theta_o_bin(w_o);
  const int r = std::min(static_cast<int>(w.z * nu), nu - 1);
  double co, so, cw, sw;
  azimuth(w_o, co, so);
  azimuth(w, cw, sw);
  const double dphi = std::atan2(std::fabs(co * sw - so * cw), co * cw + so * sw);  // in [0, pi]
  const int c = std::min(static_cast<int>(dphi / kPi * np), np - 1);
  return cell_probability_[static_cast<std::size_t>(b) * nu * np + static_cast<std::size_t>(r) * np + c] * nu * np /
         (2.0 * kPi);
}

}  // namespace roadbrdf::surface
