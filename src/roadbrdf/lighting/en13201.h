// What the figures of an installation mean: the M lighting class it meets (EN 13201-2:2015, Table 1,
// dry road surfaces), its energy performance indicators (EN 13201-5:2015) and the least flux that
// still meets a requested class.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/lighting/calculation.h"

namespace roadbrdf::lighting {

// An M class of EN 13201-2:2015 Table 1: minimum L_av [cd/m^2], U_o, U_l, R_EI and maximum f_TI [%].
struct MClass {
  std::string name;
  double L_av = 0.0, U_o = 0.0, U_l = 0.0, f_TI = 0.0, R_EI = 0.0;
};
// M1 to M6, from the most demanding.
const std::vector<MClass>& m_classes();
// The class named `name` (M1-M6, either letter case); throws FieldError(field, ...).
const MClass& m_class_from_name(const std::string& name, const std::string& field);

// The criteria (`L_av`, `U_o`, `U_l`, `f_TI`, `R_EI`) of `c` that figures fail when every
// luminaire's flux is multiplied by `dimming` (luminances scale with it, f_TI with L_v and L_av).
std::vector<std::string> failed_criteria(const LightingFigures& figures, const MClass& c, double dimming = 1.0);
// f_TI [%] of the installation with every flux multiplied by `dimming`.
double threshold_increment_at(const LightingFigures& figures, double dimming);

struct ClassAssessment {
  std::string met;                    // the most demanding class met ("" when none)
  std::string next;                   // the next more demanding class ("" when M1 is met)
  std::vector<std::string> limiting;  // the criteria of `next` that fail: what limits the class
};
ClassAssessment assess_class(const LightingFigures& figures);

struct EnergyFigures {
  double luminaires_per_km = 0.0;  // lighting this carriageway
  double power_per_luminaire_w = 0.0;
  double power_per_km_w = 0.0;
  double area_per_period_m2 = 0.0;  // carriageway over one spacing
  double D_P = 0.0;                 // P / sum(E_av A) [W lx^-1 m^-2]
  double D_E = 0.0;                 // P t / A [Wh m^-2 per year]
  double operating_hours = 0.0;     // t [h per year]
};
// EN 13201-5:2015: D_P = P / sum_i(E_av,i A_i) and D_E = sum_j(P_j t_j) / A over the carriageway of
// one spacing, with the maintained E_av and the power of the luminaires that light it, burning
// `operating_hours` a year at full power.
EnergyFigures energy_figures(const Installation& installation, double power_per_luminaire_w,
                             const LightingFigures& figures, double operating_hours);

struct LeastFlux {
  std::string target;                 // the requested class
  bool feasible = false;              // some flux meets it
  std::vector<std::string> blocking;  // criteria no flux can meet (U_o, U_l, R_EI, or f_TI)
  double dimming_factor = 0.0;        // least flux / installed flux (above 1: more flux is needed)
  double flux_lm = 0.0;               // per luminaire
  double power_per_km_w = 0.0;        // with the power proportional to the flux
  double L_av = 0.0, f_TI = 0.0;      // at that flux
};
// Luminances and illuminances are proportional to the flux, the uniformities and R_EI do not depend
// on it, and f_TI falls with it: the least flux meets L_av exactly, if the rest allows.
LeastFlux least_flux(const LightingFigures& figures, const MClass& target, double installed_flux_lm,
                     const EnergyFigures& energy);

}  // namespace roadbrdf::lighting
