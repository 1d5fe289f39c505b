// marking(): the figures of a MarkingRequest's source, a model (fit file, MIX.json, model name) or
// measured data (marking_request.h).
#include <fmt/core.h>

#include <cmath>
#include <limits>

#include "roadbrdf/core/error.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/photometry/marking_request.h"
#include "roadbrdf/spectra/cie.h"

namespace roadbrdf::photometry {

namespace {

// The request's weighting of a spectral model (as `roadbrdf rtable` reduces one), with its JSON.
SpectralWeighting model_weighting(const MarkingRequest& request, const SpectralModel& model, MarkingResult& result) {
  SpectralWeighting w;
  if (request.wavelength) {
    w.kind = SpectralWeighting::Kind::wavelength;
    w.wavelength_nm = *request.wavelength;
    result.weighting = {{"kind", "wavelength"}, {"wavelength_nm", w.wavelength_nm}};
  } else {
    if (!request.illuminant.empty()) w.illuminant = illuminant_from_name(request.illuminant);
    result.weighting = {{"kind", "photometric (V(lambda) x illuminant)"},
                        {"illuminant", request.illuminant.empty() ? "A" : request.illuminant}};
  }
  if (!model.is_spectral()) {
    result.weighting = {{"kind", "none (wavelength-independent model)"}};
    if (request.wavelength || !request.illuminant.empty()) {
      result.diagnostics.note("weighting_ignored",
                              "the model does not depend on wavelength: `wavelength` and `illuminant` do not apply");
    }
    return w;
  }
  std::string note;
  w = effective_weighting(model, w, &note);
  if (!note.empty()) {
    result.diagnostics.note("single_band", fmt::format("single-band model ({} nm): the figures are at that wavelength "
                                                       "(a photometric weighting needs a spectrum)",
                                                       w.wavelength_nm));
    result.weighting = {{"kind", "wavelength (the model's single band)"}, {"wavelength_nm", w.wavelength_nm}};
  }
  return w;
}

void from_model(const MarkingRequest& request, const SpectralModel& model, MarkingResult& result) {
  result.model = model.model().name();
  const SpectralWeighting w = model_weighting(request, model, result);
  MarkingFigures f;
  try {
    f = marking_figures(model, w, request.illumination_angle, request.observation_angle);
  } catch (const FieldError&) {
    throw;
  } catch (const InputError& e) {
    throw FieldError(request.wavelength ? "wavelength" : "source", e.what());
  }
  result.rl = f.rl;
  result.qd = f.qd;
  result.qd_error = f.qd_error;
  result.beta = f.beta;
  if (!f.qd_converged) {
    result.diagnostics.warn("not_converged", "the Q_d integral did not reach its tolerance within its budget");
  }
  if (model.coverage()) {
    const AngularCoverage& c = *model.coverage();
    if (!c.covers(retroreflection_geometry(request.illumination_angle, request.observation_angle))) {
      result.diagnostics.warn(
          "extrapolated",
          fmt::format("the fit's data reach theta_i {:.1f}-{:.1f} deg and theta_r {:.1f}-{:.1f} deg: R_L at theta_i "
                      "{:.2f} deg, theta_r {:.2f} deg is the model's extrapolation",
                      c.theta_i_min_deg, c.theta_i_max_deg, c.theta_r_min_deg, c.theta_r_max_deg,
                      90.0 - request.illumination_angle, 90.0 - request.observation_angle));
    }
  }
}

// Weights of the data's wavelengths: V(lambda) x illuminant (trapezoid, spectra/cie.h), or the two
// neighbours of one wavelength (linear interpolation), or the single band.
std::vector<double> data_weights(const MarkingRequest& request, const SpectralDataset& data, MarkingResult& result) {
  const std::vector<double>& l = data.wavelengths;
  std::vector<double> w(l.size(), 0.0);
  if (request.wavelength) {
    const double x = *request.wavelength;
    result.weighting = {{"kind", "wavelength"}, {"wavelength_nm", x}};
    for (std::size_t j = 0; j < l.size(); ++j) {
      if (l[j] == x) {
        w[j] = 1.0;
        return w;
      }
      if (j + 1 < l.size() && l[j] < x && x < l[j + 1]) {
        const double t = (x - l[j]) / (l[j + 1] - l[j]);
        w[j] = 1.0 - t;
        w[j + 1] = t;
        return w;
      }
    }
    throw FieldError("wavelength",
                     fmt::format("{} nm lies outside the data's wavelengths ({}-{} nm)", x, l.front(), l.back()));
  }
  if (l.size() == 1) {
    w[0] = 1.0;
    result.weighting = {{"kind", "wavelength (the data's single band)"}, {"wavelength_nm", l[0]}};
    result.diagnostics.note("single_band", fmt::format("the data have a single band ({} nm): the figures are at that "
                                                       "band, not weighted by V(lambda)",
                                                       l[0]));
    return w;
  }
  const spectra::Spectrum illuminant =
      request.illuminant.empty() ? illuminant_a() : illuminant_from_name(request.illuminant);
  result.weighting = {{"kind", "photometric (V(lambda) x illuminant)"},
                      {"illuminant", request.illuminant.empty() ? "A" : request.illuminant}};
  try {
    return photometric_weights(l, illuminant);
  } catch (const InputError& e) {
    throw FieldError("source", std::string(e.what()) + "; give a `wavelength`");
  }
}

void from_data(const MarkingRequest& request, MarkingResult& result) {
  DatasetReadOptions options;
  options.warn = [&result](const std::string& message) { result.diagnostics.warn("data", message); };
  const SpectralDataset data = read_dataset(request.source, options);
  const std::vector<double> weights = data_weights(request, data, result);
  const Geometry retro = retroreflection_geometry(request.illumination_angle, request.observation_angle);
  double nearest = std::numeric_limits<double>::infinity();
  const std::optional<DataValue> rl = data_value_at(data, retro, weights, request.tolerance, &nearest);
  if (!rl) {
    throw FieldError(
        "source",
        fmt::format("the data do not reach the geometry theta_i {:.2f} deg, theta_r {:.2f} deg, same azimuth: the "
                    "nearest measured geometry is {:.2f} deg away (`tolerance` {} deg). Fit a model to the data "
                    "(retro-phong for a retroreflective marking, lambert or oren-nayar for a diffuse one) and pass "
                    "the fit file as `source`",
                    90.0 - request.illumination_angle, 90.0 - request.observation_angle, nearest, request.tolerance));
  }
  result.rl = rl_from_brdf(rl->value, request.illumination_angle);
  result.rl_nearest_distance = rl->nearest_distance_deg;
  result.rl_points = rl->points;
  double beta_nearest = 0.0;
  if (const auto beta = data_value_at(data, luminance_factor_geometry(), weights, request.tolerance, &beta_nearest)) {
    result.beta = std::acos(-1.0) * beta->value;
    result.beta_nearest_distance = beta->nearest_distance_deg;
  } else {
    result.diagnostics.note(
        "beta_not_measured",
        fmt::format("the data do not reach the 45/0 geometry of beta (nearest {:.2f} deg away)", beta_nearest));
  }
  result.diagnostics.note("qd_needs_model",
                          "Q_d integrates the BRDF over every direction of incidence, which measured data do not "
                          "cover: fit a model to the data and pass the fit file as `source` for Q_d");
}

}  // namespace

MarkingResult marking(const MarkingRequest& request, const MarkingContrastFunction& contrast) {
  request.validate();
  if (request.wants_contrast() && !contrast) {
    throw FieldError(request.pavement.empty() ? "installation" : "pavement",
                     "the contrast against a pavement is computed by the lighting module (lighting::marking)");
  }
  MarkingResult result;
  result.illumination_angle = request.illumination_angle;
  result.observation_angle = request.observation_angle;
  result.source_kind = source_kind(request.source);
  std::optional<SpectralModel> model;
  if (result.source_kind == "data") {
    from_data(request, result);
  } else {
    model = result.source_kind == "fit"
                ? read_spectral_model_file(request.source, request.fit)
                : spectral_model_from_assignments(request.source, request.parameters, request.options);
    from_model(request, *model, result);
  }
  if (request.standard_geometry()) {
    if (result.rl) result.rl_class = marking_class(rl_classes(), *result.rl);
    if (result.qd) result.qd_class = marking_class(qd_classes(), *result.qd);
  } else {
    result.diagnostics.note("no_class",
                            "the EN 1436 classes apply to its geometry only (illumination 1.24 deg, "
                            "observation 2.29 deg): none is given");
  }
  if (request.wants_contrast())
    result.contrast = contrast(request, model ? &*model : nullptr, result, result.diagnostics);
  return result;
}

}  // namespace roadbrdf::photometry
