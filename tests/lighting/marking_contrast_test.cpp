// The luminance contrast of a road marking against a pavement (lighting/marking_contrast.h), against
// independent references:
// - a Lambertian marking of albedo rho_m on a Lambertian pavement of albedo rho_r has
//   L_marking / L_road = rho_m / rho_r at every point under any light, so C = rho_m / rho_r - 1 exactly
//   under the headlamp and at every grid point of the installation;
// - the headlamp's light from its file's table read here by hand: E = I(C270, gamma = epsilon)
//   cos(theta_i) / d^2, with d = 30 m / cos(epsilon), and L = (rho / pi) E for a Lambertian surface;
// - the real TU Berlin headlamp file (skipped when ../shared/real-data is absent);
// - bad requests name their field.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/marking_contrast.h"
#include "support/paths.h"
#include "support/scratch.h"

namespace roadbrdf::lighting {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEpsilon = 1.24 * kPi / 180.0;  // EN 1436 illumination angle

std::string data(const std::string& name) { return test::test_data_dir() + "/lighting/" + name; }

template <class F>
std::string field_of(F&& f) {
  try {
    f();
  } catch (const FieldError& e) {
    return e.field() + ": " + e.detail();
  }
  return "no error";
}

photometry::MarkingRequest lambertian(double rho_marking, double rho_road) {
  photometry::MarkingRequest r;
  r.source = "lambert";
  r.parameters = {"albedo=" + std::to_string(rho_marking)};
  r.pavement = "lambert";
  r.pavement_parameters = {"albedo=" + std::to_string(rho_road)};
  return r;
}

TEST(MarkingContrast, LambertianOnLambertianUnderTheHeadlampIsTheRatioOfAlbedos) {
  const double rho_m = 0.6, rho_r = 0.08;
  photometry::MarkingRequest request = lambertian(rho_m, rho_r);
  const photometry::MarkingResult result = lighting::marking(request);
  ASSERT_TRUE(result.contrast && result.contrast->headlamp);
  const photometry::HeadlampContrast& h = *result.contrast->headlamp;
  EXPECT_NEAR(h.contrast, rho_m / rho_r - 1.0, 1e-12);
  // R_L of a Lambertian surface: 1000 (rho / pi) sin(epsilon) (EN 1436 R_L = f_r cos theta_i).
  EXPECT_NEAR(h.rl_road, 1000.0 * rho_r / kPi * std::sin(kEpsilon), 1e-12);
  EXPECT_NEAR(h.headlamp_height_m, 0.65, 0.002);  // EN 1436: headlamp 0.65 m, eye 1.2 m, 30 m
  EXPECT_NEAR(h.eye_height_m, 1.2, 0.002);
  EXPECT_FALSE(h.light);  // no headlamp file: no luminances
  EXPECT_FALSE(result.contrast->installation);
}

TEST(MarkingContrast, SyntheticHeadlampLightByHand) {
  const double rho_m = 0.5, rho_r = 0.1;
  photometry::MarkingRequest request = lambertian(rho_m, rho_r);
  request.headlamp = data("headlamp.ies");
  const photometry::MarkingResult result = lighting::marking(request);
  ASSERT_TRUE(result.contrast && result.contrast->headlamp && result.contrast->headlamp->light);
  const photometry::HeadlampLight& l = *result.contrast->headlamp->light;
  // headlamp.ies, plane C270 (the one pointing down): 12000 cd at gamma 1 deg, 9000 cd at 2 deg;
  // linear in gamma at 1.24 deg.
  const double intensity = 12000.0 + (1.24 - 1.0) * (9000.0 - 12000.0);
  const double d = 30.0 / std::cos(kEpsilon);
  const double e_road = intensity * std::sin(kEpsilon) / (d * d);  // cos(theta_i) = sin(epsilon)
  EXPECT_NEAR(l.intensity_cd, intensity, 1e-9);
  EXPECT_NEAR(l.illuminance_lx, e_road, 1e-12);
  EXPECT_NEAR(l.L_marking, rho_m / kPi * e_road, 1e-12);
  EXPECT_NEAR(l.L_road, rho_r / kPi * e_road, 1e-12);
  EXPECT_NEAR(result.contrast->headlamp->contrast, rho_m / rho_r - 1.0, 1e-12);

  // A file whose C90 plane points down: 2000 cd at gamma 1 deg, 600 cd at 2 deg in that plane.
  request.headlamp_down_plane = 90.0;
  const photometry::MarkingResult turned = lighting::marking(request);
  EXPECT_NEAR(turned.contrast->headlamp->light->intensity_cd, 2000.0 + (1.24 - 1.0) * (600.0 - 2000.0), 1e-9);
  EXPECT_EQ(turned.contrast->headlamp->light->c_deg, 90.0);
}

TEST(MarkingContrast, LambertianOnLambertianUnderAnInstallationIsTheRatioEverywhere) {
  const double rho_m = 0.45, rho_r = 0.12;
  photometry::MarkingRequest request = lambertian(rho_m, rho_r);
  request.installation = data("installation.json");
  const photometry::MarkingResult result = lighting::marking(request);
  ASSERT_TRUE(result.contrast && result.contrast->installation);
  const photometry::InstallationContrast& b = *result.contrast->installation;
  const double expected = rho_m / rho_r - 1.0;
  EXPECT_EQ(b.grid_points, 60u);  // 10 x (3 points x 2 lanes), EN 13201-3 grid of the file
  ASSERT_EQ(b.observers.size(), 2u);
  for (const photometry::ObserverContrast& o : b.observers) {
    EXPECT_NEAR(o.contrast_of_averages, expected, 1e-9 * expected);
    EXPECT_NEAR(o.contrast_min, expected, 1e-9 * expected);
    EXPECT_NEAR(o.contrast_max, expected, 1e-9 * expected);
    EXPECT_NEAR(o.contrast_mean, expected, 1e-9 * expected);
    ASSERT_TRUE(o.contrast_of_averages_true_alpha);
    EXPECT_NEAR(*o.contrast_of_averages_true_alpha, expected, 1e-9 * expected);
    EXPECT_NEAR(o.L_av_marking / o.L_av_road, rho_m / rho_r, 1e-9);
    EXPECT_NEAR(o.L_min_marking / o.L_min_road, rho_m / rho_r, 1e-9);
    ASSERT_EQ(o.contrast.size(), b.x_m.size() * b.y_m.size());
    for (std::size_t p = 0; p < o.contrast.size(); ++p) {
      EXPECT_NEAR(o.L_marking[p] / o.L_road[p], rho_m / rho_r, 1e-9);
      EXPECT_NEAR(o.contrast[p], expected, 1e-9 * expected);
    }
  }
  EXPECT_NEAR(b.contrast_of_averages, expected, 1e-9 * expected);
}

TEST(MarkingContrast, TheInstallationsSurfaceIsThePavementWhenNoneIsGiven) {
  photometry::MarkingRequest request;
  request.source = "lambert";
  request.parameters = {"albedo=0.4"};
  request.installation = data("installation.json");  // its surface: lambert, albedo 0.2
  const photometry::MarkingResult result = lighting::marking(request);
  ASSERT_TRUE(result.contrast && result.contrast->headlamp && result.contrast->installation);
  EXPECT_NEAR(result.contrast->headlamp->contrast, 0.4 / 0.2 - 1.0, 1e-12);
  EXPECT_NEAR(result.contrast->installation->contrast_of_averages, 1.0, 1e-9);
}

TEST(MarkingContrast, MeasuredMarkingUnderTheHeadlampButNotUnderAnInstallation) {
  // A measured marking with a value at the R_L geometry itself: f_r = 0.5 sr^-1 at 550 nm.
  const std::string file = test::scratch_path("marking-contrast-measured.csv");
  std::ofstream(file) << "theta_i,phi_i,theta_r,phi_r,550\n88.76,0,87.71,0,0.5\n45,0,0,0,0.2\n";
  photometry::MarkingRequest request;
  request.source = file;
  request.pavement = "lambert";
  request.pavement_parameters = {"albedo=0.1"};
  const photometry::MarkingResult result = lighting::marking(request);
  ASSERT_TRUE(result.contrast && result.contrast->headlamp);
  // R_L = f_r sin(epsilon) for both; the pavement's f_r = 0.1 / pi.
  EXPECT_NEAR(result.contrast->headlamp->contrast, 0.5 / (0.1 / kPi) - 1.0, 1e-9);
  request.installation = data("installation.json");
  const std::string e = field_of([&] { lighting::marking(request); });
  EXPECT_EQ(e.rfind("installation:", 0), 0u) << e;
}

// The numbers of an IES LM-63 file after its TILT=NONE line, read here on their own.
std::vector<double> numbers_after_tilt(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line.rfind("TILT=", 0) != 0) {
  }
  std::vector<double> out;
  double x = 0.0;
  while (in >> x) out.push_back(x);
  return out;
}

TEST(MarkingContrast, RealHeadlampFileOfTuBerlin) {
  const std::string shared = test::shared_real_data_dir();
  if (shared.empty()) GTEST_SKIP() << "../shared/real-data is absent: the TU Berlin headlamp file is not available";
  const std::string file = shared + "/luminaires/tuberlin-roadrad/HeadLight.ies";
  // LM-63: lamps, lumens, multiplier, n_vertical, n_horizontal, type, units, w, l, h; ballast, future, watts;
  // the vertical angles, the horizontal angles, then the candela plane by plane.
  const std::vector<double> v = numbers_after_tilt(file);
  ASSERT_GE(v.size(), 13u);
  const auto nv = static_cast<std::size_t>(v[3]), nh = static_cast<std::size_t>(v[4]);
  const double scale = v[2] * v[10];  // multiplier x ballast factor
  const std::vector<double> gamma(v.begin() + 13, v.begin() + 13 + static_cast<long>(nv));
  const std::vector<double> c(v.begin() + 13 + static_cast<long>(nv), v.begin() + 13 + static_cast<long>(nv + nh));
  std::size_t plane = nh;
  for (std::size_t k = 0; k < nh; ++k) {
    if (c[k] == 270.0) plane = k;
  }
  ASSERT_LT(plane, nh) << "the file has a C270 plane";
  const double* candela = v.data() + 13 + nv + nh + plane * nv;
  std::size_t j = 0;
  while (gamma[j + 1] < 1.24) ++j;
  const double t = (1.24 - gamma[j]) / (gamma[j + 1] - gamma[j]);
  const double intensity = scale * ((1.0 - t) * candela[j] + t * candela[j + 1]);
  const double d = 30.0 / std::cos(kEpsilon);

  photometry::MarkingRequest request = lambertian(0.6, 0.1);
  request.headlamp = file;
  const photometry::MarkingResult result = lighting::marking(request);
  ASSERT_TRUE(result.contrast && result.contrast->headlamp && result.contrast->headlamp->light);
  const photometry::HeadlampLight& l = *result.contrast->headlamp->light;
  EXPECT_NEAR(l.intensity_cd, intensity, 1e-9 * std::max(1.0, intensity));
  EXPECT_NEAR(l.illuminance_lx, intensity * std::sin(kEpsilon) / (d * d), 1e-12);
  EXPECT_NEAR(l.L_road, 0.1 / kPi * intensity * std::sin(kEpsilon) / (d * d), 1e-12);
}

TEST(MarkingContrast, BadRequestsNameTheirField) {
  photometry::MarkingRequest missing = lambertian(0.6, 0.1);
  missing.pavement = "no-such-pavement.fit.json";
  missing.pavement_parameters.clear();
  const std::string e1 = field_of([&] { lighting::marking(missing); });
  EXPECT_EQ(e1.rfind("pavement:", 0), 0u) << e1;
  EXPECT_NE(e1.find("no-such-pavement.fit.json"), std::string::npos) << e1;

  photometry::MarkingRequest lamp_alone;
  lamp_alone.source = "lambert";
  lamp_alone.headlamp = data("headlamp.ies");
  EXPECT_EQ(field_of([&] { lighting::marking(lamp_alone); }).rfind("headlamp:", 0), 0u);

  photometry::MarkingRequest table_and_lamp = lambertian(0.6, 0.1);
  table_and_lamp.pavement = "R3";
  table_and_lamp.pavement_parameters.clear();
  table_and_lamp.headlamp = data("headlamp.ies");
  EXPECT_EQ(field_of([&] { lighting::marking(table_and_lamp); }).rfind("headlamp:", 0), 0u);

  photometry::MarkingRequest bad_parameter = lambertian(0.6, 0.1);
  bad_parameter.pavement_parameters = {"albdo=0.1"};
  EXPECT_EQ(field_of([&] { lighting::marking(bad_parameter); }).rfind("pavement_parameters:", 0), 0u);

  photometry::MarkingRequest plane_alone = lambertian(0.6, 0.1);
  plane_alone.headlamp_down_plane = 90.0;
  EXPECT_EQ(field_of([&] { lighting::marking(plane_alone); }).rfind("headlamp_down_plane:", 0), 0u);
  plane_alone.headlamp = data("headlamp.ies");
  plane_alone.headlamp_down_plane = 360.0;
  EXPECT_EQ(field_of([&] { lighting::marking(plane_alone); }).rfind("headlamp_down_plane:", 0), 0u);

  photometry::MarkingRequest stray;
  stray.source = "lambert";
  stray.pavement_fit = "lambert";
  EXPECT_EQ(field_of([&] { lighting::marking(stray); }).rfind("pavement_fit:", 0), 0u);

  // The photometry module alone cannot compute a contrast: it says so rather than dropping the field.
  photometry::MarkingRequest contrast = lambertian(0.6, 0.1);
  EXPECT_EQ(field_of([&] { photometry::marking(contrast); }).rfind("pavement:", 0), 0u);
}

}  // namespace
}  // namespace roadbrdf::lighting
