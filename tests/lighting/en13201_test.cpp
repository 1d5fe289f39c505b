// M classes of EN 13201-2:2015 Table 1, the energy indicators of EN 13201-5 and the least flux for a
// class, on figures set by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/en13201.h"

namespace roadbrdf::lighting {
namespace {

// Figures with L_av, U_o, U_l, R_EI as given and one observer whose f_TI is `ti` (L_av <= 5).
LightingFigures figures(double l_av, double u_o, double u_l, double ti, double r_ei, double mf = 0.8) {
  LightingFigures f;
  f.L_av = l_av;
  f.U_o = u_o;
  f.U_l = u_l;
  f.R_EI = r_ei;
  f.E_av = 12.0;
  ObserverFigures o;
  o.initial_L_av = l_av / mf;
  // TI = 65 L_v / L_av^0.8  =>  L_v = TI L_av^0.8 / 65.
  o.veiling_luminance = ti * std::pow(o.initial_L_av, 0.8) / 65.0;
  f.observers.push_back(o);
  f.f_TI = ti;
  return f;
}

TEST(En13201, TheTableOfMClasses) {
  const std::vector<MClass>& c = m_classes();
  ASSERT_EQ(c.size(), 6u);
  EXPECT_EQ(c[0].name, "M1");
  EXPECT_EQ(c[0].L_av, 2.0);
  EXPECT_EQ(c[3].name, "M4");
  EXPECT_EQ(c[3].L_av, 0.75);
  EXPECT_EQ(c[3].U_o, 0.40);
  EXPECT_EQ(c[3].U_l, 0.60);
  EXPECT_EQ(c[3].f_TI, 15.0);
  EXPECT_EQ(c[3].R_EI, 0.30);
  EXPECT_EQ(c[5].f_TI, 20.0);
  EXPECT_EQ(m_class_from_name("m3", "target_class").name, "M3");
  try {
    m_class_from_name("M7", "target_class");
    FAIL();
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "target_class");
  }
}

TEST(En13201, ClassMetAndWhatLimitsIt) {
  const ClassAssessment a = assess_class(figures(0.9, 0.45, 0.65, 12.0, 0.5));
  EXPECT_EQ(a.met, "M4");
  EXPECT_EQ(a.next, "M3");
  EXPECT_EQ(a.limiting, std::vector<std::string>{"L_av"});
  const ClassAssessment b = assess_class(figures(2.5, 0.45, 0.65, 12.0, 0.5));
  EXPECT_EQ(b.met, "M3");  // U_l 0.65 < 0.70 and f_TI 12 > 10 keep it out of M2
  EXPECT_EQ(b.limiting, (std::vector<std::string>{"U_l", "f_TI"}));
  const ClassAssessment none = assess_class(figures(0.2, 0.3, 0.3, 25.0, 0.1));
  EXPECT_EQ(none.met, "");
  EXPECT_EQ(none.limiting.size(), 5u);
}

TEST(En13201, EnergyIndicators) {
  Installation inst;
  inst.road.lanes = 2;
  inst.road.lane_width_m = 3.5;
  inst.luminaires.spacing_m = 35.0;
  inst.luminaires.arrangement = Arrangement::opposite;
  const EnergyFigures e = energy_figures(inst, 60.0, figures(1.0, 0.5, 0.7, 10.0, 0.5), 4000.0);
  const double area = 7.0 * 35.0, power = 2 * 60.0;
  EXPECT_DOUBLE_EQ(e.D_P, power / (12.0 * area));
  EXPECT_DOUBLE_EQ(e.D_E, power * 4000.0 / area);
  EXPECT_DOUBLE_EQ(e.luminaires_per_km, 2000.0 / 35.0);
  EXPECT_DOUBLE_EQ(e.power_per_km_w, 120.0 * 1000.0 / 35.0);
}

TEST(En13201, LeastFluxForAClass) {
  const LightingFigures f = figures(1.2, 0.45, 0.65, 12.0, 0.5);
  EnergyFigures e;
  e.power_per_km_w = 3000.0;
  const LeastFlux l = least_flux(f, m_class_from_name("M4", "c"), 10000.0, e);
  ASSERT_TRUE(l.feasible);
  EXPECT_DOUBLE_EQ(l.dimming_factor, 0.75 / 1.2);
  EXPECT_DOUBLE_EQ(l.flux_lm, 10000.0 * 0.75 / 1.2);
  EXPECT_DOUBLE_EQ(l.power_per_km_w, 3000.0 * 0.75 / 1.2);
  // f_TI = 65 k L_v / (k L_av)^0.8 = k^0.2 f_TI.
  EXPECT_NEAR(l.f_TI, 12.0 * std::pow(0.75 / 1.2, 0.2), 1e-12);
  // U_l 0.65 is below M2's 0.70: no flux helps.
  const LeastFlux m2 = least_flux(f, m_class_from_name("M2", "c"), 10000.0, e);
  EXPECT_FALSE(m2.feasible);
  EXPECT_EQ(m2.blocking, std::vector<std::string>{"U_l"});
  // f_TI 14.5 at the installed flux: more flux for M3 (1.0 / 0.8) raises it above 15.
  const LightingFigures glaring = figures(0.8, 0.45, 0.65, 14.5, 0.5);
  const LeastFlux m3 = least_flux(glaring, m_class_from_name("M3", "c"), 10000.0, e);
  EXPECT_FALSE(m3.feasible);
  EXPECT_EQ(m3.blocking, std::vector<std::string>{"f_TI"});
  EXPECT_NEAR(m3.f_TI, 14.5 * std::pow(1.25, 0.2), 1e-12);
}

}  // namespace
}  // namespace roadbrdf::lighting
