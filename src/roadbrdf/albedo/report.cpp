#include "roadbrdf/albedo/report.h"

#include <fmt/core.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "roadbrdf/albedo/coverage.h"
#include "roadbrdf/albedo/report_stages.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/range.h"

namespace roadbrdf::albedo {

namespace {

nlohmann::json nullable(const std::vector<std::vector<double>>& v) {
  if (v.empty()) return nullptr;
  return v;
}

nlohmann::json nullable(const std::vector<double>& v) {
  if (v.empty()) return nullptr;
  return v;
}

// What each key holds, in the document itself (docs/albedo.md repeats it).
nlohmann::json units() {
  return {{"wavelengths", "nm"},
          {"sun_zenith_deg", "deg"},
          {"black_sky", "1 (directional-hemispherical reflectance), [sun zenith][wavelength]"},
          {"white_sky", "1 (bi-hemispherical reflectance), [wavelength]"},
          {"blue_sky", "1, (1 - D) black_sky + D white_sky, [sun zenith][wavelength]"},
          {"diffuse_fraction", "1, D = diffuse / global horizontal irradiance, [sun zenith][wavelength]"},
          {"errors", "absolute error estimates of the same quantities"},
          {"broadband", "solar-weighted values; null when they cannot be formed (one wavelength; see notes)"},
          {"coverage",
           "the fit's measured directions (deg) and the fractions (1) of the black-sky [sun zenith] "
           "and white-sky integrals outside them; null when unknown"},
          {"uncertainty",
           "standard uncertainties (1) of black_sky, white_sky and blue_sky from the parameter "
           "covariance of a fit, or of a mixture from its end-members' fits, same shapes; null when "
           "unknown (a model, a mixture fitted to measured data, wavelengths other than the fit's), null entries where "
           "the covariance is "
           "undefined; the table's "
           "last columns *_u; broadband: {independent, correlated} per value (albedo/uncertainty.h)"}};
}

nlohmann::json broadband_json(const detail::Broadband& b) {
  if (!b.formed) return nullptr;
  return {{"weighting", b.weighting},
          {"black_sky", b.black},
          {"black_sky_error", b.black_error},
          {"white_sky", b.white},
          {"white_sky_error", b.white_error},
          {"blue_sky", nullable(b.blue)},
          {"blue_sky_error", nullable(b.blue_error)},
          {"solar_fraction_outside_range", b.outside}};
}

}  // namespace

void AlbedoRequest::validate() const {
  if (!(tolerance > 0.0)) throw FieldError("tolerance", fmt::format("must be > 0, got {:g}", tolerance));
  if (!diffuse_fraction.empty() && !atmosphere.empty()) {
    throw FieldError("diffuse_fraction", "excludes atmosphere: give one of the two");
  }
  check_thread_count(threads);
  if (sun_zenith_deg.empty()) throw FieldError("sun_zenith", "no sun zenith given");
  if (sun_azimuth_deg && !std::isfinite(*sun_azimuth_deg)) throw FieldError("sun_azimuth", "expected a finite number");
  if (!wavelengths.empty()) check_range_values(wavelengths, "wavelengths", wavelength_rules());
  for (double z : sun_zenith_deg) {
    if (!(z >= 0.0 && z < 90.0)) throw FieldError("sun_zenith", fmt::format("must be in [0, 90) deg, got {:g}", z));
  }
}

nlohmann::json compute_albedo(const SpectralModel& sm, const AlbedoRequest& a) {
  return compute_albedo(sm, a, HemisphericalIntegrals{});
}

nlohmann::json compute_albedo(const SpectralModel& sm, const AlbedoRequest& a,
                              const HemisphericalIntegrals& integrals) {
  a.validate();
  const Model& model = sm.model();
  const detail::ParameterSets sets = detail::parameter_sets(sm, a);
  const std::vector<double>& zeniths = a.sun_zenith_deg;
  const bool isotropic = is_isotropic(model, sets.params.data(), sets.n_sets);
  detail::SunAzimuth azimuth;
  azimuth.mean = !isotropic && a.azimuth_mean && !a.sun_azimuth_deg;
  azimuth.phi_s = a.sun_azimuth_deg.value_or(0.0) * kDegree;
  QuadratureSettings settings;
  settings.tolerance = a.tolerance;

  std::vector<std::string> notes;
  if (!sets.spectral) {
    notes.emplace_back(
        "non-spectral model (one parameter set, no fit file): values are for its constant parameters; the broadband "
        "values equal them");
  }
  const detail::UncertaintyPlan uncertainty_plan = detail::uncertainty_plan(sm, sets, a);
  const GradientPlan* gradients = uncertainty_plan.gradients ? &*uncertainty_plan.gradients : nullptr;
  ProgressCounter progress(a.progress, zeniths.size() + 1);
  // The integral stages run their integrals in parallel in this arena (report_stages.h).
  // More threads than the machine runs at once would only make TBB warn.
  const int all_cores = tbb::info::default_concurrency();
  tbb::task_arena arena(a.threads > 0 ? std::min(a.threads, all_cores) : all_cores);
  const detail::Hemispherical albedos = arena.execute([&] {
    return detail::hemispherical_albedos(model, sets, zeniths, azimuth, settings, integrals, gradients, progress);
  });
  if (!isotropic) {
    notes.emplace_back(azimuth.mean ? "anisotropic model: black-sky averaged over the sun azimuth"
                                    : fmt::format("anisotropic model: black-sky at sun azimuth {} deg",
                                                  a.sun_azimuth_deg.value_or(0.0)));
  }
  Diagnostics diagnostics;  // the warnings; the notes stay plain text in the document
  if (!albedos.converged) {
    diagnostics.warn("not_converged", "the quadrature stopped before meeting the tolerance; see the error estimates");
  }
  const detail::Sky sky = detail::sky_conditions(sets, a, albedos);
  const detail::Broadband broadband = detail::broadband_albedos(sets, a, albedos, sky, notes);
  if (broadband.formed && broadband.outside > 0.5) {
    diagnostics.warn("partial_solar_spectrum",
                     fmt::format("the fit's wavelengths ({:g}-{:g} nm) hold only {:.0f}% of the solar energy: the "
                                 "broadband values weigh that part only",
                                 sets.wavelengths.front(), sets.wavelengths.back(), 100.0 * (1.0 - broadband.outside)));
  }
  const nlohmann::json luminous = detail::luminous_albedos(sets, a, albedos, notes);
  const nlohmann::json uncertainty = arena.execute([&] {
    return detail::albedo_uncertainty(sm, sets, a, uncertainty_plan, azimuth, albedos, sky, broadband, progress, notes);
  });
  progress.finish();

  // Non-physical values, and how much of the result the model extrapolates beyond the fit's data
  // (albedo/coverage.h; at the middle parameter set).
  flag_non_physical(zeniths, sets.wavelengths, albedos.black, albedos.white.value, diagnostics);
  nlohmann::json coverage = nullptr;  // null: no coverage known (a model, a mixture, an older fit file)
  if (sm.coverage()) {
    const std::size_t mid = sets.n_sets / 2;
    coverage = albedo_coverage(model, sets.params.data() + mid * model.parameter_count(),
                               sets.spectral ? sets.wavelengths[mid] : std::numeric_limits<double>::quiet_NaN(),
                               zeniths, *sm.coverage(), notes, diagnostics);
  }

  nlohmann::json j;
  j["model"] = model.name();
  j["spectral"] = sets.spectral;
  j["isotropic"] = isotropic;
  j["units"] = units();
  j["sun_zenith_deg"] = zeniths;
  j["wavelengths"] = sets.wavelengths;
  j["tolerance"] = a.tolerance;
  j["converged"] = albedos.converged;
  j["black_sky"] = albedos.black;
  j["black_sky_error"] = albedos.black_error;
  j["white_sky"] = albedos.white.value;
  j["white_sky_error"] = albedos.white.error;
  j["diffuse_fraction"] = nullable(sky.diffuse);
  j["blue_sky"] = nullable(sky.blue);
  j["blue_sky_error"] = nullable(sky.blue_error);
  j["broadband"] = broadband_json(broadband);
  j["luminous"] = luminous;
  j["coverage"] = coverage;
  j["uncertainty"] = uncertainty;
  j["notes"] = notes;
  j["warnings"] = diagnostics.to_json().at("warnings");
  return j;
}

}  // namespace roadbrdf::albedo
