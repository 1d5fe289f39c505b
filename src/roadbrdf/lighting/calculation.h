// The EN 13201-3:2015 calculation of a road-lighting installation (CIE 140-2000): the field and grid
// of calculation, the observers, the luminaires that count, the horizontal illuminance and the
// luminance (r-table method) at every grid point, and from them L_av, U_o, U_l, E_av, E_min, U_o_E,
// the threshold increment f_TI and the edge illuminance ratio R_EI. docs/lighting.md gives the clause
// each rule follows and the choices made where the standard leaves one.
//
// Units: lengths in m, angles in deg (radians inside), intensities in cd, illuminance in lx,
// luminance in cd/m^2, r in sr^-1 (the r-table stores R = 1e4 r).
#pragma once

#include <cstddef>
#include <vector>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/lighting/installation.h"
#include "roadbrdf/lighting/luminaire.h"
#include "roadbrdf/lighting/road_surface.h"

namespace roadbrdf::lighting {

inline constexpr double kEyeHeight = 1.5;           // observer's eye above the road [m]
inline constexpr double kObserverDistance = 60.0;   // observer before the field of calculation [m]
inline constexpr double kCountedHeights = 5.0;      // luminaires within 5 H of a grid point count
inline constexpr double kScreeningAngleDeg = 20.0;  // TI: the vehicle roof screens luminaires above 20 deg
inline constexpr double kSightDownDeg = 1.0;        // TI: line of sight 1 deg below the horizontal
inline constexpr double kGlareRange = 500.0;        // TI: luminaires up to 500 m ahead count
inline constexpr double kObserverAge = 23.0;        // TI: age of the standard observer [years]

// The luminaire of an installation with its flux: intensities in cd for the installed flux
// (layout.flux_lm, or the file's), without the maintenance factor.
struct InstalledPhotometry {
  const Luminaire* luminaire = nullptr;
  double flux_scale = 1.0;  // flux_lm / luminaire.flux_lm (1 without an override)
  double tilt_deg = 0.0;
  // Intensity [cd] of the luminaire at `at` towards the world direction (dx, dy, dz) (any length):
  // C-plane and gamma of luminaire.h after the turn by at.azimuth_deg and the tilt.
  double towards(const PlacedLuminaire& at, double dx, double dy, double dz) const;
};
InstalledPhotometry installed_photometry(const Luminaire& luminaire, const LuminaireLayout& layout);

// C [deg, in [0, 360)] and gamma [deg] of the world direction (dx, dy, dz) in the frame of a
// luminaire turned by azimuth_deg and tilted by tilt_deg (installation.h).
void luminaire_angles(double azimuth_deg, double tilt_deg, double dx, double dy, double dz, double& c_deg,
                      double& gamma_deg);

// The grid of EN 13201-3:2015 over one spacing: N = 10 longitudinal points for S <= 30 m, else the
// least N with S / N <= 3 m, the first D / 2 after the luminaire at x = 0; three points across each
// lane, the outer ones d / 2 from the lane's edges (d = lane width / 3).
struct CalculationGrid {
  double spacing_m = 0.0;  // S, the length of the field
  double step_x_m = 0.0;   // D = S / N
  double step_y_m = 0.0;   // d = lane width / 3
  std::vector<double> x, y;
  std::size_t size() const { return x.size() * y.size(); }
};
CalculationGrid standard_grid(const Road& road, double spacing_m);

// r(beta, tan gamma) [sr^-1] of a table: three-point (quadratic) Lagrange interpolation in beta and
// in tan gamma on the three tabulated values nearest to the point (the stencil centred on the
// nearest node, moved inwards at the table's ends). Cells the table does not define count as 0 and
// are counted in `missing`; beyond tan gamma = 12 the result is 0, counted in `beyond`.
double interpolate_r(const photometry::RTable& table, double tan_gamma, double beta_deg, std::size_t& missing,
                     std::size_t& beyond);

// Horizontal illuminance [lx] at (x, y) on the road: sum of I cos^3(eps) / h^2 x mf over the
// luminaires within 5 h of x along the road.
double horizontal_illuminance(const std::vector<PlacedLuminaire>& luminaires, const InstalledPhotometry& photometry,
                              double mf, double x, double y);

struct ObserverFigures {
  std::size_t lane = 0;           // 0 = the lane along the right-hand edge
  double x_m = 0.0, y_m = 0.0;    // plan position (eye 1.5 m above the road)
  std::vector<double> luminance;  // [cd/m^2] at grid point (i, j): luminance[i * grid.y.size() + j]
  double L_av = 0.0, U_o = 0.0;
  double U_l = 0.0;                // along the centre line of the observer's lane
  double f_TI = 0.0;               // [%] the largest over the observer's TI positions
  double f_TI_observer_x_m = 0.0;  // where that largest value was found
  double veiling_luminance = 0.0;  // L_v [cd/m^2] there, new installation (no maintenance factor)
  double initial_L_av = 0.0;       // L_av / MF [cd/m^2], the new installation's, which f_TI uses
  // The luminance from the BRDF itself (surfaces with a BRDF only): at each point's true observation
  // angle, and at alpha = 1 deg (the r-table's convention, without the table's interpolation).
  std::vector<double> luminance_true_alpha, luminance_alpha_1;
  double alpha_min_deg = 0.0, alpha_max_deg = 0.0;  // range of the true observation angles
};

struct LightingFigures {
  CalculationGrid grid;
  double maintenance_factor = 1.0;
  std::vector<double> illuminance;  // [lx], maintained, as luminance
  double E_av = 0.0, E_min = 0.0, U_o_E = 0.0;
  std::vector<ObserverFigures> observers;  // one per lane
  // Governing values: the lowest L_av, U_o, U_l and the highest f_TI over the observers.
  double L_av = 0.0, U_o = 0.0, U_l = 0.0, f_TI = 0.0;
  // Edge illuminance ratio per edge and the governing (lower) one; strip width min(5 m, W / 2).
  double R_EI = 0.0, R_EI_right = 0.0, R_EI_left = 0.0, edge_strip_width_m = 0.0;
  bool has_brdf_luminance = false;
  std::size_t missing_cells = 0, beyond_table = 0;  // r-table look-ups (interpolate_r)
};

// Everything above for `installation` with `luminaire` (the photometry of installation.luminaires.file)
// on `surface`. Notes (r-table cells used outside the table) go to `diagnostics`.
LightingFigures compute_lighting(const Installation& installation, const Luminaire& luminaire,
                                 const RoadSurface& surface, Diagnostics& diagnostics);

// Threshold increment [%] from the veiling luminance L_v and the average road luminance L_av
// (CIE 140 / EN 13201-3): 65 L_v / L_av^0.8 for L_av <= 5 cd/m^2, 95 L_v / L_av^1.05 above.
double threshold_increment(double veiling_luminance, double average_luminance);
// The age factor of the veiling luminance L_v = K sum E_eye / theta^2 (theta in deg):
// K = 9.86 (1 + (A / 66.4)^4) (CIE 146:2002 disability glare, A in years; 10.0 at 23 years).
double veiling_age_factor(double age_years);

}  // namespace roadbrdf::lighting
