// Helpers shared by the mixing tests: in-memory end-members and formulations.
#pragma once

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/spectral_model.h"

namespace mixtest {

using namespace roadbrdf;
using namespace roadbrdf::mixing;

inline const std::vector<double>& test_wavelengths() {
  static const std::vector<double> w = {400.0, 500.0, 600.0, 700.0};
  return w;
}

// Oren-Nayar (full) with albedo a0 + a1 * (lambda - 400)/300 and a fixed sigma.
inline SpectralModel oren_nayar_spectral(double a0, double a1, double sigma) {
  std::shared_ptr<const Model> model = make_model("oren-nayar");
  std::vector<double> table;
  for (double w : test_wavelengths()) {
    table.push_back(a0 + a1 * (w - 400.0) / 300.0);
    table.push_back(sigma);
  }
  return SpectralModel(model, test_wavelengths(), table);
}

inline SpectralModel lambert_spectral(double a0, double a1) {
  std::shared_ptr<const Model> model = make_model("lambert");
  std::vector<double> table;
  for (double w : test_wavelengths()) table.push_back(a0 + a1 * (w - 400.0) / 300.0);
  return SpectralModel(model, test_wavelengths(), table);
}

// Glossy binder: Ashikhmin-Shirley with diffuse rd, specular rs and exponent n (isotropic).
inline SpectralModel glossy_spectral(double rd, double rs, double n) {
  std::shared_ptr<const Model> model = make_model("ashikhmin-shirley");
  const std::vector<double> p =
      parameters_from_assignments(model->description(), {{"rd", rd}, {"rs", rs}, {"nu", n}, {"nv", n}});
  std::vector<double> table;
  for (std::size_t w = 0; w < test_wavelengths().size(); ++w) table.insert(table.end(), p.begin(), p.end());
  return SpectralModel(model, test_wavelengths(), table);
}

// A loader that serves in-memory models by fit "path".
inline FitLoader memory_loader(std::map<std::string, SpectralModel> models) {
  auto shared = std::make_shared<std::map<std::string, SpectralModel>>(std::move(models));
  return [shared](const std::string& path, const std::string&) {
    const auto it = shared->find(path);
    if (it == shared->end()) throw InputError("no in-memory model '" + path + "'");
    return it->second;
  };
}

inline Component component(const std::string& name, ComponentKind kind, double mass, double density, double d_min,
                           double d_max, const std::string& fit) {
  Component c;
  c.name = name;
  c.kind = kind;
  c.mass_percent = mass;
  c.density = density;
  if (d_max > 0.0) {
    c.d_min = d_min;
    c.d_max = d_max;
  }
  c.fit = fit;
  c.fit_path = fit;
  return c;
}

// Binder + fines (in a mastic fit) + coarse aggregate, each with its own fit "path".
inline Formulation three_component_formulation(const std::string& binder_fit, const std::string& fines_fit,
                                               const std::string& coarse_fit, const std::string& mastic_fit) {
  Formulation f;
  f.name = "test";
  f.components.push_back(component("binder", ComponentKind::kBinder, 6.0, 1.03, 0, 0, binder_fit));
  f.components.push_back(component("fines", ComponentKind::kAggregate, 34.0, 2.65, 0.0, 2.0, fines_fit));
  f.components.push_back(component("coarse", ComponentKind::kAggregate, 60.0, 2.70, 6.0, 10.0, coarse_fit));
  MasticSpec m;
  m.name = "mastic";
  m.fit = m.fit_path = mastic_fit;
  f.mastic = m;
  return f;
}

// Geometries of a small gonioreflectometer-like grid (degrees), away from exact grazing.
inline std::vector<Geometry> test_geometries() {
  std::vector<Geometry> g;
  for (double ti : {0.0, 20.0, 40.0, 60.0, 75.0}) {
    for (double tr : {0.0, 15.0, 30.0, 45.0, 60.0, 80.0}) {
      for (double dphi : {0.0, 45.0, 90.0, 135.0, 180.0}) g.push_back(geometry_from_degrees(ti, 0.0, tr, dphi));
    }
  }
  return g;
}

// Dataset on test_geometries() x test_wavelengths() from a function f(geometry, wavelength).
template <class F>
SpectralDataset make_dataset(F&& f) {
  SpectralDataset d;
  d.geometries = test_geometries();
  d.wavelengths = test_wavelengths();
  for (const Geometry& g : d.geometries) {
    for (double w : d.wavelengths) d.brdf.push_back(f(g, w));
  }
  return d;
}

inline double value_at(const SpectralModel& m, const Geometry& g, double wavelength) {
  const std::vector<double> p = m.parameters_at(wavelength);
  return m.model().evaluate(p.data(), g);
}

// Independent white-sky albedo: midpoint rule in theta_i, theta_r and the relative azimuth,
// A = (1/pi) * 2pi * int int int f cos(ti) sin(ti) cos(tr) sin(tr) dti dtr ddphi.
template <class F>
double midpoint_white_sky_albedo(F&& f, int n_theta = 48, int n_phi = 48) {
  const double dt = 0.5 * kPi / n_theta, dp = 2.0 * kPi / n_phi;
  double sum = 0.0;
  for (int a = 0; a < n_theta; ++a) {
    const double ti = (a + 0.5) * dt;
    for (int b = 0; b < n_theta; ++b) {
      const double tr = (b + 0.5) * dt;
      const double w = std::cos(ti) * std::sin(ti) * std::cos(tr) * std::sin(tr);
      for (int c = 0; c < n_phi; ++c) {
        const double phi = (c + 0.5) * dp;
        sum += w * f(geometry_from_radians(ti, 0.0, tr, phi));
      }
    }
  }
  return 2.0 * sum * dt * dt * dp;
}

}  // namespace mixtest
