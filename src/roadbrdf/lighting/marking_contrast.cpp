#include "roadbrdf/lighting/marking_contrast.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>

#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/calculation.h"
#include "roadbrdf/lighting/installation.h"
#include "roadbrdf/lighting/luminaire_file.h"
#include "roadbrdf/modelfile/model_source.h"
#include "roadbrdf/spectra/cie.h"

namespace roadbrdf::lighting {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

// The pavement's BRDF reduced over wavelength as the marking's figures are (the request's
// `wavelength`, or V(lambda) x its illuminant, CIE A by default).
photometry::SpectralWeighting pavement_weighting(const photometry::MarkingRequest& request, const SpectralModel& model,
                                                 Diagnostics& diagnostics) {
  photometry::SpectralWeighting w;
  if (!model.is_spectral()) return w;
  if (request.wavelength) {
    w.kind = photometry::SpectralWeighting::Kind::wavelength;
    w.wavelength_nm = *request.wavelength;
  } else if (!request.illuminant.empty()) {
    w.illuminant = photometry::illuminant_from_name(request.illuminant);
  }
  std::string note;
  w = photometry::effective_weighting(model, w, &note);
  if (!note.empty()) {
    diagnostics.note(
        "pavement_single_band",
        fmt::format("the pavement's model has a single band ({} nm): its R_L is at that wavelength", w.wavelength_nm));
  }
  return w;
}

}  // namespace

photometry::HeadlampContrast headlamp_contrast(double rl_marking, double rl_road, double illumination_angle_deg,
                                               double observation_angle_deg, const Luminaire* headlamp,
                                               double down_plane_deg) {
  if (!(rl_road > 0.0)) throw InputError("R_L of the pavement is 0 at this geometry: the contrast is undefined");
  photometry::HeadlampContrast h;
  const double epsilon = illumination_angle_deg * kDeg;
  h.headlamp_height_m = h.distance_m * std::tan(epsilon);
  h.eye_height_m = h.distance_m * std::tan(observation_angle_deg * kDeg);
  h.rl_marking = rl_marking;
  h.rl_road = rl_road;
  // L = R_L E_perp for both surfaces under the same light: E_perp cancels in the ratio.
  h.contrast = rl_marking / rl_road - 1.0;
  if (headlamp != nullptr) {
    photometry::HeadlampLight l;
    l.file = headlamp->file;
    l.c_deg = down_plane_deg;
    l.gamma_deg = illumination_angle_deg;
    l.intensity_cd = headlamp->distribution.intensity(l.c_deg, l.gamma_deg);
    l.distance_m = h.distance_m / std::cos(epsilon);
    // Inverse-square law for a point source: E_perp = I / d^2 on a plane facing the lamp; on the road
    // plane E = E_perp cos(theta_i), theta_i = 90 deg - epsilon.
    l.illuminance_perpendicular_lx = l.intensity_cd / (l.distance_m * l.distance_m);
    l.illuminance_lx = l.illuminance_perpendicular_lx * std::sin(epsilon);
    l.L_marking = rl_marking / photometry::kMillicandela * l.illuminance_perpendicular_lx;
    l.L_road = rl_road / photometry::kMillicandela * l.illuminance_perpendicular_lx;
    h.light = l;
  }
  return h;
}

photometry::InstallationContrast installation_contrast(const Installation& installation, const Luminaire& luminaire,
                                                       const RoadSurface& marking, const RoadSurface& road,
                                                       Diagnostics& diagnostics) {
  Diagnostics marking_diagnostics;
  const LightingFigures fm = compute_lighting(installation, luminaire, marking, marking_diagnostics);
  const LightingFigures fr = compute_lighting(installation, luminaire, road, diagnostics);
  for (const Diagnostic& d : marking_diagnostics.notes)
    diagnostics.note(d.kind, "marking as the surface: " + d.message);
  for (const Diagnostic& d : marking_diagnostics.warnings) {
    diagnostics.warn(d.kind, "marking as the surface: " + d.message);
  }
  photometry::InstallationContrast out;
  out.installation = installation.file;
  out.grid_points = fr.grid.size();
  out.x_m = fr.grid.x;
  out.y_m = fr.grid.y;
  const bool true_alpha = fm.has_brdf_luminance && fr.has_brdf_luminance;
  std::size_t dark_points = 0;
  for (std::size_t k = 0; k < fr.observers.size(); ++k) {
    const ObserverFigures& om = fm.observers[k];
    const ObserverFigures& orr = fr.observers[k];
    photometry::ObserverContrast o;
    o.lane = orr.lane;
    o.L_av_marking = om.L_av;
    o.L_av_road = orr.L_av;
    if (!(o.L_av_road > 0.0)) {
      throw InputError("the road's average luminance is 0 under the installation: the contrast is undefined");
    }
    o.contrast_of_averages = o.L_av_marking / o.L_av_road - 1.0;
    o.L_marking = om.luminance;
    o.L_road = orr.luminance;
    o.L_min_marking = *std::min_element(om.luminance.begin(), om.luminance.end());
    o.L_min_road = *std::min_element(orr.luminance.begin(), orr.luminance.end());
    o.contrast.assign(orr.luminance.size(), std::numeric_limits<double>::quiet_NaN());
    // The contrast at each grid point where the road is lit (a point of zero road luminance has none).
    double sum = 0.0;
    std::size_t counted = 0;
    for (std::size_t p = 0; p < orr.luminance.size(); ++p) {
      if (!(orr.luminance[p] > 0.0)) {
        ++dark_points;
        continue;
      }
      const double c = om.luminance[p] / orr.luminance[p] - 1.0;
      o.contrast[p] = c;
      o.contrast_min = counted == 0 ? c : std::min(o.contrast_min, c);
      o.contrast_max = counted == 0 ? c : std::max(o.contrast_max, c);
      sum += c;
      ++counted;
    }
    o.contrast_mean = counted > 0 ? sum / static_cast<double>(counted) : 0.0;
    if (true_alpha) {
      const double road_true = mean(orr.luminance_true_alpha);
      if (road_true > 0.0) o.contrast_of_averages_true_alpha = mean(om.luminance_true_alpha) / road_true - 1.0;
    }
    out.contrast_of_averages =
        k == 0 ? o.contrast_of_averages : std::min(out.contrast_of_averages, o.contrast_of_averages);
    out.contrast_min = k == 0 ? o.contrast_min : std::min(out.contrast_min, o.contrast_min);
    out.contrast_max = k == 0 ? o.contrast_max : std::max(out.contrast_max, o.contrast_max);
    out.observers.push_back(o);
  }
  if (dark_points > 0) {
    diagnostics.note("unlit_points",
                     fmt::format("{} grid point(s) (over the observers) where the road's luminance is 0 "
                                 "have no contrast and are left out of the grid-point figures",
                                 dark_points));
  }
  if (!true_alpha) {
    diagnostics.note("no_true_alpha_contrast",
                     "the pavement is an r-table only: the contrast at the true observation angles needs its BRDF");
  }
  return out;
}

RoadSurface pavement_surface(const photometry::MarkingRequest& request, Diagnostics& diagnostics) {
  const std::string& text = request.pavement;
  // CIE tables, r-table files and fit files as the lighting command's `surface` takes them; a name
  // that is none of these is a model.
  SurfaceSpec spec;
  bool as_surface = true;
  try {
    spec = surface_from_text(text, "pavement");
  } catch (const FieldError&) {
    as_surface = false;
  }
  if (as_surface) {
    if (!spec.path.empty() && !std::filesystem::exists(spec.path)) {
      throw FieldError("pavement", "file '" + spec.path + "' does not exist");
    }
    spec.selection = request.pavement_fit;
    return make_surface(spec, diagnostics);
  }
  if (source_kind(text) != "model") {
    throw FieldError("pavement", "'" + text +
                                     "' is measured data: fit a model to it and give the fit file, or give a CIE "
                                     "table, an r-table file, a MIX.json or a model name");
  }
  try {
    return surface_from_model(spectral_model_from_assignments(text, request.pavement_parameters, {}), text,
                              diagnostics);
  } catch (const FieldError& e) {
    throw FieldError(e.field() == "parameters" ? "pavement_parameters" : "pavement", e.detail());
  }
}

photometry::MarkingContrast marking_contrast(const photometry::MarkingRequest& request,
                                             const SpectralModel* marking_model,
                                             const photometry::MarkingResult& figures, Diagnostics& diagnostics) {
  std::optional<Installation> installation;
  if (!request.installation.empty()) installation = read_installation(request.installation);
  const RoadSurface road = request.pavement.empty() ? make_surface(installation->surface, diagnostics)
                                                    : pavement_surface(request, diagnostics);
  photometry::MarkingContrast contrast;
  contrast.pavement = road.description;

  // (a) The headlamp at 30 m: R_L of both surfaces.
  if (road.has_brdf() && figures.rl) {
    const photometry::SpectralWeighting w = pavement_weighting(request, *road.model, diagnostics);
    const Geometry retro = photometry::retroreflection_geometry(request.illumination_angle, request.observation_angle);
    const double rl_road =
        photometry::rl_from_brdf(photometry::weighted_brdf(*road.model, w, {retro})[0], request.illumination_angle);
    std::optional<Luminaire> headlamp;
    if (!request.headlamp.empty()) headlamp = read_luminaire(request.headlamp, diagnostics);
    try {
      contrast.headlamp = headlamp_contrast(*figures.rl, rl_road, request.illumination_angle, request.observation_angle,
                                            headlamp ? &*headlamp : nullptr, request.headlamp_down_plane);
    } catch (const FieldError&) {
      throw;
    } catch (const InputError& e) {
      throw FieldError("pavement", e.what());
    }
  } else if (!request.headlamp.empty()) {
    throw FieldError("headlamp", "needs the pavement's BRDF: '" + road.description +
                                     "' is an r-table, which stops at tan gamma = 12 (a headlamp 30 m away lights "
                                     "the road at tan gamma = 46): give a FIT.json, a MIX.json or a model");
  } else {
    diagnostics.note("no_headlamp_contrast",
                     "the pavement is an r-table only: the contrast under a headlamp at 30 m needs its BRDF");
  }

  // (b) The installation, once with the marking and once with the pavement as the surface.
  if (installation) {
    if (marking_model == nullptr) {
      throw FieldError("installation",
                       "needs the marking's BRDF over the whole grid: the source is measured data; fit "
                       "a model to it and give the fit file as `source`");
    }
    if (request.wavelength || !request.illuminant.empty()) {
      diagnostics.note("installation_weighting",
                       "the installation's luminances are photometric under CIE A (as `lighting` computes them): "
                       "`wavelength` and `illuminant` apply to R_L and the headlamp only");
    }
    const Luminaire luminaire = read_luminaire(installation->luminaires.file, diagnostics);
    Diagnostics marking_surface;
    const RoadSurface marking = surface_from_model(*marking_model, "marking", marking_surface);
    for (const Diagnostic& d : marking_surface.notes) diagnostics.note(d.kind, "marking's r-table: " + d.message);
    for (const Diagnostic& d : marking_surface.warnings) diagnostics.warn(d.kind, "marking's r-table: " + d.message);
    try {
      contrast.installation = installation_contrast(*installation, luminaire, marking, road, diagnostics);
    } catch (const FieldError&) {
      throw;
    } catch (const FileError&) {
      throw;
    } catch (const InputError& e) {
      throw FieldError("installation", e.what());
    }
    contrast.installation->installation = request.installation;
  }
  return contrast;
}

photometry::MarkingResult marking(const photometry::MarkingRequest& request) {
  return photometry::marking(request, marking_contrast);
}

}  // namespace roadbrdf::lighting
