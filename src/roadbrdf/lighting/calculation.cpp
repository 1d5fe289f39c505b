#include "roadbrdf/lighting/calculation.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::lighting {

void luminaire_angles(double azimuth_deg, double tilt_deg, double dx, double dy, double dz, double& c_deg,
                      double& gamma_deg) {
  // Into the luminaire's frame: turn by -azimuth about z (C0 becomes +x', C90 +y'), then undo the
  // tilt, a turn by -tilt about x' (the tilt turned the downward axis towards +y').
  const double a = deg_to_rad(azimuth_deg), t = deg_to_rad(tilt_deg);
  const double x1 = std::cos(a) * dx + std::sin(a) * dy;
  const double y1 = -std::sin(a) * dx + std::cos(a) * dy;
  const double y2 = std::cos(t) * y1 + std::sin(t) * dz;
  const double z2 = -std::sin(t) * y1 + std::cos(t) * dz;
  const double horizontal = std::hypot(x1, y2);
  gamma_deg = rad_to_deg(std::atan2(horizontal, -z2));
  c_deg = horizontal > 0.0 ? rad_to_deg(std::atan2(y2, x1)) : 0.0;
  if (c_deg < 0.0) c_deg += 360.0;
}

double InstalledPhotometry::towards(const PlacedLuminaire& at, double dx, double dy, double dz) const {
  double c = 0.0, gamma = 0.0;
  luminaire_angles(at.azimuth_deg, tilt_deg, dx, dy, dz, c, gamma);
  return flux_scale * luminaire->distribution.intensity(c, gamma);
}

InstalledPhotometry installed_photometry(const Luminaire& luminaire, const LuminaireLayout& layout) {
  InstalledPhotometry p;
  p.luminaire = &luminaire;
  p.tilt_deg = layout.tilt_deg;
  if (layout.flux_lm) {
    if (!(luminaire.flux_lm > 0.0)) {
      throw InputError("luminaires.flux_lm: the luminaire file gives no rated flux to scale from");
    }
    p.flux_scale = *layout.flux_lm / luminaire.flux_lm;
  }
  return p;
}

CalculationGrid standard_grid(const Road& road, double spacing_m) {
  CalculationGrid grid;
  grid.spacing_m = spacing_m;
  // EN 13201-3:2015: N = 10 for S <= 30 m, else the least integer with D = S / N <= 3 m.
  const auto n = spacing_m <= 30.0 ? std::size_t{10} : static_cast<std::size_t>(std::ceil(spacing_m / 3.0 - 1e-12));
  grid.step_x_m = spacing_m / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) grid.x.push_back((static_cast<double>(i) + 0.5) * grid.step_x_m);
  grid.step_y_m = road.lane_width_m / 3.0;
  for (int lane = 0; lane < road.lanes; ++lane) {
    for (int j = 0; j < 3; ++j) grid.y.push_back(lane * road.lane_width_m + (j + 0.5) * grid.step_y_m);
  }
  return grid;
}

namespace {

// Three-point Lagrange interpolation of f at x on the nodes xs[k-1], xs[k], xs[k+1].
double lagrange3(const double* xs, const double* f, double x) {
  const double x0 = xs[0], x1 = xs[1], x2 = xs[2];
  return f[0] * (x - x1) * (x - x2) / ((x0 - x1) * (x0 - x2)) + f[1] * (x - x0) * (x - x2) / ((x1 - x0) * (x1 - x2)) +
         f[2] * (x - x0) * (x - x1) / ((x2 - x0) * (x2 - x1));
}

// First index of the three-node stencil for x: centred on the nearest node, kept inside the axis.
template <std::size_t N>
std::size_t stencil_start(const std::array<double, N>& xs, double x) {
  std::size_t nearest = 0;
  for (std::size_t k = 1; k < N; ++k) {
    if (std::abs(xs[k] - x) < std::abs(xs[nearest] - x)) nearest = k;
  }
  return std::clamp<std::size_t>(nearest, 1, N - 2) - 1;
}

}  // namespace

double interpolate_r(const photometry::RTable& table, double tan_gamma, double beta_deg, std::size_t& missing,
                     std::size_t& beyond) {
  const auto& ts = photometry::standard_tan_gamma();
  const auto& bs = photometry::standard_beta_deg();
  if (tan_gamma > ts.back()) {
    ++beyond;
    return 0.0;
  }
  const std::size_t i0 = stencil_start(ts, tan_gamma), j0 = stencil_start(bs, beta_deg);
  double along_t[3];
  bool any_missing = false;
  for (std::size_t a = 0; a < 3; ++a) {
    double row[3];
    for (std::size_t b = 0; b < 3; ++b) {
      const double v = table.at(i0 + a, j0 + b);
      any_missing = any_missing || std::isnan(v);
      row[b] = std::isnan(v) ? 0.0 : v;
    }
    along_t[a] = lagrange3(&bs[j0], row, beta_deg);
  }
  if (any_missing) ++missing;
  return lagrange3(&ts[i0], along_t, tan_gamma) / photometry::kRScale;
}

double veiling_age_factor(double age_years) { return 9.86 * (1.0 + std::pow(age_years / 66.4, 4.0)); }

double threshold_increment(double veiling_luminance, double average_luminance) {
  if (!(average_luminance > 0.0)) return std::numeric_limits<double>::infinity();
  return average_luminance <= 5.0 ? 65.0 * veiling_luminance / std::pow(average_luminance, 0.8)
                                  : 95.0 * veiling_luminance / std::pow(average_luminance, 1.05);
}

namespace {

struct Statistics {
  double average = 0.0, minimum = 0.0, maximum = 0.0;
};
Statistics statistics(const std::vector<double>& values) {
  Statistics s;
  if (values.empty()) return s;
  s.minimum = *std::min_element(values.begin(), values.end());
  s.maximum = *std::max_element(values.begin(), values.end());
  double sum = 0.0;
  for (double v : values) sum += v;
  s.average = sum / static_cast<double>(values.size());
  return s;
}
double ratio(double a, double b) { return b > 0.0 ? a / b : 0.0; }

}  // namespace

double horizontal_illuminance(const std::vector<PlacedLuminaire>& luminaires, const InstalledPhotometry& photometry,
                              double mf, double x, double y) {
  double e = 0.0;
  for (const PlacedLuminaire& l : luminaires) {
    if (std::abs(l.x - x) > kCountedHeights * l.z) continue;
    const double dx = x - l.x, dy = y - l.y, dz = -l.z;
    const double d2 = dx * dx + dy * dy + dz * dz;
    // E = I cos(eps) / d^2 with cos(eps) = h / d: I cos^3(eps) / h^2.
    e += photometry.towards(l, dx, dy, dz) * l.z / (d2 * std::sqrt(d2));
  }
  return mf * e;
}

namespace {

double strip_average(const std::vector<PlacedLuminaire>& luminaires, const InstalledPhotometry& photometry, double mf,
                     const CalculationGrid& grid, double y_lo, double width) {
  double sum = 0.0;
  for (double x : grid.x) {
    for (int j = 0; j < 3; ++j)
      sum += horizontal_illuminance(luminaires, photometry, mf, x, y_lo + (j + 0.5) * width / 3.0);
  }
  return sum / (3.0 * static_cast<double>(grid.x.size()));
}

// One contribution of a luminaire to a grid point seen by an observer, for the BRDF evaluations.
struct Contribution {
  std::size_t point = 0;
  double irradiance = 0.0;  // I cos^3(eps) / h^2 x MF [lx]
  RoadAngles angles;
};

void luminance_for_observer(const Installation& inst, const std::vector<PlacedLuminaire>& luminaires,
                            const InstalledPhotometry& photometry, const RoadSurface& surface,
                            const CalculationGrid& grid, ObserverFigures& obs, LightingFigures& fig,
                            std::vector<Contribution>& contributions) {
  const double mf = inst.luminaires.maintenance_factor;
  const std::size_t ny = grid.y.size();
  obs.luminance.assign(grid.size(), 0.0);
  obs.alpha_min_deg = 90.0;
  obs.alpha_max_deg = 0.0;
  for (std::size_t i = 0; i < grid.x.size(); ++i) {
    for (std::size_t j = 0; j < ny; ++j) {
      const double px = grid.x[i], py = grid.y[j];
      const double ox = obs.x_m - px, oy = obs.y_m - py;  // towards the observer
      const double observer_distance = std::hypot(ox, oy);
      const double alpha = rad_to_deg(std::atan2(kEyeHeight, observer_distance));
      obs.alpha_min_deg = std::min(obs.alpha_min_deg, alpha);
      obs.alpha_max_deg = std::max(obs.alpha_max_deg, alpha);
      double l_sum = 0.0;
      for (const PlacedLuminaire& l : luminaires) {
        if (std::abs(l.x - px) > kCountedHeights * l.z) continue;
        const double lx = l.x - px, ly = l.y - py;  // towards the luminaire's foot
        const double foot = std::hypot(lx, ly);
        const double tan_gamma = foot / l.z;
        // beta: 180 deg minus the plan angle between the directions to the observer and to the
        // luminaire (0 = luminaire beyond the point, the forward side).
        double beta = 0.0;
        if (foot > 0.0) {
          const double c = std::clamp((ox * lx + oy * ly) / (observer_distance * foot), -1.0, 1.0);
          beta = 180.0 - rad_to_deg(std::acos(c));
        }
        const double intensity = mf * photometry.towards(l, -lx, -ly, -l.z);
        const double r = interpolate_r(surface.table, tan_gamma, beta, fig.missing_cells, fig.beyond_table);
        l_sum += r * intensity / (l.z * l.z);
        if (surface.has_brdf()) {
          Contribution c;
          c.point = i * ny + j;
          c.irradiance = intensity * std::pow(1.0 + tan_gamma * tan_gamma, -1.5) / (l.z * l.z);
          c.angles.gamma = rad_to_deg(std::atan(tan_gamma));
          c.angles.alpha = alpha;
          c.angles.beta = beta;
          contributions.push_back(c);
        }
      }
      obs.luminance[i * ny + j] = l_sum;
    }
  }
}

// Average, overall uniformity and the longitudinal uniformity along the centre line of `lane`.
void luminance_figures(const std::vector<double>& luminance, const CalculationGrid& grid, std::size_t lane,
                       double& average, double& overall, double& longitudinal) {
  const Statistics s = statistics(luminance);
  average = s.average;
  overall = ratio(s.minimum, s.average);
  std::vector<double> centre;
  for (std::size_t i = 0; i < grid.x.size(); ++i) centre.push_back(luminance[i * grid.y.size() + 3 * lane + 1]);
  const Statistics c = statistics(centre);
  longitudinal = ratio(c.minimum, c.maximum);
}

void brdf_luminance(const RoadSurface& surface, const std::vector<Contribution>& contributions,
                    const CalculationGrid& grid, ObserverFigures& obs) {
  std::vector<Geometry> geometries;
  geometries.reserve(2 * contributions.size());
  for (const Contribution& c : contributions) geometries.push_back(geometry_from_road_angles(c.angles));
  for (const Contribution& c : contributions) {
    RoadAngles at_one = c.angles;
    at_one.alpha = 1.0;
    geometries.push_back(geometry_from_road_angles(at_one));
  }
  const std::vector<double> f = surface.brdf(geometries);
  obs.luminance_true_alpha.assign(grid.size(), 0.0);
  obs.luminance_alpha_1.assign(grid.size(), 0.0);
  const std::size_t n = contributions.size();
  for (std::size_t k = 0; k < n; ++k) {
    // L = f_r E: the luminance coefficient q is the BRDF (CIE 144), r = q cos^3(gamma).
    obs.luminance_true_alpha[contributions[k].point] += f[k] * contributions[k].irradiance;
    obs.luminance_alpha_1[contributions[k].point] += f[n + k] * contributions[k].irradiance;
  }
}

// f_TI of one observer (lane centre): the observer moves over one spacing in steps D from the
// position where the first luminaire of the field is screened at 20 deg; the largest value counts.
// Computed for the new installation (maintenance factor 1 in L_v and L_av).
void glare_for_observer(const Installation& inst, const InstalledPhotometry& photometry, const CalculationGrid& grid,
                        double mf, ObserverFigures& obs) {
  const LuminaireLayout& layout = inst.luminaires;
  const double start = -std::tan(deg_to_rad(90.0 - kScreeningAngleDeg)) * (layout.height_m - kEyeHeight);
  const double initial_l_av = obs.L_av / mf;
  const double k_age = veiling_age_factor(kObserverAge);
  const double sd = deg_to_rad(kSightDownDeg);
  const double sight[3] = {std::cos(sd), 0.0, -std::sin(sd)};
  const double tan_screen = std::tan(deg_to_rad(kScreeningAngleDeg));
  obs.f_TI = 0.0;
  obs.initial_L_av = initial_l_av;
  for (std::size_t k = 0; k < grid.x.size(); ++k) {
    const double ex = start + static_cast<double>(k) * grid.step_x_m;
    const std::vector<PlacedLuminaire> ahead =
        luminaires_between(inst.road, layout, std::nextafter(ex, ex + 1.0), ex + kGlareRange);
    double veiling = 0.0;
    for (const PlacedLuminaire& l : ahead) {
      const double dx = l.x - ex, dy = l.y - obs.y_m, dz = l.z - kEyeHeight;
      if (dz / dx > tan_screen) continue;  // hidden by the roof
      const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
      const double cos_theta = std::clamp((sight[0] * dx + sight[2] * dz) / d, -1.0, 1.0);
      const double theta_deg = rad_to_deg(std::acos(cos_theta));
      if (!(theta_deg > 0.0)) continue;
      const double e_eye = photometry.towards(l, -dx, -dy, -dz) * cos_theta / (d * d);
      veiling += e_eye / (theta_deg * theta_deg);
    }
    const double ti = threshold_increment(k_age * veiling, initial_l_av);
    if (ti > obs.f_TI || k == 0) {
      obs.f_TI = ti;
      obs.f_TI_observer_x_m = ex;
      obs.veiling_luminance = k_age * veiling;
    }
  }
}

}  // namespace

LightingFigures compute_lighting(const Installation& inst, const Luminaire& luminaire, const RoadSurface& surface,
                                 Diagnostics& diagnostics) {
  luminaire.distribution.check_consistent();
  const LuminaireLayout& layout = inst.luminaires;
  const InstalledPhotometry photometry = installed_photometry(luminaire, layout);
  LightingFigures fig;
  fig.maintenance_factor = layout.maintenance_factor;
  fig.grid = standard_grid(inst.road, layout.spacing_m);
  const CalculationGrid& grid = fig.grid;
  const double mf = layout.maintenance_factor;
  const double reach = kCountedHeights * layout.height_m;
  const double w = inst.road.width_m();
  const std::vector<PlacedLuminaire> luminaires =
      luminaires_between(inst.road, layout, -reach - layout.spacing_m, layout.spacing_m + reach);

  fig.illuminance.resize(grid.size());
  for (std::size_t i = 0; i < grid.x.size(); ++i) {
    for (std::size_t j = 0; j < grid.y.size(); ++j) {
      fig.illuminance[i * grid.y.size() + j] = horizontal_illuminance(luminaires, photometry, mf, grid.x[i], grid.y[j]);
    }
  }
  const Statistics e = statistics(fig.illuminance);
  fig.E_av = e.average;
  fig.E_min = e.minimum;
  fig.U_o_E = ratio(e.minimum, e.average);

  fig.edge_strip_width_m = std::min(5.0, 0.5 * w);
  const double ws = fig.edge_strip_width_m;
  fig.R_EI_right = ratio(strip_average(luminaires, photometry, mf, grid, -ws, ws),
                         strip_average(luminaires, photometry, mf, grid, 0.0, ws));
  fig.R_EI_left = ratio(strip_average(luminaires, photometry, mf, grid, w, ws),
                        strip_average(luminaires, photometry, mf, grid, w - ws, ws));
  fig.R_EI = std::min(fig.R_EI_right, fig.R_EI_left);

  fig.has_brdf_luminance = surface.has_brdf();
  for (int lane = 0; lane < inst.road.lanes; ++lane) {
    ObserverFigures obs;
    obs.lane = static_cast<std::size_t>(lane);
    obs.x_m = -kObserverDistance;
    obs.y_m = (lane + 0.5) * inst.road.lane_width_m;
    std::vector<Contribution> contributions;
    luminance_for_observer(inst, luminaires, photometry, surface, grid, obs, fig, contributions);
    luminance_figures(obs.luminance, grid, obs.lane, obs.L_av, obs.U_o, obs.U_l);
    if (surface.has_brdf()) brdf_luminance(surface, contributions, grid, obs);
    glare_for_observer(inst, photometry, grid, mf, obs);
    fig.observers.push_back(std::move(obs));
  }
  fig.L_av = fig.observers.front().L_av;
  fig.U_o = fig.observers.front().U_o;
  fig.U_l = fig.observers.front().U_l;
  fig.f_TI = fig.observers.front().f_TI;
  for (const ObserverFigures& o : fig.observers) {
    fig.L_av = std::min(fig.L_av, o.L_av);
    fig.U_o = std::min(fig.U_o, o.U_o);
    fig.U_l = std::min(fig.U_l, o.U_l);
    fig.f_TI = std::max(fig.f_TI, o.f_TI);
  }
  if (fig.missing_cells > 0) {
    diagnostics.note(
        "rtable_missing_cells",
        fmt::format("{} r-table look-ups touched cells the table does not define; they count as 0", fig.missing_cells));
  }
  if (fig.beyond_table > 0) {
    diagnostics.note("beyond_rtable", fmt::format("{} luminaire contributions at tan(gamma) > 12 count as 0 (beyond "
                                                  "the r-table)",
                                                  fig.beyond_table));
  }
  return fig;
}

}  // namespace roadbrdf::lighting
