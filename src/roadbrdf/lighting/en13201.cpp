#include "roadbrdf/lighting/en13201.h"

#include <algorithm>
#include <cctype>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"

namespace roadbrdf::lighting {

const std::vector<MClass>& m_classes() {
  // EN 13201-2:2015 Table 1 (M classes, dry road surface): L_av min, U_o min, U_l min, f_TI max [%],
  // R_EI min.
  static const std::vector<MClass> classes = {
      {"M1", 2.00, 0.40, 0.70, 10.0, 0.35}, {"M2", 1.50, 0.40, 0.70, 10.0, 0.35}, {"M3", 1.00, 0.40, 0.60, 15.0, 0.30},
      {"M4", 0.75, 0.40, 0.60, 15.0, 0.30}, {"M5", 0.50, 0.35, 0.40, 15.0, 0.30}, {"M6", 0.30, 0.35, 0.40, 20.0, 0.30},
  };
  return classes;
}

const MClass& m_class_from_name(const std::string& name, const std::string& field) {
  std::string upper = name;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  std::vector<std::string> names;
  for (const MClass& c : m_classes()) {
    if (c.name == upper) return c;
    names.push_back(c.name);
  }
  throw FieldError(field, "'" + name + "' is not an M lighting class (M1-M6)" + did_you_mean(upper, names));
}

double threshold_increment_at(const LightingFigures& figures, double dimming) {
  double worst = 0.0;
  for (const ObserverFigures& o : figures.observers) {
    worst = std::max(worst, threshold_increment(dimming * o.veiling_luminance, dimming * o.initial_L_av));
  }
  return worst;
}

std::vector<std::string> failed_criteria(const LightingFigures& figures, const MClass& c, double dimming) {
  std::vector<std::string> failed;
  if (dimming * figures.L_av < c.L_av) failed.emplace_back("L_av");
  if (figures.U_o < c.U_o) failed.emplace_back("U_o");
  if (figures.U_l < c.U_l) failed.emplace_back("U_l");
  if (threshold_increment_at(figures, dimming) > c.f_TI) failed.emplace_back("f_TI");
  if (figures.R_EI < c.R_EI) failed.emplace_back("R_EI");
  return failed;
}

ClassAssessment assess_class(const LightingFigures& figures) {
  ClassAssessment a;
  const std::vector<MClass>& classes = m_classes();
  for (std::size_t k = 0; k < classes.size(); ++k) {
    if (!failed_criteria(figures, classes[k]).empty()) continue;
    a.met = classes[k].name;
    if (k > 0) {
      a.next = classes[k - 1].name;
      a.limiting = failed_criteria(figures, classes[k - 1]);
    }
    return a;
  }
  a.next = classes.back().name;
  a.limiting = failed_criteria(figures, classes.back());
  return a;
}

EnergyFigures energy_figures(const Installation& installation, double power_per_luminaire_w,
                             const LightingFigures& figures, double operating_hours) {
  EnergyFigures e;
  const double s = installation.luminaires.spacing_m;
  const auto n = static_cast<double>(luminaires_per_period(installation.luminaires));
  e.luminaires_per_km = n * 1000.0 / s;
  e.power_per_luminaire_w = power_per_luminaire_w;
  e.power_per_km_w = e.luminaires_per_km * power_per_luminaire_w;
  e.area_per_period_m2 = installation.road.width_m() * s;
  e.operating_hours = operating_hours;
  const double power = n * power_per_luminaire_w;
  e.D_P = figures.E_av > 0.0 ? power / (figures.E_av * e.area_per_period_m2) : 0.0;
  e.D_E = power * operating_hours / e.area_per_period_m2;
  return e;
}

LeastFlux least_flux(const LightingFigures& figures, const MClass& target, double installed_flux_lm,
                     const EnergyFigures& energy) {
  LeastFlux f;
  f.target = target.name;
  if (figures.U_o < target.U_o) f.blocking.emplace_back("U_o");
  if (figures.U_l < target.U_l) f.blocking.emplace_back("U_l");
  if (figures.R_EI < target.R_EI) f.blocking.emplace_back("R_EI");
  if (!(figures.L_av > 0.0)) f.blocking.emplace_back("L_av");
  if (!f.blocking.empty()) return f;
  f.dimming_factor = target.L_av / figures.L_av;
  f.flux_lm = f.dimming_factor * installed_flux_lm;
  f.power_per_km_w = f.dimming_factor * energy.power_per_km_w;
  f.L_av = target.L_av;
  f.f_TI = threshold_increment_at(figures, f.dimming_factor);
  if (f.f_TI > target.f_TI) {
    // f_TI grows with the flux (as k^0.2 for L_av <= 5 cd/m^2): no more flux can bring it down.
    f.blocking.emplace_back("f_TI");
    return f;
  }
  f.feasible = true;
  return f;
}

}  // namespace roadbrdf::lighting
