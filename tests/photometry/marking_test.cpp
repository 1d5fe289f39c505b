// Road-marking photometry (photometry/marking.h, marking_request.h): closed forms of a Lambertian
// marking, Q_d against an independent quadrature written here, the EN 1436 class limits, measured data
// near and far from the geometry, and the request's errors.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "roadbrdf/core/error.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/photometry/marking.h"
#include "roadbrdf/photometry/marking_request.h"
#include "support/paths.h"
#include "support/scratch.h"

namespace roadbrdf::photometry {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

SpectralModel lambert(double rho) { return SpectralModel(make_model("lambert"), {rho}); }

// Lambertian marking: f_r = rho/pi, so R_L = 1000 (rho/pi) cos(88.76 deg), Q_d = 1000 rho/pi, beta = rho.
TEST(Marking, LambertianClosedForms) {
  for (const double rho : {0.2, 0.5, 0.9}) {
    const MarkingFigures f = marking_figures(lambert(rho), SpectralWeighting{}, 1.24, 2.29);
    EXPECT_NEAR(f.rl, 1000.0 * rho / kPi * std::cos(88.76 * kDeg), 1e-9);
    EXPECT_NEAR(f.qd, 1000.0 * rho / kPi, 0.01);
    EXPECT_LE(f.qd_error, 0.01);
    EXPECT_NEAR(f.beta, rho, 1e-12);
  }
}

// Q_d of a rough, non-Lambertian surface against an independent product rule written here:
// (1/pi) int_0^{pi/2} int_0^{2pi} f(w_i, w_r) cos(theta_i) sin(theta_i) dphi dtheta, Gauss-Legendre in
// cos(theta_i) (mu) and the midpoint rule in phi, on panels split where the lobe is.
double independent_qd(const Model& model, const std::vector<double>& p, double theta_r) {
  // 48-point Gauss-Legendre nodes on [-1, 1] by Newton iteration on P_n (independent of core/quadrature.h).
  const int n = 48;
  std::vector<double> x(n), w(n);
  for (int k = 0; k < n; ++k) {
    double z = std::cos(kPi * (k + 0.75) / (n + 0.5));
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int j = 2; j <= n; ++j) {
        const double p2 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p0) / j;
        p0 = p1;
        p1 = p2;
      }
      const double dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-15) break;
    }
    double p0 = 1.0, p1 = z;
    for (int j = 2; j <= n; ++j) {
      const double p2 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p0) / j;
      p0 = p1;
      p1 = p2;
    }
    const double dp = n * (z * p1 - p0) / (z * z - 1.0);
    x[k] = z;
    w[k] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
  const int panels = 8, n_phi = 720;
  double sum = 0.0;
  for (int q = 0; q < panels; ++q) {
    const double a = static_cast<double>(q) / panels, b = static_cast<double>(q + 1) / panels;
    for (int k = 0; k < n; ++k) {
      const double mu = 0.5 * (a + b) + 0.5 * (b - a) * x[k];
      const double wmu = 0.5 * (b - a) * w[k];
      double inner = 0.0;
      for (int j = 0; j < n_phi; ++j) {
        const double phi = (j + 0.5) * 2.0 * kPi / n_phi;
        inner += model.evaluate(p.data(), geometry_from_radians(std::acos(mu), phi, theta_r, 0.0));
      }
      sum += wmu * mu * inner * 2.0 * kPi / n_phi;
    }
  }
  return 1000.0 * sum / kPi;
}

TEST(Marking, QdMatchesAnIndependentIntegral) {
  const auto model = make_model("oren-nayar");
  std::vector<double> p;
  for (const auto& d : model->description().parameters) p.push_back(d.default_value);
  const double theta_r = (90.0 - 2.29) * kDeg;
  const QdIntegral qd = qd_of_model(*model, p.data(), 1, 2.29);
  ASSERT_TRUE(qd.converged);
  EXPECT_NEAR(qd.value[0], independent_qd(*model, p, theta_r), 0.02);
}

// Retro-phong is not reciprocal (its lobe weights depend on theta_i): the integral runs over the
// directions of incidence, not over those of observation.
TEST(Marking, QdOfANonReciprocalModelIntegratesOverIncidence) {
  const auto model = make_model("retro-phong");
  std::vector<double> p;
  for (const auto& d : model->description().parameters) p.push_back(d.name == "n" ? 8.0 : d.default_value);
  const double theta_r = (90.0 - 2.29) * kDeg;
  const QdIntegral qd = qd_of_model(*model, p.data(), 1, 2.29);
  ASSERT_TRUE(qd.converged);
  const double reference = independent_qd(*model, p, theta_r);
  EXPECT_NEAR(qd.value[0], reference, 1e-3 * reference);
}

// EN 1436:2018 class limits [mcd m^-2 lx^-1] (Q_d: Q1 80, Q2 100, Q3 130, Q4 160; R_L dry: R1 80,
// R2 100, R3 150, R4 200, R5 300).
TEST(Marking, ClassLimitsOfTheStandard) {
  EXPECT_EQ(marking_class(rl_classes(), 0.0), "R0");
  EXPECT_EQ(marking_class(rl_classes(), 79.9), "R0");
  EXPECT_EQ(marking_class(rl_classes(), 80.0), "R1");
  EXPECT_EQ(marking_class(rl_classes(), 149.9), "R2");
  EXPECT_EQ(marking_class(rl_classes(), 200.0), "R4");
  EXPECT_EQ(marking_class(rl_classes(), 2000.0), "R5");
  EXPECT_EQ(marking_class(qd_classes(), 99.0), "Q1");
  EXPECT_EQ(marking_class(qd_classes(), 130.0), "Q3");
  EXPECT_EQ(marking_class(qd_classes(), 160.0), "Q4");
}

TEST(Marking, RequestForAModelGivesValuesAndClasses) {
  MarkingRequest r;
  r.source = "lambert";
  r.parameters = {"albedo=0.6"};
  const MarkingResult result = marking(r);
  ASSERT_TRUE(result.qd && result.rl && result.beta);
  EXPECT_NEAR(*result.qd, 600.0 / kPi, 0.01);  // 191 mcd: Q4
  EXPECT_EQ(result.qd_class, "Q4");
  EXPECT_EQ(result.rl_class, "R0");  // a Lambertian surface retroreflects little: 4.2 mcd
  EXPECT_EQ(result.to_json()["Qd_class"], "Q4");
}

TEST(Marking, RequestErrorsNameTheirFields) {
  const auto field_of = [](MarkingRequest r) {
    try {
      r.validate();
    } catch (const FieldError& e) {
      return e.field();
    }
    return std::string("none");
  };
  MarkingRequest r;
  r.source = "lambert";
  r.illumination_angle = 0.0;
  EXPECT_EQ(field_of(r), "illumination_angle");
  r = {};
  r.source = "lambert";
  r.tolerance = -1.0;
  EXPECT_EQ(field_of(r), "tolerance");
  r = {};
  r.source = "data.csv";
  r.parameters = {"albedo=0.5"};
  EXPECT_EQ(field_of(r), "parameters");
  r = {};
  r.source = "lambert";
  r.wavelength = 550.0;
  r.illuminant = "D65";
  EXPECT_EQ(field_of(r), "illuminant");
}

// A measured dataset written here: a Lambertian sample of albedo 0.4 at the exact R_L geometry and at
// 45/0, and a file without the grazing geometry.
std::string write_data(const std::string& name, bool with_grazing) {
  const std::string path = test::scratch_path(name);
  std::ofstream out(path);
  out.precision(17);
  out << "theta_i,phi_i,theta_r,phi_r,550\n";
  const double f = 0.4 / kPi;
  out << "45,0,0,0," << f << "\n";
  out << "30,0,30,180," << f << "\n";
  if (with_grazing) {
    out << "88.76,10,87.71,10," << f << "\n";  // the geometry itself, turned by 10 deg about the normal
    out << "88,0,87,0," << 2 * f << "\n";
  }
  return path;
}

TEST(Marking, MeasuredDataAtTheGeometry) {
  MarkingRequest r;
  r.source = write_data("marking_data_covered.csv", true);
  const MarkingResult result = marking(r);
  ASSERT_TRUE(result.rl);
  EXPECT_NEAR(*result.rl, 1000.0 * 0.4 / kPi * std::sin(1.24 * kDeg), 1e-9);
  EXPECT_NEAR(*result.rl_nearest_distance, 0.0, 1e-6);
  ASSERT_TRUE(result.beta);
  EXPECT_NEAR(*result.beta, 0.4, 1e-12);
  EXPECT_FALSE(result.qd);  // Q_d needs a model: a note says so
  EXPECT_FALSE(result.diagnostics.notes.empty());
}

TEST(Marking, MeasuredDataFarFromTheGeometryIsAnErrorNamingAFit) {
  MarkingRequest r;
  r.source = write_data("marking_data_far.csv", false);
  try {
    marking(r);
    FAIL() << "expected an error";
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "source");
    EXPECT_NE(e.detail().find("retro-phong"), std::string::npos) << e.detail();
    EXPECT_NE(e.detail().find("nearest measured geometry"), std::string::npos) << e.detail();
  }
}

// Inverse-distance weights between two measured values at equal distance give their mean.
TEST(Marking, DataValueInterpolatesBetweenNeighbours) {
  SpectralDataset d;
  d.wavelengths = {550.0};
  d.geometries = {geometry_from_degrees(60.0, 0.0, 59.0, 0.0), geometry_from_degrees(60.0, 0.0, 61.0, 0.0)};
  d.brdf = {1.0, 3.0};
  const auto v = data_value_at(d, geometry_from_degrees(60.0, 0.0, 60.0, 0.0), {1.0}, 1.5);
  ASSERT_TRUE(v);
  EXPECT_NEAR(v->value, 2.0, 1e-12);
  EXPECT_EQ(v->points, 2u);
  EXPECT_NEAR(v->nearest_distance_deg, 1.0, 1e-9);
  double nearest = 0.0;
  EXPECT_FALSE(data_value_at(d, geometry_from_degrees(60.0, 0.0, 65.0, 0.0), {1.0}, 1.5, &nearest));
  EXPECT_NEAR(nearest, 4.0, 1e-9);
}

}  // namespace
}  // namespace roadbrdf::photometry
