// The result of `roadbrdf lighting` as JSON and as the summary the command line prints.
#include <fmt/core.h>

#include "roadbrdf/lighting/lighting_request.h"

namespace roadbrdf::lighting {

namespace {

using nlohmann::json;

json optional_number(const std::optional<double>& x) { return x ? json(*x) : json(nullptr); }

json grid_json(const LightingFigures& fig) {
  const std::size_t ny = fig.grid.y.size();
  const auto rows = [&](const std::vector<double>& values) {
    json out = json::array();
    for (std::size_t i = 0; i < fig.grid.x.size(); ++i) {
      out.push_back(std::vector<double>(values.begin() + static_cast<long>(i * ny),
                                        values.begin() + static_cast<long>((i + 1) * ny)));
    }
    return out;
  };
  json g = {{"spacing_m", fig.grid.spacing_m},
            {"step_x_m", fig.grid.step_x_m},
            {"step_y_m", fig.grid.step_y_m},
            {"x_m", fig.grid.x},
            {"y_m", fig.grid.y},
            {"E_lx", rows(fig.illuminance)}};
  json l = json::array(), lt = json::array();
  for (const ObserverFigures& o : fig.observers) {
    l.push_back(rows(o.luminance));
    if (fig.has_brdf_luminance) lt.push_back(rows(o.luminance_true_alpha));
  }
  g["L_cd_m2"] = l;
  g["L_true_alpha_cd_m2"] = fig.has_brdf_luminance ? lt : json(nullptr);
  return g;
}

}  // namespace

nlohmann::json LightingResult::to_json() const {
  const LightingFigures& f = figures;
  json j;
  j["format"] = "roadbrdf-lighting";
  j["version"] = 1;
  j["installation"] = installation.file;
  j["luminaire"] = {{"file", installation.luminaires.file},
                    {"name", luminaire_name},
                    {"arrangement", name_of(installation.luminaires.arrangement)},
                    {"flux_lm", installed_flux_lm},
                    {"power_w", power_per_luminaire_w},
                    {"maintenance_factor", f.maintenance_factor}};
  j["surface"] = {{"description", surface.description},
                  {"Q0", surface.q0},
                  {"S1", surface.road_class.empty() ? json(nullptr) : json(surface.s1)},
                  {"class", surface.road_class.empty() ? json(nullptr) : json(surface.road_class)},
                  {"has_brdf", surface.has_brdf()}};
  j["L_av"] = f.L_av;
  j["U_o"] = f.U_o;
  j["U_l"] = f.U_l;
  j["f_TI"] = f.f_TI;
  j["R_EI"] = f.R_EI;
  j["E_av"] = f.E_av;
  j["E_min"] = f.E_min;
  j["U_o_E"] = f.U_o_E;
  j["D_P"] = energy.D_P;
  j["D_E"] = energy.D_E;
  j["M_class"] = lighting_class.met.empty() ? json(nullptr) : json(lighting_class.met);
  j["next_class"] = lighting_class.next.empty() ? json(nullptr) : json(lighting_class.next);
  j["limited_by"] = lighting_class.limiting;
  j["R_EI_right"] = f.R_EI_right;
  j["R_EI_left"] = f.R_EI_left;
  j["edge_strip_width_m"] = f.edge_strip_width_m;
  json lanes = json::array();
  for (const ObserverFigures& o : f.observers) {
    lanes.push_back({{"lane", o.lane + 1},
                     {"observer_m", {o.x_m, o.y_m, kEyeHeight}},
                     {"L_av", o.L_av},
                     {"U_o", o.U_o},
                     {"U_l", o.U_l},
                     {"f_TI", o.f_TI},
                     {"f_TI_observer_x_m", o.f_TI_observer_x_m},
                     {"L_v", o.veiling_luminance}});
  }
  j["lanes"] = lanes;
  j["energy"] = {{"D_P", energy.D_P},
                 {"D_E", energy.D_E},
                 {"operating_hours", energy.operating_hours},
                 {"power_per_km_w", energy.power_per_km_w},
                 {"luminaires_per_km", energy.luminaires_per_km}};
  if (least_flux) {
    const LeastFlux& l = *least_flux;
    j["least_flux"] = {{"class", l.target},
                       {"feasible", l.feasible},
                       {"blocking", l.blocking},
                       {"dimming_factor", l.feasible ? json(l.dimming_factor) : json(nullptr)},
                       {"flux_lm", l.feasible ? json(l.flux_lm) : json(nullptr)},
                       {"power_per_km_w", l.feasible ? json(l.power_per_km_w) : json(nullptr)},
                       {"f_TI", l.dimming_factor > 0.0 ? json(l.f_TI) : json(nullptr)}};
  } else {
    j["least_flux"] = nullptr;
  }
  j["upward"] = {{"ULOR", upward.ULOR},
                 {"luminaire_flux_lm", upward.luminaire_flux_lm},
                 {"direct_upward_lm_per_km", upward.direct_upward_lm_per_km},
                 {"flux_on_carriageway_lm_per_km", upward.flux_on_carriageway_lm_per_km},
                 {"reflected_upward_lm_per_km", optional_number(upward.reflected_upward_lm_per_km)},
                 {"reflectance", optional_number(upward.reflectance)},
                 {"reflectance_error", upward.reflectance ? json(upward.reflectance_error) : json(nullptr)}};
  if (alpha_variation) {
    const AlphaVariation& a = *alpha_variation;
    j["alpha_variation"] = {{"alpha_min_deg", a.alpha_min_deg},
                            {"alpha_max_deg", a.alpha_max_deg},
                            {"L_av_true_alpha", a.L_av_true_alpha},
                            {"U_o_true_alpha", a.U_o_true_alpha},
                            {"U_l_true_alpha", a.U_l_true_alpha},
                            {"L_av_alpha_1", a.L_av_alpha_1},
                            {"L_av_difference", a.L_av_difference},
                            {"max_point_difference", a.max_point_difference},
                            {"interpolation_difference", a.interpolation_difference}};
  } else {
    j["alpha_variation"] = nullptr;
  }
  j["grid"] = grid_json(f);
  json positions = json::array();  // the luminaires around the field, for plans
  for (const PlacedLuminaire& l : luminaires_between(installation.road, installation.luminaires,
                                                     -0.25 * f.grid.spacing_m, 1.25 * f.grid.spacing_m)) {
    positions.push_back({l.x, l.y});
  }
  j["luminaires_m"] = positions;
  j["units"] = {{"L_av", "cd/m^2"},
                {"U_o", "1"},
                {"U_l", "1"},
                {"f_TI", "%"},
                {"R_EI", "1"},
                {"E_av", "lx"},
                {"E_min", "lx"},
                {"U_o_E", "1"},
                {"D_P", "W lx^-1 m^-2"},
                {"D_E", "Wh m^-2 per year"},
                {"operating_hours", "h per year"},
                {"flux", "lm"},
                {"power", "W"},
                {"lengths", "m"},
                {"angles", "deg"},
                {"Q0", "sr^-1"},
                {"differences", "relative (ratio - 1)"}};
  const json d = diagnostics.to_json();
  j["notes"] = d["notes"];
  j["warnings"] = d["warnings"];
  return j;
}

std::string LightingResult::summary_text() const {
  const LightingFigures& f = figures;
  std::string s;
  s += fmt::format("installation: {} ({}, {} lanes x {:g} m, spacing {:g} m, height {:g} m)\n", installation.file,
                   name_of(installation.luminaires.arrangement), installation.road.lanes,
                   installation.road.lane_width_m, installation.luminaires.spacing_m, installation.luminaires.height_m);
  s += fmt::format("luminaire: {} ({:g} lm, {:g} W, MF {:g})\n", luminaire_name, installed_flux_lm,
                   power_per_luminaire_w, f.maintenance_factor);
  s += fmt::format("surface: {} (Q0 {:.4f} sr^-1{})\n", surface.description, surface.q0,
                   surface.road_class.empty() ? "" : fmt::format(", S1 {:.3f}, {}", surface.s1, surface.road_class));
  s += fmt::format("grid: {} x {} points (D = {:.3g} m, d = {:.3g} m), {} observers\n", f.grid.x.size(),
                   f.grid.y.size(), f.grid.step_x_m, f.grid.step_y_m, f.observers.size());
  s += fmt::format("L_av {:.3f} cd/m^2   U_o {:.3f}   U_l {:.3f}   f_TI {:.1f} %   R_EI {:.3f}\n", f.L_av, f.U_o, f.U_l,
                   f.f_TI, f.R_EI);
  s += fmt::format("E_av {:.2f} lx   E_min {:.2f} lx   U_o_E {:.3f}\n", f.E_av, f.E_min, f.U_o_E);
  std::string limits;
  for (const std::string& c : lighting_class.limiting) limits += (limits.empty() ? "" : ", ") + c;
  if (lighting_class.met.empty()) {
    s += fmt::format("M class: none (M6 fails on {})\n", limits);
  } else if (lighting_class.next.empty()) {
    s += "M class: M1\n";
  } else {
    s += fmt::format("M class: {} ({} limited by {})\n", lighting_class.met, lighting_class.next, limits);
  }
  s += fmt::format("energy: D_P {:.4f} W lx^-1 m^-2   D_E {:.3g} Wh m^-2 per year ({:g} h)   {:.4g} kW/km\n",
                   energy.D_P, energy.D_E, energy.operating_hours, energy.power_per_km_w / 1000.0);
  if (least_flux) {
    const LeastFlux& l = *least_flux;
    std::string blocking;
    for (const std::string& c : l.blocking) blocking += (blocking.empty() ? "" : ", ") + c;
    if (l.feasible) {
      s += fmt::format("least flux for {}: {:.4g} x installed = {:.0f} lm per luminaire, {:.4g} kW/km\n", l.target,
                       l.dimming_factor, l.flux_lm, l.power_per_km_w / 1000.0);
    } else {
      s += fmt::format("least flux for {}: no flux meets it ({} fail)\n", l.target, blocking);
    }
  }
  s += fmt::format("upward: ULOR {:.4f}, direct {:.4g} lm/km, on the carriageway {:.4g} lm/km", upward.ULOR,
                   upward.direct_upward_lm_per_km, upward.flux_on_carriageway_lm_per_km);
  if (upward.reflected_upward_lm_per_km) {
    s += fmt::format(", reflected upward {:.4g} lm/km (reflectance {:.4f})\n", *upward.reflected_upward_lm_per_km,
                     *upward.reflectance);
  } else {
    s += ", reflected upward: needs a BRDF (r-table only)\n";
  }
  if (alpha_variation) {
    const AlphaVariation& a = *alpha_variation;
    s += fmt::format(
        "true observation angle ({:.2f}-{:.2f} deg): L_av {:.3f} cd/m^2 ({:+.2f}% vs the r-table), U_o {:.3f}, "
        "U_l {:.3f}; largest point difference {:.2f}%; table interpolation alone {:+.2f}%\n",
        a.alpha_min_deg, a.alpha_max_deg, a.L_av_true_alpha, 100.0 * a.L_av_difference, a.U_o_true_alpha,
        a.U_l_true_alpha, 100.0 * a.max_point_difference, 100.0 * a.interpolation_difference);
  }
  return s;
}

}  // namespace roadbrdf::lighting
