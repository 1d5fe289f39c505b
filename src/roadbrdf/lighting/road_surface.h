// The pavement as the road-lighting calculation sees it: its r-table at the standard observation
// angle alpha = 1 deg (the luminance method of EN 13201-3), and, when the surface is a BRDF (a model,
// a FIT.json or a MIX.json), the BRDF itself: for the luminance at each point's true observation
// angle and for the flux the road reflects upward (directional-hemispherical reflectance), which an
// r-table cannot give (it is one slice of the BRDF, at alpha = 1 deg).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/lighting/installation.h"
#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/photometry/rtable.h"
#include "roadbrdf/photometry/rtable_request.h"

namespace roadbrdf::lighting {

// A directional-hemispherical reflectance tabulated against the incidence angle (below).
struct ReflectanceTable {
  std::vector<double> theta_deg, reflectance;
  double max_error = 0.0;  // the quadrature's error estimate (largest over the nodes)
  double at(double theta_deg) const;
};

struct RoadSurface {
  std::string description;   // "CIE R3 (Q0 0.07 sr^-1)", "lambert", "F1.MIX.json"...
  photometry::RTable table;  // reduced luminance coefficients at alpha = 1 deg, R = 1e4 r
  double q0 = 0.0;           // of `table`, over the standard region [sr^-1]
  double s1 = 0.0;
  std::string road_class;                   // R class from S1 ("" when S1 is undefined)
  std::optional<SpectralModel> model;       // the BRDF, when known
  photometry::SpectralWeighting weighting;  // how `model` is reduced to one value (photometric, CIE A)
  // The BRDF's directional-hemispherical reflectance when already known (hemispherical_reflectance
  // then returns it rather than integrating `model`).
  std::optional<ReflectanceTable> reflectance;
  // How brdf() evaluates `model` when set (the same numbers by a faster way, e.g. a mixture from its
  // end-members' values shared across many mixtures: mixing/end_member_cache.h).
  photometry::WeightedBrdf weighted_brdf;

  bool has_brdf() const { return model.has_value(); }
  // The photometrically weighted BRDF [sr^-1] at `geometries`; requires has_brdf().
  std::vector<double> brdf(const std::vector<Geometry>& geometries) const;
};

// The surface of an installation or of the request's `surface` field. Notes and warnings of the
// r-table computation (extrapolation, weighting) go to `diagnostics`. Throws InputError / FileError.
RoadSurface make_surface(const SurfaceSpec& spec, Diagnostics& diagnostics);
// The model of a SurfaceSpec::Kind::model with its parameters (the others at their defaults),
// checked against the model's bounds. Throws FieldError (`options`, `parameters`).
SpectralModel model_with_parameters(const SurfaceSpec& spec);
// A surface from a BRDF: its r-table computed as `roadbrdf rtable` does (photometric, CIE A).
RoadSurface surface_from_model(const SpectralModel& model, std::string description, Diagnostics& diagnostics);
// A surface known only by its r-table.
RoadSurface surface_from_table(photometry::RTable table, std::string description);

// Directional-hemispherical (black-sky) reflectance of the surface's BRDF, photometrically weighted
// as the r-table, tabulated at incidence angles [deg] 0, 10, ..., 80, 85, 89 and interpolated
// linearly in between (and held at its 89 deg value up to 90 deg). Azimuth-averaged for anisotropic
// models (the luminaires' azimuths vary over the road). The surface's `reflectance` when it carries
// one (computed elsewhere, e.g. a design study's mixture from its end-members' integrals).
ReflectanceTable hemispherical_reflectance(const RoadSurface& surface);

}  // namespace roadbrdf::lighting
