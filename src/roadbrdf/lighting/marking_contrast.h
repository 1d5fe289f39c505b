// The luminance contrast of a road marking against a pavement (photometry/marking_contrast.h) under a
// vehicle's headlamp at EN 1436's 30 m geometry and under a road-lighting installation (EN 13201-3),
// and `marking`, the task of `roadbrdf marking` / roadbrdf.marking with it: photometry::marking with
// this module's contrast (the lighting module sits above photometry and reads the headlamp, the
// installation and the pavement).
//
// Headlamp frame. A headlamp's file is read as any luminaire's (luminaire.h, type C photometry), with
// its photometric axis (gamma = 0) aimed straight ahead along the road, horizontally, and its C270
// half-plane pointing down (C0 to the driver's right, C90 up): the type C solid turned by +90 deg about
// the axis across the road, the way the TU Berlin RoadRad scenes place their headlamp file (a turn of
// +90 deg about x of a file whose C0 lies along x and C90 along y). The marking lies straight ahead of
// the headlamp at epsilon below the axis: C = the down plane, gamma = epsilon. Files of another
// convention give their down plane in the request (`headlamp_down_plane`).
#pragma once

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/lighting/luminaire.h"
#include "roadbrdf/lighting/road_surface.h"
#include "roadbrdf/photometry/marking_request.h"

namespace roadbrdf::lighting {

// (a) The contrast from the two R_L values [mcd m^-2 lx^-1] at illumination angle epsilon and
// observation angle alpha [deg], with the luminances when `headlamp` is given (its C-plane
// `down_plane_deg` pointing down).
photometry::HeadlampContrast headlamp_contrast(double rl_marking, double rl_road, double illumination_angle_deg,
                                               double observation_angle_deg, const Luminaire* headlamp,
                                               double down_plane_deg = photometry::kHeadlampDownPlaneDeg);

// (b) The contrast of `marking` against `road` under `installation` lit by `luminaire`.
photometry::InstallationContrast installation_contrast(const Installation& installation, const Luminaire& luminaire,
                                                       const RoadSurface& marking, const RoadSurface& road,
                                                       Diagnostics& diagnostics);

// The pavement of a marking request: a CIE table, an r-table file, a FIT.json / MIX.json or a model
// name with `pavement_parameters`. Throws FieldError naming `pavement`.
RoadSurface pavement_surface(const photometry::MarkingRequest& request, Diagnostics& diagnostics);

// The contrast part of `marking` (photometry::MarkingContrastFunction).
photometry::MarkingContrast marking_contrast(const photometry::MarkingRequest& request,
                                             const SpectralModel* marking_model,
                                             const photometry::MarkingResult& figures, Diagnostics& diagnostics);

// The marking request's task with its contrast. Throws FieldError / FileError / InputError.
photometry::MarkingResult marking(const photometry::MarkingRequest& request);

}  // namespace roadbrdf::lighting
