#include "roadbrdf/lighting/upward_light.h"

#include <cmath>

#include "roadbrdf/core/math.h"
#include "roadbrdf/core/quadrature.h"

namespace roadbrdf::lighting {

namespace {

// Gauss-Legendre nodes and weights of the 4-point rule on [-1, 1].
constexpr double kNodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
constexpr double kWeights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

// Incident flux (reflectance == nullptr) or reflected flux on the strip 0 <= y <= W of an infinitely
// long road from one luminaire: with x = x_l + h tan(u), dx = h du / cos^2(u), the integrand
// I cos^3(eps) / h^2 is smooth in u over (-pi/2, pi/2).
double strip_flux(const InstalledPhotometry& photometry, const PlacedLuminaire& l, double width,
                  const ReflectanceTable* reflectance) {
  constexpr int kUPanels = 48;
  const int y_panels = std::max(4, static_cast<int>(std::ceil(width / 0.5)));
  const double h = l.z;
  const double du = kPi / kUPanels, dy = width / y_panels;
  double total = 0.0;
  for (int a = 0; a < kUPanels; ++a) {
    for (int ka = 0; ka < 4; ++ka) {
      const double u = -0.5 * kPi + (a + 0.5 * (1.0 + kNodes[ka])) * du;
      const double dx = h * std::tan(u);
      const double jacobian_x = h / (std::cos(u) * std::cos(u)) * 0.5 * du * kWeights[ka];
      for (int b = 0; b < y_panels; ++b) {
        for (int kb = 0; kb < 4; ++kb) {
          const double y = (b + 0.5 * (1.0 + kNodes[kb])) * dy;
          const double ry = y - l.y;
          const double d2 = dx * dx + ry * ry + h * h;
          const double d = std::sqrt(d2);
          double e = photometry.towards(l, dx, ry, -h) * h / (d2 * d);
          if (reflectance) e *= reflectance->at(rad_to_deg(std::acos(h / d)));
          total += e * jacobian_x * 0.5 * dy * kWeights[kb];
        }
      }
    }
  }
  return total;
}

}  // namespace

double hemisphere_flux(const InstalledPhotometry& photometry, const PlacedLuminaire& at, bool upper) {
  constexpr int kZenith = 90, kAzimuth = 180;  // 1 deg x 2 deg cells
  const double dt = 0.5 * kPi / kZenith, dp = 2.0 * kPi / kAzimuth;
  double flux = 0.0;
  for (int i = 0; i < kZenith; ++i) {
    const double t0 = i * dt, t1 = (i + 1) * dt, t = (i + 0.5) * dt;
    const double solid = (std::cos(t0) - std::cos(t1)) * dp;  // exact solid angle of the cell
    const double z = upper ? std::cos(t) : -std::cos(t);
    double ring = 0.0;
    for (int k = 0; k < kAzimuth; ++k) {
      const double p = (k + 0.5) * dp;
      ring += photometry.towards(at, std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), z);
    }
    flux += ring * solid;
  }
  return flux;
}

UpwardLight upward_light(const Installation& inst, const Luminaire& luminaire, const RoadSurface& surface,
                         Diagnostics& diagnostics) {
  const LuminaireLayout& layout = inst.luminaires;
  const InstalledPhotometry photometry = installed_photometry(luminaire, layout);
  const double mf = layout.maintenance_factor;
  const double per_km = 1000.0 / layout.spacing_m;
  UpwardLight up;
  const std::vector<PlacedLuminaire> period = luminaires_of_period(inst.road, layout);
  bool first = true;
  for (const PlacedLuminaire& l : period) {
    if (!l.lights_this_carriageway) continue;
    const double upward = hemisphere_flux(photometry, l, true);
    if (first) {
      up.luminaire_flux_lm = upward + hemisphere_flux(photometry, l, false);
      up.ULOR = up.luminaire_flux_lm > 0.0 ? upward / up.luminaire_flux_lm : 0.0;
      first = false;
    }
    up.direct_upward_lm_per_km += mf * upward * per_km;
  }
  std::optional<ReflectanceTable> rho;
  if (surface.has_brdf()) {
    rho = hemispherical_reflectance(surface);
    up.reflectance_error = rho->max_error;
  } else {
    diagnostics.note("no_brdf_upward",
                     "the surface is an r-table only: the flux the road reflects upward needs the whole BRDF "
                     "(its directional-hemispherical reflectance), which an r-table does not give");
  }
  double incident = 0.0, reflected = 0.0;
  const double w = inst.road.width_m();
  for (const PlacedLuminaire& l : period) {
    incident += strip_flux(photometry, l, w, nullptr);
    if (rho) reflected += strip_flux(photometry, l, w, &*rho);
  }
  up.flux_on_carriageway_lm_per_km = mf * incident * per_km;
  if (rho) {
    up.reflected_upward_lm_per_km = mf * reflected * per_km;
    up.reflectance = incident > 0.0 ? reflected / incident : 0.0;
  }
  return up;
}

}  // namespace roadbrdf::lighting
