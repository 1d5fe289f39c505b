#include "roadbrdf/photometry/rtable.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <limits>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::photometry {

const std::array<double, kColumns>& standard_beta_deg() {
  static const std::array<double, kColumns> beta = {0,  2,  5,  10, 15,  20,  25,  30,  35,  40,
                                                    45, 60, 75, 90, 105, 120, 135, 150, 165, 180};
  return beta;
}

const std::array<double, kRows>& standard_tan_gamma() {
  static const std::array<double, kRows> t = [] {
    std::array<double, kRows> v{};
    for (std::size_t k = 0; k <= 8; ++k) v[k] = 0.25 * static_cast<double>(k);
    for (std::size_t k = 9; k < kRows; ++k) v[k] = 2.5 + 0.5 * static_cast<double>(k - 9);
    return v;
  }();
  return t;
}

double gamma_deg(std::size_t row) { return rad_to_deg(std::atan(standard_tan_gamma()[row])); }

const std::array<std::size_t, kRows>& standard_region_columns() {
  static const std::array<std::size_t, kRows> columns = {20, 20, 20, 20, 20, 20, 20, 20, 20, 20, 20, 20, 20, 20, 20,
                                                         10, 9,  8,  8,  7,  7,  7,  6,  6,  6,  6,  6,  5,  5};
  return columns;
}

double RTable::q(std::size_t row, std::size_t column) const {
  const double t = standard_tan_gamma()[row];
  const double cos3 = std::pow(1.0 + t * t, -1.5);
  return r(row, column) / cos3;
}

std::size_t RTable::defined_count() const {
  return static_cast<std::size_t>(std::count_if(scaled.begin(), scaled.end(), [](double x) { return !std::isnan(x); }));
}

std::vector<Geometry> rtable_geometries(double alpha_deg) {
  if (!(alpha_deg > 0.0 && alpha_deg < 90.0)) {
    throw InputError("observation angle alpha = " + std::to_string(alpha_deg) + " deg must be in (0, 90) deg");
  }
  std::vector<Geometry> g;
  g.reserve(kRows * kColumns);
  for (std::size_t i = 0; i < kRows; ++i) {
    for (std::size_t j = 0; j < kColumns; ++j) {
      RoadAngles road;
      road.gamma = gamma_deg(i);
      road.alpha = alpha_deg;
      road.beta = standard_beta_deg()[j];
      road.delta = 0.0;
      g.push_back(geometry_from_road_angles(road));
    }
  }
  return g;
}

RTable rtable_from_brdf(const std::vector<double>& f, double alpha_deg, std::string name) {
  RTable table;
  table.name = std::move(name);
  table.alpha_deg = alpha_deg;
  for (std::size_t i = 0; i < kRows; ++i) {
    const double t = standard_tan_gamma()[i];
    const double cos3 = std::pow(1.0 + t * t, -1.5);
    for (std::size_t j = 0; j < kColumns; ++j) {
      const double q = f[i * kColumns + j];
      if (!std::isfinite(q)) {
        throw InputError("the BRDF is not finite at beta = " + std::to_string(standard_beta_deg()[j]) +
                         " deg, tan(gamma) = " + std::to_string(t));
      }
      table.at(i, j) = kRScale * q * cos3;
    }
  }
  return table;
}

namespace {

// Wavelength grid and weights (summing to 1) for a spectral reduction.
void spectral_grid(const SpectralModel& model, const SpectralWeighting& w, std::vector<double>& grid,
                   std::vector<double>& weights) {
  const auto& wl = model.wavelengths();
  const double lo = wl.front(), hi = wl.back();
  switch (w.kind) {
    case SpectralWeighting::Kind::wavelength:
      grid = {w.wavelength_nm};
      weights = {1.0};
      return;
    case SpectralWeighting::Kind::band: {
      if (!(w.band_hi_nm > w.band_lo_nm)) {
        throw InputError("band " + std::to_string(w.band_lo_nm) + ":" + std::to_string(w.band_hi_nm) +
                         " nm: the upper end must exceed the lower end");
      }
      if (w.band_lo_nm < lo || w.band_hi_nm > hi) {
        throw InputError("band " + std::to_string(w.band_lo_nm) + "-" + std::to_string(w.band_hi_nm) +
                         " nm is outside the model's wavelength range " + std::to_string(lo) + "-" +
                         std::to_string(hi) + " nm (no extrapolation)");
      }
      grid.clear();
      grid.push_back(w.band_lo_nm);
      for (double l = std::floor(w.band_lo_nm) + 1.0; l < w.band_hi_nm; l += 1.0) grid.push_back(l);
      grid.push_back(w.band_hi_nm);
      weights.assign(grid.size(), 0.0);
      const double width = w.band_hi_nm - w.band_lo_nm;
      for (std::size_t k = 0; k + 1 < grid.size(); ++k) {
        const double h = 0.5 * (grid[k + 1] - grid[k]) / width;
        weights[k] += h;
        weights[k + 1] += h;
      }
      return;
    }
    case SpectralWeighting::Kind::photometric: {
      if (wl.size() < 2) {
        grid = {lo};  // effective_weighting: a single band is used as it is
        weights = {1.0};
        return;
      }
      const spectra::Spectrum& illuminant = w.illuminant ? *w.illuminant : illuminant_a();
      if (luminous_coverage(lo, hi, illuminant) < 0.99) {
        std::string bands;
        for (std::size_t k = 0; k < wl.size() && k < 12; ++k) bands += fmt::format("{}{:g}", k ? ", " : "", wl[k]);
        if (wl.size() > 12) bands += ", ...";
        throw InputError(
            fmt::format("the model's wavelengths ({} nm) hold {:.1f}% of the luminous integral under {} "
                        "(99% needed for photometric weighting): choose one band with `wavelength` NM "
                        "or a range with `band` A:B",
                        bands, 100.0 * luminous_coverage(lo, hi, illuminant), illuminant.name()));
      }
      grid = photometric_grid(lo, hi);
      if (grid.size() < 2) {
        throw InputError("the model's wavelengths " + std::to_string(lo) + "-" + std::to_string(hi) +
                         " nm do not overlap the visible range of V(lambda) (340-830 nm)");
      }
      weights = photometric_weights(grid, illuminant);
      return;
    }
  }
}

}  // namespace

SpectralWeighting effective_weighting(const SpectralModel& model, const SpectralWeighting& requested,
                                      std::string* note) {
  if (note) note->clear();
  if (!model.is_spectral() || requested.kind != SpectralWeighting::Kind::photometric ||
      model.wavelengths().size() != 1) {
    return requested;
  }
  SpectralWeighting w;
  w.kind = SpectralWeighting::Kind::wavelength;
  w.wavelength_nm = model.wavelengths().front();
  if (note) {
    *note = fmt::format(
        "single-band model ({:g} nm): the r-table is at that wavelength (photometric weighting "
        "needs a spectrum)",
        w.wavelength_nm);
  }
  return w;
}

WeightedWavelengths weighted_wavelengths(const SpectralModel& model, const SpectralWeighting& weighting) {
  WeightedWavelengths result;
  if (!model.is_spectral()) return result;
  std::vector<double> grid, weights;
  spectral_grid(model, weighting, grid, weights);
  for (std::size_t k = 0; k < grid.size(); ++k) {
    if (weights[k] == 0.0) continue;
    result.wavelengths.push_back(grid[k]);
    result.weights.push_back(weights[k]);
  }
  if (result.wavelengths.empty()) throw InputError("no wavelength to weight");
  return result;
}

std::vector<double> weighted_brdf(const SpectralModel& model, const SpectralWeighting& weighting,
                                  const std::vector<Geometry>& geometries) {
  const Model& m = model.model();
  const std::size_t np = m.parameter_count();
  std::vector<double> result(geometries.size(), 0.0);
  if (!model.is_spectral()) {
    m.evaluate_batch(geometries.data(), geometries.size(), model.parameter_table().data(), 1, result.data());
    return result;
  }
  const WeightedWavelengths w = weighted_wavelengths(model, weighting);
  std::vector<double> params;
  for (double wavelength : w.wavelengths) {
    const std::vector<double> p = model.parameters_at(wavelength);
    params.insert(params.end(), p.begin(), p.end());
  }
  const std::size_t n_sets = w.weights.size();
  if (params.size() != n_sets * np) throw InputError("no wavelength to weight");
  std::vector<double> values(geometries.size() * n_sets);
  m.evaluate_batch(geometries.data(), geometries.size(), params.data(), n_sets, values.data());
  for (std::size_t n = 0; n < geometries.size(); ++n) {
    double s = 0.0;
    for (std::size_t k = 0; k < n_sets; ++k) s += w.weights[k] * values[n * n_sets + k];
    result[n] = s;
  }
  return result;
}

RTable compute_rtable(const Model& model, const std::vector<double>& parameters, double alpha_deg) {
  if (parameters.size() != model.parameter_count()) {
    throw InputError("model '" + model.name() + "' needs " + std::to_string(model.parameter_count()) +
                     " parameters, got " + std::to_string(parameters.size()));
  }
  const std::vector<Geometry> g = rtable_geometries(alpha_deg);
  std::vector<double> f(g.size());
  model.evaluate_batch(g.data(), g.size(), parameters.data(), 1, f.data());
  return rtable_from_brdf(f, alpha_deg, model.name());
}

RTable compute_rtable(const SpectralModel& model, const SpectralWeighting& weighting, double alpha_deg) {
  const std::vector<Geometry> g = rtable_geometries(alpha_deg);
  return rtable_from_brdf(weighted_brdf(model, weighting, g), alpha_deg, model.model().name());
}

// ---- summary figures ------------------------------------------------------------------------

namespace {

// Trapezoid weights of a grid (half intervals at the ends).
template <std::size_t N>
std::array<double, N> trapezoid_weights(const std::array<double, N>& x) {
  std::array<double, N> w{};
  for (std::size_t k = 0; k + 1 < N; ++k) {
    const double h = 0.5 * (x[k + 1] - x[k]);
    w[k] += h;
    w[k + 1] += h;
  }
  return w;
}

const std::array<double, kRows>& t_weights() {
  static const auto w = trapezoid_weights(standard_tan_gamma());
  return w;
}
const std::array<double, kColumns>& beta_weights() {
  static const auto w = [] {
    std::array<double, kColumns> rad{};
    for (std::size_t j = 0; j < kColumns; ++j) rad[j] = deg_to_rad(standard_beta_deg()[j]);
    return trapezoid_weights(rad);
  }();
  return w;
}

}  // namespace

double q0(const RTable& table, Q0Region region) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < kRows; ++i) {
    const double t = standard_tan_gamma()[i];
    const double cos3 = std::pow(1.0 + t * t, -1.5);
    for (std::size_t j = 0; j < kColumns; ++j) {
      if (!table.defined(i, j)) continue;
      if (region == Q0Region::standard && !in_standard_region(i, j)) continue;
      const double w = t_weights()[i] * beta_weights()[j];
      num += table.r(i, j) * t * w;
      den += cos3 * t * w;
    }
  }
  if (!(den > 0.0)) throw InputError("Q0: no defined cell of the r-table in the averaging region");
  return num / den;
}

double s1(const RTable& table) {
  if (!table.defined(0, 0) || !table.defined(8, 0)) {
    throw InputError("S1 needs r(beta = 0, tan gamma = 0) and r(0, 2), which the table does not define");
  }
  if (table.at(0, 0) == 0.0) throw InputError("S1: r(0, 0) is zero");
  return table.at(8, 0) / table.at(0, 0);
}

double s2(const RTable& table, Q0Region region) {
  if (!table.defined(0, 0)) throw InputError("S2 needs r(beta = 0, tan gamma = 0), which the table does not define");
  if (table.at(0, 0) == 0.0) throw InputError("S2: r(0, 0) is zero");
  return q0(table, region) / table.r(0, 0);
}

double qd(const RTable& table) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < kRows; ++i) {
    const double t = standard_tan_gamma()[i];
    const double cos3 = std::pow(1.0 + t * t, -1.5);
    const double sin_g = t / std::sqrt(1.0 + t * t);
    for (std::size_t j = 0; j < kColumns; ++j) {
      if (!table.defined(i, j)) continue;
      const double w = t_weights()[i] * beta_weights()[j];
      num += table.r(i, j) * sin_g * w;
      den += cos3 * sin_g * w;
    }
  }
  if (!(den > 0.0)) throw InputError("Qd: no defined cell of the r-table");
  return num / den;
}

const std::vector<RoadClass>& road_classes(ClassSystem system) {
  const double inf = std::numeric_limits<double>::infinity();
  // name, standard Q0, S1 limits [lower, upper); the first class has no lower limit (S1 < upper).
  static const std::vector<RoadClass> r_classes = {
      {"R1", 0.10, -inf, 0.42}, {"R2", 0.07, 0.42, 0.85}, {"R3", 0.07, 0.85, 1.35}, {"R4", 0.08, 1.35, inf}};
  static const std::vector<RoadClass> n_classes = {
      {"N1", 0.10, -inf, 0.28}, {"N2", 0.07, 0.28, 0.60}, {"N3", 0.07, 0.60, 1.30}, {"N4", 0.08, 1.30, inf}};
  static const std::vector<RoadClass> c_classes = {{"C1", 0.10, -inf, 0.40}, {"C2", 0.07, 0.40, inf}};
  switch (system) {
    case ClassSystem::N:
      return n_classes;
    case ClassSystem::C:
      return c_classes;
    case ClassSystem::R:
      break;
  }
  return r_classes;
}

RoadClass classify(double s1_value, ClassSystem system) {
  if (!std::isfinite(s1_value)) throw InputError("cannot classify: S1 is not finite");
  const std::vector<RoadClass>& classes = road_classes(system);
  for (const RoadClass& c : classes) {
    if (s1_value < c.s1_upper) return c;
  }
  return classes.back();
}

ClassSystem class_system_from_name(const std::string& name, const std::string& field) {
  std::string upper = name;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return parse_name<ClassSystem>(upper, field);
}

RTableSummary summarize(const RTable& table, Q0Region region) {
  RTableSummary s;
  s.defined_cells = table.defined_count();
  s.q0 = q0(table, region);
  s.s1 = s1(table);
  s.r00 = table.r(0, 0);
  s.s2 = s.q0 / s.r00;
  s.qd = qd(table);
  s.r_class = classify(s.s1, ClassSystem::R);
  s.n_class = classify(s.s1, ClassSystem::N);
  s.c_class = classify(s.s1, ClassSystem::C);
  return s;
}

RTableComparison compare(const RTable& a, const RTable& b, Q0Region region) {
  RTableComparison c;
  double sum = 0.0;
  for (std::size_t i = 0; i < kRows; ++i) {
    for (std::size_t j = 0; j < kColumns; ++j) {
      const bool da = a.defined(i, j), db = b.defined(i, j);
      if (da && !db) ++c.only_in_a;
      if (db && !da) ++c.only_in_b;
      if (!da || !db || b.at(i, j) == 0.0) continue;
      const double rel = std::abs(a.at(i, j) - b.at(i, j)) / std::abs(b.at(i, j));
      sum += rel;
      ++c.compared_cells;
      if (rel > c.max_relative || c.compared_cells == 1) {
        c.max_relative = rel;
        c.max_row = i;
        c.max_column = j;
      }
    }
  }
  if (c.compared_cells == 0) throw InputError("the two r-tables have no defined cell in common");
  c.mean_relative = sum / static_cast<double>(c.compared_cells);
  c.q0_difference = q0(a, region) - q0(b, region);
  c.s1_difference = s1(a) - s1(b);
  return c;
}

}  // namespace roadbrdf::photometry
