// compute_albedo's first stages (report_stages.h): the parameter sets, the hemispherical integrals,
// and the sky (diffuse fraction and blue-sky).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <cmath>
#include <typeinfo>
#include <utility>

#include "roadbrdf/albedo/gradient_integrals.h"
#include "roadbrdf/albedo/report_stages.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/spectra/interpolation.h"

namespace roadbrdf::albedo::detail {

namespace {

constexpr spectra::Extrapolation kRefuse = spectra::Extrapolation::kRefuse;

// Diffuse-fraction table: CSV wavelength_nm, diffuse_fraction.
spectra::Spectrum read_diffuse_table(const std::string& path) {
  spectra::Spectrum t = read_solar_spectrum(path);  // same two-column format and checks
  for (double d : t.values()) {
    if (d > 1.0) throw FileError(path, 0, 0, "a diffuse fraction must be in [0, 1]");
  }
  return t;
}

// D = E_diffuse / E_global at one wavelength of SPECTRL2's spectra, or of their integrals for a
// model without wavelengths (trapezoid over SPECTRL2's own grid).
double spectrl2_diffuse_fraction(const Spectrl2Output& o, const ParameterSets& sets, std::size_t s) {
  if (sets.spectral) {
    const double wl = sets.wavelengths[s];
    const double dif = spectra::interpolate_linear(o.wavelengths, o.diffuse, wl, kRefuse, "SPECTRL2 (300-4000 nm)");
    const double glo = spectra::interpolate_linear(o.wavelengths, o.global, wl, kRefuse, "SPECTRL2 (300-4000 nm)");
    return glo > 0.0 ? dif / glo : 1.0;
  }
  double dif = 0.0, glo = 0.0;
  for (std::size_t k = 1; k < o.wavelengths.size(); ++k) {
    const double dl = o.wavelengths[k] - o.wavelengths[k - 1];
    dif += 0.5 * (o.diffuse[k] + o.diffuse[k - 1]) * dl;
    glo += 0.5 * (o.global[k] + o.global[k - 1]) * dl;
  }
  return dif / glo;
}

}  // namespace

ParameterSets parameter_sets(const SpectralModel& sm, const AlbedoRequest& a) {
  ParameterSets sets;
  sets.spectral = sm.is_spectral();
  if (!sets.spectral && !a.wavelengths.empty()) {
    throw FieldError("wavelengths", "needs a fit file: a model with one parameter set has no wavelength axis");
  }
  if (sets.spectral && !a.wavelengths.empty()) {
    sets.wavelengths = a.wavelengths;
    for (double l : sets.wavelengths) {
      const auto p = sm.parameters_at(l);
      sets.params.insert(sets.params.end(), p.begin(), p.end());
    }
  } else {
    if (sets.spectral) sets.wavelengths = sm.wavelengths();
    sets.params = sm.parameter_table();
  }
  sets.n_sets = sets.params.size() / sm.model().parameter_count();
  return sets;
}

SpectralIntegral black_sky_at(const Model& model, const std::vector<double>& params, std::size_t n_sets, double theta_s,
                              const SunAzimuth& azimuth, const QuadratureSettings& settings) {
  return azimuth.mean ? black_sky_azimuth_mean(model, params.data(), n_sets, theta_s, settings)
                      : black_sky(model, params.data(), n_sets, theta_s, azimuth.phi_s, settings);
}

Hemispherical hemispherical_albedos(const Model& model, const ParameterSets& sets,
                                    const std::vector<double>& zeniths_deg, const SunAzimuth& azimuth,
                                    const QuadratureSettings& settings, const HemisphericalIntegrals& integrals,
                                    const GradientPlan* plan, ProgressCounter& progress) {
  const std::size_t n_zeniths = zeniths_deg.size();
  // Value and gradient in one pass where the quadrature is this module's and no grazing cross-check
  // runs (report_stages.h).
  const bool own_quadrature = typeid(integrals) == typeid(HemisphericalIntegrals);
  auto in_one_pass = [&](std::size_t z) {
    return plan != nullptr && own_quadrature &&
           (z == n_zeniths || !grazing_check_applies(model, zeniths_deg[z] * kDegree, settings));
  };
  std::vector<SpectralIntegral> values(n_zeniths + 1);  // [z], the white-sky one last
  std::vector<std::vector<double>> gradients(n_zeniths + 1);
  // The integrals are independent: one task each (the white-sky one, the longest, first so that it
  // starts first), in the caller's arena (compute_albedo: AlbedoRequest::threads). Each integral is
  // deterministic, so the results do not depend on the number of threads.
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n_zeniths + 1, 1),
      [&](const tbb::blocked_range<std::size_t>& tasks) {
        for (std::size_t t = tasks.begin(); t != tasks.end(); ++t) {
          const std::size_t z = t == 0 ? n_zeniths : t - 1;
          const bool white = z == n_zeniths;
          const double theta_s = white ? 0.0 : zeniths_deg[z] * kDegree;
          if (in_one_pass(z)) {
            GradientIntegral g =
                white ? white_sky_gradient(model, sets.params.data(), sets.n_sets, plan->scale, plan->settings,
                                           GradientNodes::value_nodes)
                      : black_sky_gradient(model, sets.params.data(), sets.n_sets, plan->scale, theta_s, azimuth.phi_s,
                                           azimuth.mean, plan->settings, GradientNodes::value_nodes);
            values[z] = std::move(g.values);
            gradients[z] = plan->with_nans(std::move(g.gradient));
          } else if (white) {
            values[z] = integrals.white_sky(model, sets.params.data(), sets.n_sets, settings);
          } else {
            values[z] = integrals.black_sky(model, sets.params.data(), sets.n_sets, theta_s, azimuth.phi_s,
                                            azimuth.mean, settings);
          }
          progress.add();
        }
      },
      tbb::simple_partitioner());
  Hemispherical h;
  h.white = std::move(values[n_zeniths]);
  h.white_gradient = std::move(gradients[n_zeniths]);
  h.converged = h.white.converged;
  for (std::size_t z = 0; z < n_zeniths; ++z) {
    SpectralIntegral& r = values[z];
    h.converged = h.converged && r.converged;
    h.black_lobes_checked.push_back(r.lobes_checked);
    h.black.push_back(std::move(r.value));
    h.black_error.push_back(std::move(r.error));
    h.black_gradient.push_back(std::move(gradients[z]));
  }
  return h;
}

Sky sky_conditions(const ParameterSets& sets, const AlbedoRequest& a, const Hemispherical& albedos) {
  Sky sky;
  if (!a.atmosphere.empty()) sky.atmosphere = parse_spectrl2_spec(a.atmosphere);
  if (a.diffuse_fraction.empty() && !sky.atmosphere) return sky;

  // A number is a constant D; anything else names a table file.
  std::optional<double> constant;
  spectra::Spectrum table;
  if (!a.diffuse_fraction.empty()) {
    double v = 0.0;
    if (parse_finite_double(a.diffuse_fraction, v)) {
      if (!(v >= 0.0 && v <= 1.0)) throw FieldError("diffuse_fraction", "must be in [0, 1]");
      constant = v;
    } else {
      if (!sets.spectral) {
        throw FieldError("diffuse_fraction", "a table needs a fit file (a model has no wavelengths)");
      }
      table = read_diffuse_table(a.diffuse_fraction);
    }
  }
  const std::size_t n_zeniths = albedos.black.size();
  sky.diffuse.assign(n_zeniths, std::vector<double>(sets.n_sets, 0.0));
  for (std::size_t z = 0; z < n_zeniths; ++z) {
    if (sky.atmosphere) {
      Spectrl2Input in = *sky.atmosphere;
      in.zenith_deg = a.sun_zenith_deg[z];
      sky.spectra.push_back(spectrl2(in));
    }
    for (std::size_t s = 0; s < sets.n_sets; ++s) {
      if (constant) {
        sky.diffuse[z][s] = *constant;
      } else if (sky.atmosphere) {
        sky.diffuse[z][s] = spectrl2_diffuse_fraction(sky.spectra.back(), sets, s);
      } else {
        sky.diffuse[z][s] = table.value(sets.wavelengths[s], a.diffuse_fraction);
      }
    }
  }

  // Blue-sky albedo (report eq. 2.19) and its error estimate, the same combination.
  sky.blue.assign(n_zeniths, std::vector<double>(sets.n_sets));
  sky.blue_error.assign(n_zeniths, std::vector<double>(sets.n_sets));
  for (std::size_t z = 0; z < n_zeniths; ++z) {
    for (std::size_t s = 0; s < sets.n_sets; ++s) {
      const double d = sky.diffuse[z][s];
      sky.blue[z][s] = (1.0 - d) * albedos.black[z][s] + d * albedos.white.value[s];
      sky.blue_error[z][s] = (1.0 - d) * albedos.black_error[z][s] + d * albedos.white.error[s];
    }
  }
  return sky;
}

}  // namespace roadbrdf::albedo::detail

namespace roadbrdf::albedo {

SpectralIntegral HemisphericalIntegrals::black_sky(const Model& model, const double* params, std::size_t n_sets,
                                                   double theta_s, double phi_s, bool azimuth_mean,
                                                   const QuadratureSettings& settings) const {
  return azimuth_mean ? black_sky_azimuth_mean(model, params, n_sets, theta_s, settings)
                      : albedo::black_sky(model, params, n_sets, theta_s, phi_s, settings);
}

SpectralIntegral HemisphericalIntegrals::white_sky(const Model& model, const double* params, std::size_t n_sets,
                                                   const QuadratureSettings& settings) const {
  return albedo::white_sky(model, params, n_sets, settings);
}

}  // namespace roadbrdf::albedo
