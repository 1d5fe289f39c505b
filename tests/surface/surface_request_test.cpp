// The surface request (surface/surface_request.h): one validation naming fields for the virtual
// sample of a formulation and for the validation surfaces, and the command line's flags for them.
#include "roadbrdf/surface/surface_request.h"

#include <gtest/gtest.h>

#include <functional>

#include "roadbrdf/core/error.h"
#include "support/cli.h"

namespace roadbrdf::surface {
namespace {

using Kind = SurfaceRequest::Kind;

std::string field_of(const SurfaceRequest& request) {
  try {
    request.validate();
  } catch (const FieldError& e) {
    return e.field();
  }
  return "";
}

SurfaceRequest with(Kind kind, const std::function<void(SurfaceRequest&)>& change) {
  SurfaceRequest r;
  // The kind follows from `flat` and `sigma_rad` (SurfaceRequest::kind).
  r.flat = kind == Kind::flat;
  if (kind == Kind::gaussian_slopes) r.sigma_rad = 0.3;
  change(r);
  return r;
}

TEST(SurfaceRequest, FormulationSampleFields) {
  const auto none = [](SurfaceRequest&) {};
  EXPECT_EQ(field_of(with(Kind::formulation, none)), "");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.cell_mm = 0.001; })), "cell_mm");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.cell_mm = 20.0; })), "cell_mm");
  // 60 mm / 0.25 mm = 240 cells; 60.1 mm is not a whole number of 0.25 mm cells; 1 mm is 4 cells.
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.cell_mm = 0.25; })), "");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.cell_mm = 0.25, r.size_mm = 60.1; })),
            "size_mm");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.cell_mm = 0.25, r.size_mm = 1.0; })), "size_mm");
  // 1000 mm / 0.1 mm = 1e4 cells per side, 1e8 cells: above the 4e7 limit.
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.size_mm = 1000.0; })), "size_mm");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.matrix_level = 1.5; })), "matrix_level");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.matrix_level = 0.5, r.target_mpd = 1.0; })),
            "matrix_level");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.target_mpd = 1.0, r.mastic_fraction = 0.4; })),
            "target_mpd");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.target_mpd = 0.0; })), "target_mpd");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.mastic_fraction = 1.0; })), "mastic_fraction");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.cells = 64; })), "cells");
}

TEST(SurfaceRequest, ValidationSurfaceFields) {
  EXPECT_EQ(field_of(with(Kind::flat, [](SurfaceRequest&) {})), "");
  EXPECT_EQ(with(Kind::flat, [](SurfaceRequest&) {}).cell_count(), 16);
  EXPECT_EQ(with(Kind::gaussian_slopes, [](SurfaceRequest&) {}).cell_count(), 128);
  EXPECT_EQ(field_of(with(Kind::flat, [](SurfaceRequest& r) { r.size_mm = 60.0; })), "size_mm");
  EXPECT_EQ(field_of(with(Kind::flat, [](SurfaceRequest& r) { r.matrix_level = 0.5; })), "matrix_level");
  EXPECT_EQ(field_of(with(Kind::flat, [](SurfaceRequest& r) { r.cells = 1; })), "cells");
  EXPECT_EQ(field_of(with(Kind::flat, [](SurfaceRequest& r) { r.cells = 2; })), "");
  EXPECT_EQ(field_of(with(Kind::gaussian_slopes, [](SurfaceRequest& r) { r.cells = 16; })), "cells");
  EXPECT_EQ(field_of(with(Kind::gaussian_slopes, [](SurfaceRequest& r) { r.sigma_rad = 1.3; })), "sigma_rad");
  EXPECT_EQ(field_of(with(Kind::gaussian_slopes, [](SurfaceRequest& r) { r.sigma_rad = 0.0; })), "sigma_rad");
  // Without `flat` or `sigma_rad` the request is a sample of a formulation; both at once are refused.
  EXPECT_EQ(with(Kind::gaussian_slopes, [](SurfaceRequest& r) { r.sigma_rad.reset(); }).kind(), Kind::formulation);
  EXPECT_EQ(field_of(with(Kind::flat, [](SurfaceRequest& r) { r.sigma_rad = 0.3; })), "flat");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.parameters["albedo"] = 0.3; })), "parameters");
  EXPECT_EQ(field_of(with(Kind::formulation, [](SurfaceRequest& r) { r.fit = "lambert"; })), "fit");
}

TEST(SurfaceRequest, GeneratorRefusesWhatTheRequestRefuses) {
  GeneratorSettings s;
  s.matrix_level = -0.1;
  EXPECT_THROW(validate(s), FieldError);
  s.matrix_level = 0.7;
  EXPECT_NO_THROW(validate(s));
}

TEST(SurfaceRequest, CommandLineNamesItsFlags) {
  using roadbrdf::test::run_cli;
  auto r = run_cli("surface lambert -p albedo=0.3 --gaussian-slopes 2 -o /nonexistent/x.json");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("roadbrdf: error: --gaussian-slopes: must be in (0, 1.3) rad, got 2"), std::string::npos)
      << r.output;
  r = run_cli("surface lambert -p albedo=0.3 --flat --cell 20 -o /nonexistent/x.json");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("roadbrdf: error: --cell: must be in [0.005, 10] mm, got 20"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace roadbrdf::surface
