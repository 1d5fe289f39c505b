// Light sent to the sky by a road-lighting installation: the flux the luminaires emit above the
// horizontal directly (their upward light output ratio as installed, tilt included), and the flux
// the road reflects upward. The reflected flux is sum over the carriageway of E(x, y) x
// rho_dh(eps(x, y)), with rho_dh the surface's directional-hemispherical reflectance for the
// luminaire's incidence eps: it needs the whole BRDF (road_surface.h); an r-table gives only the
// luminance towards one observation angle and cannot give it.
#pragma once

#include <optional>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/lighting/calculation.h"

namespace roadbrdf::lighting {

struct UpwardLight {
  double luminaire_flux_lm = 0.0;              // one luminaire's flux as installed, integrated over the sphere
  double ULOR = 0.0;                           // fraction of it above the horizontal, as installed (tilt included)
  double direct_upward_lm_per_km = 0.0;        // from the luminaires that light this carriageway
  double flux_on_carriageway_lm_per_km = 0.0;  // incident on the carriageway, from every luminaire
  std::optional<double> reflected_upward_lm_per_km;  // needs a BRDF
  std::optional<double> reflectance;                 // reflected / incident on the carriageway
  double reflectance_error = 0.0;                    // the hemispherical quadrature's error estimate
};

// Fluxes with the maintenance factor applied (the state of the luminance figures), per km of road.
// A surface without a BRDF leaves the reflected figures empty and says so in `diagnostics`.
UpwardLight upward_light(const Installation& installation, const Luminaire& luminaire, const RoadSurface& surface,
                         Diagnostics& diagnostics);

// Flux [lm] of one installed luminaire (flux override, no maintenance factor) within the upper
// (upper = true) or lower hemisphere of the road, for the luminaire at `at`: the integral of the
// intensity over the solid angle (cells of 1 deg in zenith angle and 2 deg in azimuth, each
// weighted by its exact solid angle).
double hemisphere_flux(const InstalledPhotometry& photometry, const PlacedLuminaire& at, bool upper);

}  // namespace roadbrdf::lighting
