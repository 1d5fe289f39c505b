#include "roadbrdf/photometry/marking_request.h"

#include <fmt/core.h>

#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/spectra/cie.h"

namespace roadbrdf::photometry {

namespace {

using Field = RequestField<MarkingRequest>;

const Field kFields[] = {
    {"source", "SOURCE", "", "FIT.json, MIX.json, a model name (with parameters) or a measured dataset file",
     &MarkingRequest::source, FileRole::input, true},
    {"parameters", "-p,--parameter", "", "Model parameter NAME=VALUE (repeatable); defaults otherwise",
     &MarkingRequest::parameters},
    {"options", "--option", "", "Model option NAME=VALUE (repeatable)", &MarkingRequest::options},
    {"fit", "--fit", "", "Which fit of a fit file (its model) or method of a MIX.json; default: the best",
     &MarkingRequest::fit},
    {"illuminant", "--illuminant", "", "Illuminant of the photometric weighting: A (default), D65 or a lamp file",
     &MarkingRequest::illuminant, FileRole::input},
    {"wavelength", "--wavelength", "nm", "The figures at one wavelength instead of V(lambda) x illuminant",
     &MarkingRequest::wavelength},
    {"illumination_angle", "--illumination-angle", "deg", "Illumination angle above the road surface (EN 1436: 1.24)",
     &MarkingRequest::illumination_angle},
    {"observation_angle", "--observation-angle", "deg", "Observation angle above the road surface (EN 1436: 2.29)",
     &MarkingRequest::observation_angle},
    {"tolerance", "--tolerance", "deg", "Measured data: largest distance from the geometry to a measured one",
     &MarkingRequest::tolerance},
    {"pavement", "--pavement", "",
     "Pavement to compare the marking with: a CIE table (R3, R3:0.07), an r-table file, a FIT.json / MIX.json or "
     "a model name (with pavement_parameters)",
     &MarkingRequest::pavement},
    {"pavement_parameters", "--pavement-parameter", "", "Parameter NAME=VALUE of a pavement model (repeatable)",
     &MarkingRequest::pavement_parameters},
    {"pavement_fit", "--pavement-fit", "", "Which fit / method of the pavement's file; default: the best",
     &MarkingRequest::pavement_fit},
    {"headlamp", "--headlamp", "",
     "Headlamp photometry (IES, EULUMDAT) for the luminances at 30 m; without it the contrast only",
     &MarkingRequest::headlamp, FileRole::input},
    {"headlamp_down_plane", "--headlamp-down-plane", "deg",
     "C-plane of the headlamp file that points down (its gamma = 0 axis points ahead)",
     &MarkingRequest::headlamp_down_plane},
    {"installation", "--installation", "",
     "Road-lighting installation file: the contrast under its light (EN 13201-3 grid)", &MarkingRequest::installation,
     FileRole::input},
};

std::string fmt_optional(const std::optional<double>& v, int digits) {
  return v ? fmt::format("{:.{}f}", *v, digits) : "-";
}

}  // namespace

std::span<const RequestField<MarkingRequest>> MarkingRequest::fields() { return kFields; }

void MarkingRequest::validate() const {
  if (source.empty()) throw FieldError("source", "give a fit file, a MIX.json, a model name or a dataset file");
  const auto angle = [](const char* field, double value) {
    if (!(value > 0.0 && value < 90.0)) throw FieldError(field, fmt::format("must lie in (0, 90) deg, got {}", value));
  };
  angle("illumination_angle", illumination_angle);
  angle("observation_angle", observation_angle);
  if (!(tolerance > 0.0 && tolerance <= 10.0)) {
    throw FieldError("tolerance", fmt::format("must lie in (0, 10] deg, got {}", tolerance));
  }
  if (wavelength && !(std::isfinite(*wavelength) && *wavelength > 0.0)) {
    throw FieldError("wavelength", fmt::format("must be a positive wavelength [nm], got {}", *wavelength));
  }
  if (wavelength && !illuminant.empty()) {
    throw FieldError("illuminant", "applies to the photometric weighting only, not with a single `wavelength`");
  }
  const std::string kind = source_kind(source);
  if (kind != "model" && (!parameters.empty() || !options.empty())) {
    throw FieldError(parameters.empty() ? "options" : "parameters",
                     "apply to a model given by its name, not to '" + source + "'");
  }
  if (kind != "fit" && !fit.empty()) {
    throw FieldError("fit", "selects a fit of a fit file or a method of a MIX.json; '" + source + "' is not one");
  }
  if (!(headlamp_down_plane >= 0.0 && headlamp_down_plane < 360.0)) {
    throw FieldError("headlamp_down_plane", fmt::format("must lie in [0, 360) deg, got {}", headlamp_down_plane));
  }
  if (headlamp.empty() && headlamp_down_plane != kHeadlampDownPlaneDeg) {
    throw FieldError("headlamp_down_plane", "orients a `headlamp` file: give one");
  }
  if (pavement.empty()) {
    if (!pavement_parameters.empty()) throw FieldError("pavement_parameters", "apply to a `pavement`: give one");
    if (!pavement_fit.empty()) throw FieldError("pavement_fit", "selects a fit of a `pavement` file: give one");
    if (!headlamp.empty() && installation.empty()) {
      throw FieldError("headlamp",
                       "lights the marking and a pavement: give a `pavement` (or an `installation`, "
                       "whose surface is then the pavement)");
    }
  } else {
    const bool fit_file = source_kind(pavement) == "fit";
    if (!pavement_parameters.empty() && source_kind(pavement) != "model") {
      throw FieldError("pavement_parameters", "apply to a pavement model given by its name, not to '" + pavement + "'");
    }
    if (!pavement_fit.empty() && !fit_file) {
      throw FieldError("pavement_fit",
                       "selects a fit of a fit file or a method of a MIX.json; '" + pavement + "' is not one");
    }
  }
}

bool MarkingRequest::standard_geometry() const {
  return illumination_angle == kMarkingIlluminationAngleDeg && observation_angle == kMarkingObservationAngleDeg;
}

nlohmann::json MarkingResult::to_json() const {
  const auto opt = [](const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  nlohmann::json j;
  j["source"] = {{"kind", source_kind}, {"model", model.empty() ? nlohmann::json(nullptr) : nlohmann::json(model)}};
  j["geometry"] = {{"illumination_angle_deg", illumination_angle},
                   {"observation_angle_deg", observation_angle},
                   {"theta_i_deg", 90.0 - illumination_angle},
                   {"theta_r_deg", 90.0 - observation_angle},
                   {"delta_phi_deg", 0.0}};
  j["weighting"] = weighting;
  j["RL"] = opt(rl);
  j["RL_class"] = rl_class.empty() ? nlohmann::json(nullptr) : nlohmann::json(rl_class);
  j["RL_nearest_measured_deg"] = opt(rl_nearest_distance);
  j["RL_measured_points"] = opt(rl_points);
  j["Qd"] = opt(qd);
  j["Qd_error"] = opt(qd_error);
  j["Qd_class"] = qd_class.empty() ? nlohmann::json(nullptr) : nlohmann::json(qd_class);
  j["beta"] = opt(beta);
  j["beta_nearest_measured_deg"] = opt(beta_nearest_distance);
  j["units"] = {{"RL", "mcd m^-2 lx^-1"},         {"Qd", "mcd m^-2 lx^-1"},           {"Qd_error", "mcd m^-2 lx^-1"},
                {"beta", "1 (luminance factor)"}, {"RL_nearest_measured_deg", "deg"}, {"angles", "deg"}};
  j["contrast"] = contrast ? contrast->to_json() : nlohmann::json(nullptr);
  j["diagnostics"] = diagnostics.to_json();
  return j;
}

std::string MarkingResult::summary_text() const {
  std::string text = fmt::format("geometry: illumination {:.2f} deg, observation {:.2f} deg above the road\n",
                                 illumination_angle, observation_angle);
  text += fmt::format("R_L  = {} mcd m^-2 lx^-1", fmt_optional(rl, 1));
  if (!rl_class.empty()) text += "  class " + rl_class;
  if (rl_nearest_distance) text += fmt::format("  (data: nearest measured geometry {:.3f} deg)", *rl_nearest_distance);
  text += fmt::format("\nQ_d  = {} mcd m^-2 lx^-1", fmt_optional(qd, 1));
  if (qd_error) text += fmt::format(" (+- {:.3f})", *qd_error);
  if (!qd_class.empty()) text += "  class " + qd_class;
  text += fmt::format("\nbeta = {}\n", fmt_optional(beta, 4));
  if (contrast) text += contrast->summary_text();
  return text;
}

}  // namespace roadbrdf::photometry
