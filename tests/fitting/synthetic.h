// Synthetic datasets for the fitting tests: a model evaluated at known parameters on a regular
// gonioreflectometer-like grid, plus Gaussian noise of known size.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf::test {

// Incidence 5..60 deg, reflection 5..75 deg (no duplicated direction at the normal), relative azimuth 0..180 deg (retro
// to forward).
inline std::vector<Geometry> test_grid(int n_theta_i = 5, int n_theta_r = 6, int n_phi = 5) {
  std::vector<Geometry> g;
  for (int a = 0; a < n_theta_i; ++a) {
    const double ti = n_theta_i > 1 ? 5.0 + 55.0 * a / (n_theta_i - 1) : 30.0;
    for (int b = 0; b < n_theta_r; ++b) {
      const double tr = n_theta_r > 1 ? 5.0 + 70.0 * b / (n_theta_r - 1) : 30.0;
      for (int c = 0; c < n_phi; ++c) {
        const double pr = n_phi > 1 ? 180.0 * c / (n_phi - 1) : 180.0;
        g.push_back(geometry_from_degrees(ti, 0.0, tr, pr));
      }
    }
  }
  return g;
}

// params(w) gives the parameter vector at wavelength index w. Noise: sigma = rel * f + abs.
inline SpectralDataset synthetic_dataset(const Model& model, const std::vector<Geometry>& geometries,
                                         const std::vector<double>& wavelengths,
                                         const std::function<std::vector<double>(std::size_t)>& params,
                                         double rel_noise, double abs_noise, unsigned seed, bool store_sigma = false) {
  SpectralDataset d;
  d.geometries = geometries;
  d.wavelengths = wavelengths;
  const std::size_t N = geometries.size(), M = wavelengths.size();
  d.brdf.resize(N * M);
  if (store_sigma) d.sigma.resize(N * M);
  NormalStream gauss(seed);
  for (std::size_t w = 0; w < M; ++w) {
    const std::vector<double> p = params(w);
    for (std::size_t g = 0; g < N; ++g) {
      const double f = model.evaluate(p.data(), geometries[g]);
      const double s = rel_noise * std::fabs(f) + abs_noise;
      d.brdf[g * M + w] = f + s * gauss.next();
      if (store_sigma) d.sigma[g * M + w] = s;
    }
  }
  return d;
}

}  // namespace roadbrdf::test
