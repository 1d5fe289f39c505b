// The road-lighting calculation against closed forms: a Lambertian road (f_r = rho / pi) under
// luminaires of constant intensity, one luminaire straight above a point, the symmetries of
// symmetric arrangements, a uniform field, the fluxes onto and reflected by the carriageway, the
// upward flux of a tilted luminaire, and the threshold increment written out from its definition.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "roadbrdf/lighting/calculation.h"
#include "roadbrdf/lighting/lighting_request.h"
#include "roadbrdf/lighting/upward_light.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::lighting {
namespace {

constexpr double kPi = std::numbers::pi;

// A luminaire of intensity `candela` in every direction with gamma <= gamma_max.
Luminaire constant_luminaire(double candela, double gamma_max = 180.0) {
  Luminaire l;
  l.name = "constant";
  l.distribution.c_deg = {0.0};
  l.distribution.gamma_deg = {0.0, gamma_max};
  l.distribution.candela = {candela, candela};
  l.flux_lm = 2.0 * kPi * (1.0 - std::cos(gamma_max * kPi / 180.0)) * candela;
  l.power_w = 100.0;
  return l;
}

Installation installation(Arrangement arrangement, double spacing, double height, double overhang) {
  Installation inst;
  inst.road.lanes = 2;
  inst.road.lane_width_m = 3.5;
  inst.luminaires.arrangement = arrangement;
  inst.luminaires.spacing_m = spacing;
  inst.luminaires.height_m = height;
  inst.luminaires.overhang_m = overhang;
  inst.luminaires.maintenance_factor = 0.8;
  return inst;
}

RoadSurface lambert(double rho, Diagnostics& d) {
  const std::shared_ptr<const Model> model(make_model("lambert"));
  return surface_from_model(SpectralModel(model, std::vector<double>{rho}), "lambert", d);
}

TEST(LightingClosedForm, LambertianRoadUnderConstantIntensity) {
  const double intensity = 1000.0, h = 10.0, s = 30.0, y0 = 1.0, rho = 0.2;
  const Installation inst = installation(Arrangement::single_sided, s, h, y0);
  Diagnostics d;
  const RoadSurface surface = lambert(rho, d);
  const LightingFigures fig = compute_lighting(inst, constant_luminaire(intensity), surface, d);
  ASSERT_EQ(fig.grid.x.size(), 10u);
  ASSERT_EQ(fig.grid.y.size(), 6u);
  const std::size_t ny = fig.grid.y.size();
  double worst_table = 0.0;
  for (std::size_t i = 0; i < fig.grid.x.size(); ++i) {
    // The grid of the standard: D = S / 10, first row D / 2 after the luminaire; d = w / 3.
    const double x = (i + 0.5) * s / 10.0;
    EXPECT_NEAR(fig.grid.x[i], x, 1e-12);
    for (std::size_t j = 0; j < ny; ++j) {
      const double y = (j + 0.5) * 3.5 / 3.0;
      EXPECT_NEAR(fig.grid.y[j], y, 1e-12);
      // E = sum I cos^3(eps) / h^2 over the luminaires within 5 h along the road, times MF.
      double e = 0.0;
      for (int k = -5; k <= 5; ++k) {
        const double dx = x - k * s;
        if (std::abs(dx) > 5.0 * h) continue;
        const double d2 = dx * dx + (y - y0) * (y - y0) + h * h;
        const double cos_eps = h / std::sqrt(d2);
        e += 0.8 * intensity * std::pow(cos_eps, 3) / (h * h);
      }
      const std::size_t k = i * ny + j;
      EXPECT_NEAR(fig.illuminance[k] / e, 1.0, 1e-12);
      for (const ObserverFigures& o : fig.observers) {
        // From the BRDF, at any observation angle: L = rho E / pi.
        EXPECT_NEAR(o.luminance_true_alpha[k] / (rho * e / kPi), 1.0, 1e-12);
        EXPECT_NEAR(o.luminance_alpha_1[k] / (rho * e / kPi), 1.0, 1e-12);
        worst_table = std::max(worst_table, std::abs(o.luminance[k] / (rho * e / kPi) - 1.0));
      }
    }
  }
  // Through the r-table (rho / pi cos^3 gamma at its rows, interpolated quadratically in tan gamma):
  // the interpolation of cos^3 between rows 0.25 or 0.5 apart in tan gamma stays within 1%.
  EXPECT_LT(worst_table, 1e-2);
  EXPECT_GT(worst_table, 0.0);
}

TEST(LightingClosedForm, LuminaireStraightAboveAPoint) {
  Luminaire l = constant_luminaire(1.0);
  // An intensity that varies with gamma: only the nadir value may reach the point below.
  l.distribution.gamma_deg = {0.0, 90.0};
  l.distribution.candela = {2500.0, 0.0};
  LuminaireLayout layout;
  const InstalledPhotometry p = installed_photometry(l, layout);
  const PlacedLuminaire above{4.0, 2.0, 8.0, 0.0, true};
  EXPECT_DOUBLE_EQ(horizontal_illuminance({above}, p, 0.7, 4.0, 2.0), 0.7 * 2500.0 / 64.0);
  // The r-table at tan gamma = 0 is r(beta, 0) for every beta (a tabulated row: no interpolation).
  Diagnostics d;
  SurfaceSpec r3;
  r3.name = "R3";
  const RoadSurface surface = make_surface(r3, d);
  std::size_t missing = 0, beyond = 0;
  for (double beta : {0.0, 7.0, 90.0, 180.0}) {
    EXPECT_DOUBLE_EQ(interpolate_r(surface.table, 0.0, beta, missing, beyond), surface.table.r(0, 0));
  }
}

TEST(LightingClosedForm, OppositeArrangementIsPointSymmetric) {
  // Any distribution, even one without symmetry: turning the opposite installation by 180 deg about
  // (0, W / 2) maps it onto itself, so E(x, y) = E(S - x, W - y).
  Luminaire l;
  l.distribution.c_deg = {0, 60, 120, 180, 240, 300};
  l.distribution.gamma_deg = {0, 30, 60, 80, 90};
  for (double c : l.distribution.c_deg) {
    for (double g : l.distribution.gamma_deg) {
      l.distribution.candela.push_back(300.0 + 200.0 * std::sin(c * kPi / 180.0 + 0.3) + 3.0 * g);
    }
  }
  l.flux_lm = 5000.0;
  for (const Arrangement a : {Arrangement::opposite, Arrangement::staggered}) {
    Installation inst = installation(a, 36.0, 9.0, 0.5);  // N = 12
    inst.luminaires.tilt_deg = 10.0;
    Diagnostics d;
    SurfaceSpec r3;
    r3.name = "R3";
    const LightingFigures fig = compute_lighting(inst, l, make_surface(r3, d), d);
    const std::size_t nx = fig.grid.x.size(), ny = fig.grid.y.size();
    ASSERT_EQ(nx, 12u);
    for (std::size_t i = 0; i < nx; ++i) {
      // Staggered: the turn is about (S / 4, W / 2), x -> S / 2 - x.
      const std::size_t mirror = a == Arrangement::opposite ? nx - 1 - i : (nx / 2 - 1 - i + nx) % nx;
      for (std::size_t j = 0; j < ny; ++j) {
        EXPECT_NEAR(fig.illuminance[i * ny + j] / fig.illuminance[mirror * ny + ny - 1 - j], 1.0, 1e-12)
            << name_of(a) << " " << i << " " << j;
      }
    }
    EXPECT_NEAR(fig.R_EI_left / fig.R_EI_right, 1.0, 1e-12);
  }
}

TEST(LightingClosedForm, UniformFieldHasUniformityOne) {
  // I = I0 / cos^3(gamma) gives E = I0 / h^2 at every point from each luminaire; with S = h = 10 m
  // every point counts the same ten luminaires (within 5 h), so E is uniform and U_o = 1.
  Luminaire l;
  l.distribution.c_deg = {0.0};
  for (int k = 0; k <= 1700; ++k) {
    const double g = 0.05 * k;
    l.distribution.gamma_deg.push_back(g);
    l.distribution.candela.push_back(100.0 / std::pow(std::cos(g * kPi / 180.0), 3));
  }
  l.flux_lm = 1.0;
  const Installation inst = installation(Arrangement::single_sided, 10.0, 10.0, 0.0);
  Diagnostics d;
  const LightingFigures fig = compute_lighting(inst, l, lambert(0.3, d), d);
  // Linear interpolation of sec^3 on 0.05 deg steps is exact to 1e-4 up to gamma = 80 deg.
  EXPECT_NEAR(fig.E_av, 0.8 * 10.0 * 100.0 / 100.0, 1e-4 * fig.E_av);
  EXPECT_NEAR(fig.U_o_E, 1.0, 1e-4);
  for (const ObserverFigures& o : fig.observers) {
    double lo = o.luminance_true_alpha[0], hi = lo;
    for (double v : o.luminance_true_alpha) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_NEAR(lo / hi, 1.0, 1e-4);
  }
}

TEST(LightingClosedForm, FluxesOfAConstantIntensity) {
  const double intensity = 500.0, h = 8.0, s = 25.0, y0 = 1.5, rho = 0.15, w = 7.0;
  const Installation inst = installation(Arrangement::single_sided, s, h, y0);
  Diagnostics d;
  const RoadSurface surface = lambert(rho, d);
  const UpwardLight up = upward_light(inst, constant_luminaire(intensity), surface, d);
  // Each cell is weighted by its exact solid angle: a constant intensity integrates exactly.
  EXPECT_NEAR(up.luminaire_flux_lm / (4.0 * kPi * intensity), 1.0, 1e-12);
  EXPECT_NEAR(up.ULOR, 0.5, 1e-12);
  const double per_km = 1000.0 / s;
  EXPECT_NEAR(up.direct_upward_lm_per_km / (0.8 * 2.0 * kPi * intensity * per_km), 1.0, 1e-12);
  // On an infinitely long strip 0 <= y <= W: int int I h / d^3 dx dy = 2 I [atan((W - y0)/h) + atan(y0/h)].
  const double onto = 2.0 * intensity * (std::atan((w - y0) / h) + std::atan(y0 / h));
  EXPECT_NEAR(up.flux_on_carriageway_lm_per_km / (0.8 * onto * per_km), 1.0, 1e-9);
  ASSERT_TRUE(up.reflected_upward_lm_per_km.has_value());
  // A Lambertian surface reflects rho of it at every incidence (hemispherical quadrature to 1e-4 absolute).
  EXPECT_NEAR(*up.reflected_upward_lm_per_km / (rho * 0.8 * onto * per_km), 1.0, 1e-4 / rho);
  EXPECT_NEAR(*up.reflectance, rho, 1e-4);
}

TEST(LightingClosedForm, UpwardFluxOfATiltedLuminaire) {
  // A luminaire emitting I into its lower hemisphere only, tilted by t: the part above the road's
  // horizon is a lune of dihedral angle t, of solid angle 2 t.
  const double intensity = 800.0;
  LuminaireLayout layout;
  const Luminaire lower_half = constant_luminaire(intensity, 90.0);
  for (double tilt : {0.0, 5.0, 15.0}) {
    layout.tilt_deg = tilt;
    const InstalledPhotometry p = installed_photometry(lower_half, layout);
    const double upward = hemisphere_flux(p, PlacedLuminaire{0, 0, 10, 0, true}, true);
    EXPECT_NEAR(upward, 2.0 * tilt * kPi / 180.0 * intensity, 0.01 * 2.0 * kPi * intensity) << tilt;
  }
}

TEST(LightingClosedForm, ThresholdIncrementFromItsDefinition) {
  // Written out from CIE 140 / EN 13201-3 for a constant intensity on one row: observer at each lane
  // centre, eye 1.5 m, looking 1 deg down along the road; first position 2.75 (h - 1.5) before the
  // field, then steps D over one spacing; luminaires up to 500 m ahead, screened above 20 deg;
  // L_v = 9.86 (1 + (23/66.4)^4) sum E_eye / theta^2, TI = 65 L_v / L_av^0.8 (new installation).
  const double intensity = 2000.0, h = 10.0, s = 30.0, y0 = 0.0;
  const Installation inst = installation(Arrangement::single_sided, s, h, y0);
  Diagnostics d;
  const LightingFigures fig = compute_lighting(inst, constant_luminaire(intensity), lambert(0.2, d), d);
  const double k_age = 9.86 * (1.0 + std::pow(23.0 / 66.4, 4));
  for (const ObserverFigures& o : fig.observers) {
    double worst = 0.0;
    for (int step = 0; step < 10; ++step) {
      const double ex = -std::tan(70.0 * kPi / 180.0) * (h - 1.5) + step * 3.0;
      double lv = 0.0;
      for (int k = -2; k < 40; ++k) {
        const double dx = k * s - ex, dy = y0 - o.y_m, dz = h - 1.5;
        if (dx <= 0.0 || dx > 500.0 || dz / dx > std::tan(20.0 * kPi / 180.0)) continue;
        const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
        const double cos_theta = (dx * std::cos(kPi / 180.0) - dz * std::sin(kPi / 180.0)) / dist;
        const double theta = std::acos(cos_theta) * 180.0 / kPi;
        lv += k_age * intensity * cos_theta / (dist * dist) / (theta * theta);
      }
      worst = std::max(worst, 65.0 * lv / std::pow(o.L_av / 0.8, 0.8));
    }
    EXPECT_NEAR(o.f_TI / worst, 1.0, 1e-12);
  }
  EXPECT_NEAR(veiling_age_factor(23.0), 10.0, 0.01);  // the usual "10" of the young observer
}

}  // namespace
}  // namespace roadbrdf::lighting
