// Installation files: the example of the docs, every error located by its key path, the luminaire
// positions of each arrangement and the orientation of the C-planes relative to the road.
#include <gtest/gtest.h>

#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/lighting/calculation.h"
#include "roadbrdf/lighting/installation.h"

namespace roadbrdf::lighting {
namespace {

const std::string kExample = R"({"format": "roadbrdf-installation", "version": 1,
 "road": {"lanes": 2, "lane_width_m": 3.5},
 "luminaires": {"file": "road.ldt", "arrangement": "single-sided", "side": "right", "spacing_m": 30,
                "height_m": 10, "overhang_m": 0, "tilt_deg": 0, "maintenance_factor": 0.8,
                "flux_lm": 12000, "power_w": 90},
 "surface": {"model": "lambert", "parameters": {"albedo": 0.2}}})";

Installation parse(const std::string& text) {
  return parse_installation(parse_json_text(text, "inst.json"), "inst.json", "base");
}

// The message of the error parsing `text` with `from` replaced by `to` in the example.
std::string error_of(const std::string& from, const std::string& to) {
  std::string text = kExample;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  try {
    parse(text);
  } catch (const FileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << to;
  return "";
}

TEST(Installation, TheDocumentedExample) {
  const Installation inst = parse(kExample);
  EXPECT_EQ(inst.road.lanes, 2);
  EXPECT_EQ(inst.road.lane_width_m, 3.5);
  EXPECT_EQ(inst.luminaires.file, "base/road.ldt");
  EXPECT_EQ(inst.luminaires.arrangement, Arrangement::single_sided);
  EXPECT_EQ(inst.luminaires.side, RoadSide::right);
  EXPECT_EQ(inst.luminaires.spacing_m, 30.0);
  EXPECT_EQ(inst.luminaires.maintenance_factor, 0.8);
  EXPECT_EQ(*inst.luminaires.flux_lm, 12000.0);
  EXPECT_EQ(*inst.luminaires.power_w, 90.0);
  EXPECT_EQ(inst.surface.kind, SurfaceSpec::Kind::model);
  EXPECT_EQ(inst.surface.name, "lambert");
  ASSERT_EQ(inst.surface.parameters.size(), 1u);
  EXPECT_EQ(inst.surface.parameters[0].second, 0.2);
}

TEST(Installation, ErrorsNameTheKeyPath) {
  const auto has = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << message << " (expected " << part << ")";
  };
  has(error_of("\"spacing_m\": 30", "\"spacing_m\": -3"), "inst.json: luminaires.spacing_m: must be positive");
  has(error_of("\"lanes\": 2", "\"lanes\": 2.5"), "road.lanes");
  has(error_of("\"lanes\": 2, ", ""), "road.lanes");
  has(error_of("\"single-sided\"", "\"stagered\""), "luminaires.arrangement");
  has(error_of("\"single-sided\"", "\"stagered\""), "staggered");
  has(error_of("\"single-sided\"", "\"opposite\""), "luminaires.side: applies to the single-sided arrangement only");
  has(error_of("\"maintenance_factor\": 0.8", "\"maintenance_factor\": 1.2"), "luminaires.maintenance_factor");
  has(error_of("\"height_m\": 10", "\"height_m\": 1"), "luminaires.height_m: must exceed");
  has(error_of("\"tilt_deg\": 0", "\"tilt_deg\": 95"), "luminaires.tilt_deg");
  has(error_of("\"power_w\": 90", "\"power_w\": 90, \"colour\": 3"), "colour");
  has(error_of("\"albedo\": 0.2", "\"albedoo\": 0.2"), "surface: model 'lambert' has no parameter 'albedoo'");
  has(error_of("\"albedo\": 0.2", "\"albedo\": 1.7"), "surface");
  has(error_of("\"model\": \"lambert\", \"parameters\": {\"albedo\": 0.2}", "\"rtable\": \"R5\""),
      "surface.rtable: 'R5' is not a CIE standard table");
  has(error_of("\"model\": \"lambert\", \"parameters\": {\"albedo\": 0.2}", "\"rtable\": \"R3\", \"q0\": 2"),
      "surface.q0: must lie in (0, 1)");
  has(error_of("\"model\": \"lambert\"", "\"rtable\": \"R3\", \"model\": \"lambert\""), "surface: needs exactly one");
  has(error_of("\"roadbrdf-installation\"", "\"roadbrdf-mix\""), "format: must be \"roadbrdf-installation\"");
  has(error_of("\"version\": 1", "\"version\": 2"), "version");
}

TEST(Installation, SurfaceGivenAsText) {
  EXPECT_EQ(surface_from_text("r3", "surface").name, "R3");
  EXPECT_EQ(*surface_from_text("C2:0.08", "surface").q0, 0.08);
  EXPECT_EQ(surface_from_text("x.rtb", "surface").kind, SurfaceSpec::Kind::rtable_file);
  EXPECT_EQ(surface_from_text("F1.MIX.json", "surface").kind, SurfaceSpec::Kind::model_file);
  EXPECT_THROW(surface_from_text("R3:7", "surface"), FieldError);
  try {
    surface_from_text("asphalt", "surface");
    FAIL();
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "surface");
  }
}

TEST(Installation, LuminairePositionsOfEachArrangement) {
  Road road;  // 2 x 3.5 m
  LuminaireLayout layout;
  layout.spacing_m = 30.0;
  layout.height_m = 9.0;
  layout.overhang_m = 1.0;
  auto period = luminaires_of_period(road, layout);
  ASSERT_EQ(period.size(), 1u);
  EXPECT_EQ(period[0].y, 1.0);
  EXPECT_EQ(period[0].azimuth_deg, 0.0);
  layout.side = RoadSide::left;
  period = luminaires_of_period(road, layout);
  EXPECT_EQ(period[0].y, 6.0);
  EXPECT_EQ(period[0].azimuth_deg, 180.0);
  layout.arrangement = Arrangement::staggered;
  period = luminaires_of_period(road, layout);
  ASSERT_EQ(period.size(), 2u);
  EXPECT_EQ(period[1].x, 15.0);
  EXPECT_EQ(period[1].y, 6.0);
  layout.arrangement = Arrangement::twin_central;
  road.median_width_m = 2.0;
  period = luminaires_of_period(road, layout);
  ASSERT_EQ(period.size(), 2u);
  EXPECT_EQ(period[0].y, 6.0);   // over this carriageway, from its left-hand edge
  EXPECT_EQ(period[1].y, 10.0);  // over the other one, beyond the 2 m reserve
  EXPECT_FALSE(period[1].lights_this_carriageway);
  EXPECT_EQ(luminaires_per_period(layout), 1u);
  EXPECT_EQ(luminaires_between(road, layout, 0.0, 60.0).size(), 6u);
}

TEST(Installation, CPlanesRelativeToTheRoad) {
  double c = 0.0, gamma = 0.0;
  // Right-hand side: C0 along the road (+x), C90 across the carriageway (+y).
  luminaire_angles(0.0, 0.0, 1.0, 0.0, -1.0, c, gamma);
  EXPECT_NEAR(c, 0.0, 1e-12);
  EXPECT_NEAR(gamma, 45.0, 1e-12);
  luminaire_angles(0.0, 0.0, 0.0, 1.0, -1.0, c, gamma);
  EXPECT_NEAR(c, 90.0, 1e-12);
  luminaire_angles(0.0, 0.0, 0.0, 0.0, -1.0, c, gamma);
  EXPECT_NEAR(gamma, 0.0, 1e-12);
  // Left-hand side (turned by 180 deg): C90 again across the carriageway, now towards -y.
  luminaire_angles(180.0, 0.0, 0.0, -1.0, -1.0, c, gamma);
  EXPECT_NEAR(c, 90.0, 1e-12);
  luminaire_angles(180.0, 0.0, -1.0, 0.0, -1.0, c, gamma);
  EXPECT_NEAR(c, 0.0, 1e-12);
  // rotation_deg 90: the file's C0 plane points across the road.
  luminaire_angles(90.0, 0.0, 0.0, 1.0, -1.0, c, gamma);
  EXPECT_NEAR(c, 0.0, 1e-12);
  // A tilt of 15 deg turns the downward axis 15 deg towards the carriageway.
  luminaire_angles(0.0, 15.0, 0.0, std::sin(15.0 * 3.14159265358979323846 / 180.0),
                   -std::cos(15.0 * 3.14159265358979323846 / 180.0), c, gamma);
  EXPECT_NEAR(gamma, 0.0, 1e-9);
  luminaire_angles(0.0, 15.0, 0.0, 0.0, -1.0, c, gamma);
  EXPECT_NEAR(gamma, 15.0, 1e-9);
  EXPECT_NEAR(c, 270.0, 1e-9);  // the nadir is now on the kerb side of the luminaire
}

}  // namespace
}  // namespace roadbrdf::lighting
