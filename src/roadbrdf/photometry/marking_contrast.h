// The luminance contrast of a road marking against the pavement around it,
//   C = (L_marking - L_road) / L_road
// (the luminance contrast of CIE 17.4 / CIE S 017 "luminance contrast"; positive for a marking
// brighter than the road), under
//   (a) a vehicle's headlamp at EN 1436's 30 m geometry (the geometry of R_L, marking.h): the marking
//       and the road beside it are lit by the same headlamp and seen by the same driver, so
//       L = R_L E_perp for both and C = R_L,marking / R_L,road - 1 whatever the headlamp. With a
//       headlamp file the luminances themselves are given: E_perp = I / d^2 with I the headlamp's
//       intensity towards the point and d its distance;
//   (b) a road-lighting installation computed by EN 13201-3 (lighting/calculation.h) once with the
//       marking's BRDF as the surface and once with the pavement's: at every grid point the
//       luminance a marking lying there has and the luminance of the road there, for each observer.
// These are the data of the result; lighting/marking_contrast.h computes them (it reads headlamp
// files, installations and pavements, which the lighting module owns). docs/markings.md gives the
// rules.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace roadbrdf::photometry {

// Horizontal distance from the driver (and the headlamp) to the marking in EN 1436's 30 m geometry [m];
// the headlamp and eye heights follow from the angles: h = 30 m x tan(angle) (0.65 m and 1.20 m).
inline constexpr double kHeadlampDistance = 30.0;
// The C-plane [deg] of a headlamp file that points down, by default (lighting/marking_contrast.h).
inline constexpr double kHeadlampDownPlaneDeg = 270.0;

// (a) with a headlamp file: the light at the point.
struct HeadlampLight {
  std::string file;
  double c_deg = 0.0, gamma_deg = 0.0;        // direction towards the point in the file's (C, gamma) system
  double intensity_cd = 0.0;                  // I(C, gamma)
  double distance_m = 0.0;                    // from the headlamp to the point (slant)
  double illuminance_perpendicular_lx = 0.0;  // E_perp = I / d^2, on a plane facing the headlamp
  double illuminance_lx = 0.0;                // on the road: E = E_perp cos(theta_i) = E_perp sin(epsilon)
  double L_marking = 0.0, L_road = 0.0;       // [cd/m^2] = R_L E_perp
};

struct HeadlampContrast {
  double distance_m = kHeadlampDistance;  // horizontal, driver to marking
  double headlamp_height_m = 0.0, eye_height_m = 0.0;
  double rl_marking = 0.0, rl_road = 0.0;  // [mcd m^-2 lx^-1]
  double contrast = 0.0;                   // R_L,marking / R_L,road - 1
  std::optional<HeadlampLight> light;      // with a headlamp file
};

// (b) for one observer (one per lane, EN 13201-3): the r-table method's luminances at the grid points.
struct ObserverContrast {
  std::size_t lane = 0;                                                // 0 = the lane along the right-hand edge
  double L_av_marking = 0.0, L_av_road = 0.0;                          // [cd/m^2] averages over the grid
  double L_min_marking = 0.0, L_min_road = 0.0;                        // [cd/m^2] least over the grid
  double contrast_of_averages = 0.0;                                   // L_av,marking / L_av,road - 1
  double contrast_min = 0.0, contrast_max = 0.0, contrast_mean = 0.0;  // of the grid points' contrasts
  // From both BRDFs at each point's true observation angle (when both surfaces have a BRDF).
  std::optional<double> contrast_of_averages_true_alpha;
  // At the grid points, in the order of InstallationContrast::x_m / y_m (point (i, j) at i * y_m.size() + j);
  // the contrast is NaN (JSON null) where the road's luminance is 0.
  std::vector<double> L_marking, L_road, contrast;
};

struct InstallationContrast {
  std::string installation;  // the file
  std::size_t grid_points = 0;
  std::vector<double> x_m, y_m;  // the grid: x along the road, y across from the right-hand edge [m]
  std::vector<ObserverContrast> observers;
  // Governing values over the observers: the lowest contrast of the averages, and the extreme points.
  double contrast_of_averages = 0.0, contrast_min = 0.0, contrast_max = 0.0;
};

struct MarkingContrast {
  std::string pavement;  // description of the pavement
  std::optional<HeadlampContrast> headlamp;
  std::optional<InstallationContrast> installation;

  nlohmann::json to_json() const;
  std::string summary_text() const;
};

}  // namespace roadbrdf::photometry
