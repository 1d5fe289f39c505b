// Uses the installed roadbrdf: a Lambertian surface's BRDF is albedo / pi, its white-sky albedo
// is the albedo, and the bundled ASTM G173 table integrates to ~1000 W m^-2 (global tilt).
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/albedo/solar.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/registry.h"

int main() {
  // A program outside the roadbrdf tree is told where the installed data are (roadbrdfConfig.cmake).
  setenv("ROADBRDF_DATA", ROADBRDF_INSTALLED_DATA, 0);
  const auto model = roadbrdf::make_model("lambert", {});
  const double albedo = 0.3;
  const roadbrdf::Geometry g = roadbrdf::geometry_from_degrees(30.0, 0.0, 45.0, 180.0);
  const double f = model->evaluate(&albedo, g);
  const double white = roadbrdf::albedo::white_sky(*model, &albedo, 1).value[0];
  const double total = roadbrdf::albedo::integrate_spectrum(roadbrdf::albedo::astm_g173("global"));
  std::printf("brdf %.12g white-sky %.12g astm-global %.1f\n", f, white, total);
  const bool ok =
      std::fabs(f - albedo / M_PI) < 1e-12 && std::fabs(white - albedo) < 1e-9 && std::fabs(total - 1000.4) < 1.0;
  return ok ? 0 : 1;
}
