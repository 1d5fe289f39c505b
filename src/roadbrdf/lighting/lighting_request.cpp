#include "roadbrdf/lighting/lighting_request.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/luminaire_file.h"

namespace roadbrdf::lighting {

std::span<const RequestField<LightingRequest>> LightingRequest::fields() {
  using R = LightingRequest;
  static const RequestField<R> table[] = {
      {"installation", "INSTALLATION", "", "Installation file (JSON, \"format\": \"roadbrdf-installation\")",
       &R::installation, FileRole::input, true},
      {"surface", "--surface", "",
       "Pavement replacing the installation's: a CIE table (R3, or R3:0.07 scaled to that Q0), an r-table file "
       "(.csv, .rtb, .dat) or a FIT.json / MIX.json",
       &R::surface},
      {"target_class", "--class", "", "M lighting class (M1-M6): the least flux and power per km that meet it",
       &R::target_class},
      {"operating_hours", "--operating-hours", "h", "Annual operating hours at full power, for D_E",
       &R::operating_hours},
      {"map", "--map", "", "Write the grid's illuminance and luminances as CSV", &R::map, FileRole::output},
  };
  return table;
}

void LightingRequest::validate() const {
  if (installation.empty()) throw FieldError("installation", "is required");
  if (!target_class.empty()) m_class_from_name(target_class, "target_class");
  if (!(operating_hours >= 0.0 && operating_hours <= 8784.0)) {
    throw FieldError("operating_hours", fmt::format("must lie in [0, 8784] h per year, got {:g}", operating_hours));
  }
  if (!surface.empty()) surface_from_text(surface, "surface");
}

namespace {

AlphaVariation alpha_variation(const LightingFigures& fig) {
  AlphaVariation a;
  a.alpha_min_deg = 90.0;
  bool first = true;
  double l_av_one = 0.0;
  for (const ObserverFigures& o : fig.observers) {
    double avg = 0.0, uo = 0.0, ul = 0.0, avg_one = 0.0, uo_one = 0.0, ul_one = 0.0;
    // The same statistics as the r-table figures (calculation.cpp), on the BRDF's luminances.
    const auto stats = [&](const std::vector<double>& l, double& average, double& overall, double& longitudinal) {
      double sum = 0.0, lo = l.front();
      for (double v : l) {
        sum += v;
        lo = std::min(lo, v);
      }
      average = sum / static_cast<double>(l.size());
      overall = average > 0.0 ? lo / average : 0.0;
      double cmin = 0.0, cmax = 0.0;
      for (std::size_t i = 0; i < fig.grid.x.size(); ++i) {
        const double v = l[i * fig.grid.y.size() + 3 * o.lane + 1];
        cmin = i == 0 ? v : std::min(cmin, v);
        cmax = i == 0 ? v : std::max(cmax, v);
      }
      longitudinal = cmax > 0.0 ? cmin / cmax : 0.0;
    };
    stats(o.luminance_true_alpha, avg, uo, ul);
    stats(o.luminance_alpha_1, avg_one, uo_one, ul_one);
    a.L_av_true_alpha = first ? avg : std::min(a.L_av_true_alpha, avg);
    a.U_o_true_alpha = first ? uo : std::min(a.U_o_true_alpha, uo);
    a.U_l_true_alpha = first ? ul : std::min(a.U_l_true_alpha, ul);
    l_av_one = first ? avg_one : std::min(l_av_one, avg_one);
    first = false;
    a.alpha_min_deg = std::min(a.alpha_min_deg, o.alpha_min_deg);
    a.alpha_max_deg = std::max(a.alpha_max_deg, o.alpha_max_deg);
    for (std::size_t k = 0; k < o.luminance.size(); ++k) {
      if (o.luminance[k] > 0.0) {
        a.max_point_difference =
            std::max(a.max_point_difference, std::abs(o.luminance_true_alpha[k] / o.luminance[k] - 1.0));
      }
    }
  }
  a.L_av_alpha_1 = l_av_one;
  a.L_av_difference = fig.L_av > 0.0 ? a.L_av_true_alpha / fig.L_av - 1.0 : 0.0;
  a.interpolation_difference = fig.L_av > 0.0 ? l_av_one / fig.L_av - 1.0 : 0.0;
  return a;
}

}  // namespace

LightingResult evaluate_installation(const Installation& installation, const Luminaire& luminaire,
                                     const RoadSurface& surface, const LightingOptions& options,
                                     Diagnostics diagnostics) {
  LightingResult result;
  result.installation = installation;
  result.luminaire_name = luminaire.name;
  result.surface = surface;
  const LuminaireLayout& layout = installation.luminaires;
  result.installed_flux_lm = layout.flux_lm ? *layout.flux_lm : luminaire.flux_lm;
  result.power_per_luminaire_w = layout.power_w ? *layout.power_w : luminaire.power_w;
  if (!(result.power_per_luminaire_w > 0.0)) {
    diagnostics.warn("no_power",
                     "the luminaire's power is unknown (give luminaires.power_w in the installation): "
                     "the energy figures are 0");
  }
  result.figures = compute_lighting(installation, luminaire, surface, diagnostics);
  result.lighting_class = assess_class(result.figures);
  result.energy = energy_figures(installation, result.power_per_luminaire_w, result.figures, options.operating_hours);
  if (!options.target_class.empty()) {
    const MClass& target = m_class_from_name(options.target_class, "target_class");
    result.least_flux = least_flux(result.figures, target, result.installed_flux_lm, result.energy);
  }
  result.upward = upward_light(installation, luminaire, surface, diagnostics);
  if (result.figures.has_brdf_luminance) {
    result.alpha_variation = alpha_variation(result.figures);
  } else {
    diagnostics.note("no_brdf_alpha",
                     "the surface is an r-table only: the luminance at each point's true "
                     "observation angle needs the BRDF");
  }
  result.diagnostics = std::move(diagnostics);
  return result;
}

LightingResult lighting(const LightingRequest& request) {
  request.validate();
  Installation installation = read_installation(request.installation);
  if (!request.surface.empty()) installation.surface = surface_from_text(request.surface, "surface");
  std::vector<FileArgument> inputs = {{"`installation`", request.installation},
                                      {"luminaires.file", installation.luminaires.file}};
  if (!installation.surface.path.empty()) inputs.push_back({"surface", installation.surface.path});
  check_request_files(request, inputs);
  Diagnostics diagnostics;
  const Luminaire luminaire = read_luminaire(installation.luminaires.file, diagnostics);
  const RoadSurface surface = make_surface(installation.surface, diagnostics);
  LightingOptions options;
  options.target_class = request.target_class;
  options.operating_hours = request.operating_hours;
  LightingResult result = evaluate_installation(installation, luminaire, surface, options, std::move(diagnostics));
  if (!request.map.empty()) write_lighting_map(request.map, result);
  return result;
}

void write_lighting_map(const std::string& path, const LightingResult& result) {
  const LightingFigures& fig = result.figures;
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "# roadbrdf lighting: grid of EN 13201-3 over one spacing; x along the road [m], y across from the "
         "right-hand edge [m]; E horizontal illuminance [lx]; L luminance [cd/m^2] seen by the observer of lane k "
         "(r-table method)";
  if (fig.has_brdf_luminance) out << "; L_true_alpha: from the BRDF at the true observation angle";
  out << "\nx_m,y_m,E_lx";
  for (const ObserverFigures& o : fig.observers) out << ",L_lane" << o.lane + 1 << "_cd_m2";
  if (fig.has_brdf_luminance) {
    for (const ObserverFigures& o : fig.observers) out << ",L_true_alpha_lane" << o.lane + 1 << "_cd_m2";
  }
  out << '\n';
  const std::size_t ny = fig.grid.y.size();
  for (std::size_t i = 0; i < fig.grid.x.size(); ++i) {
    for (std::size_t j = 0; j < ny; ++j) {
      const std::size_t k = i * ny + j;
      out << fmt::format("{:.6g},{:.6g},{:.6g}", fig.grid.x[i], fig.grid.y[j], fig.illuminance[k]);
      for (const ObserverFigures& o : fig.observers) out << fmt::format(",{:.6g}", o.luminance[k]);
      if (fig.has_brdf_luminance) {
        for (const ObserverFigures& o : fig.observers) out << fmt::format(",{:.6g}", o.luminance_true_alpha[k]);
      }
      out << '\n';
    }
  }
  file.commit();
}

}  // namespace roadbrdf::lighting
