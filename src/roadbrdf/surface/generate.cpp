#include "roadbrdf/surface/generate.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"

namespace roadbrdf::surface {

SampleRecipe recipe_from_formulation(const roadbrdf::Formulation& f) {
  SampleRecipe r;
  r.name = f.name;
  if (!f.mastic) {
    throw InputError("formulation '" + f.name +
                     "' has no \"mastic\" fit: the matrix of the virtual sample needs the measured mastic");
  }
  r.matrix.name = f.mastic->name.empty() ? std::string("mastic") : f.mastic->name;
  r.matrix.fit = f.mastic->fit;
  r.matrix.fit_path = f.mastic->fit_path;
  r.matrix.fit_model = f.mastic->fit_model;
  double total_volume = 0.0;
  for (const auto& c : f.components) total_volume += c.mass_percent / c.density;
  for (const auto& c : f.components) {
    if (!roadbrdf::is_coarse(f, c)) continue;
    GrainClass g;
    g.material.name = c.name;
    g.material.fit = c.fit;
    g.material.fit_path = c.fit_path;
    g.material.fit_model = c.fit_model;
    g.d_min_mm = *c.d_min;
    g.d_max_mm = *c.d_max;
    g.volume_fraction = (c.mass_percent / c.density) / total_volume;
    r.classes.push_back(g);
  }
  if (r.classes.empty()) {
    throw InputError("formulation '" + f.name + "' has no coarse aggregate class (d_min >= " +
                     std::to_string(f.coarse_min_size_mm) + " mm): nothing to place in the matrix");
  }
  return r;
}

namespace {

// Height of the top of the ellipsoid above its centre at horizontal offset (dx, dy), if any.
bool top_offset(const Mat3& Q, double dx, double dy, double& dz) {
  const double B = Q[2] * dx + Q[5] * dy;  // Q_xz dx + Q_yz dy (Q symmetric)
  const double C = Q[0] * dx * dx + 2.0 * Q[1] * dx * dy + Q[4] * dy * dy - 1.0;
  const double disc = B * B - Q[8] * C;
  if (disc < 0.0) return false;
  dz = (-B + std::sqrt(disc)) / Q[8];
  return true;
}

double mpd_of_level(const std::vector<double>& top_nodes, double level, HeightField& f) {
  for (std::size_t k = 0; k < top_nodes.size(); ++k) f.heights[k] = std::max(level, top_nodes[k]);
  return texture_statistics(f).mpd_mm;
}

}  // namespace

void validate(const GeneratorSettings& s) {
  if (!(s.cell_size_mm >= 0.005 && s.cell_size_mm <= 10.0)) {
    throw FieldError("cell_mm", fmt::format("must be in [0.005, 10] mm, got {}", s.cell_size_mm));
  }
  if (!(s.size_mm > 0.0 && std::isfinite(s.size_mm))) {
    throw FieldError("size_mm", fmt::format("must be a positive length [mm], got {}", s.size_mm));
  }
  const double n = std::round(s.size_mm / s.cell_size_mm);
  if (n < 8) throw FieldError("size_mm", "the sample must span at least 8 cells");
  if (std::fabs(n * s.cell_size_mm - s.size_mm) > 1e-6 * s.size_mm) {
    throw FieldError("size_mm",
                     fmt::format("must be a whole number of cells of {} mm, got {}", s.cell_size_mm, s.size_mm));
  }
  if (n * n > 4e7) throw FieldError("size_mm", "more than 4e7 cells: use a larger cell_mm or a smaller sample");
  if (!(s.matrix_level >= 0.0 && s.matrix_level <= 1.0)) {
    throw FieldError("matrix_level",
                     fmt::format("must be in [0, 1] (a fraction of the slab thickness), got {}", s.matrix_level));
  }
  if (s.target_mpd_mm && s.mastic_fraction) {
    throw FieldError("mastic_fraction", "matrix_level, target_mpd and mastic_fraction exclude each other");
  }
  if (s.target_mpd_mm && !(*s.target_mpd_mm > 0.0)) {
    throw FieldError("target_mpd", fmt::format("must be > 0 mm, got {}", *s.target_mpd_mm));
  }
  if (s.mastic_fraction && !(*s.mastic_fraction > 0.0 && *s.mastic_fraction < 1.0)) {
    throw FieldError("mastic_fraction", fmt::format("must be in (0, 1) (exclusive), got {}", *s.mastic_fraction));
  }
}

namespace {

// The slab thickness T: the largest grain size, after checking the classes.
double slab_thickness(const SampleRecipe& recipe, double L) {
  if (recipe.classes.empty()) throw InputError("surface: no grain class");
  if (recipe.classes.size() > 60000) throw InputError("surface: too many classes");
  double T = 0.0;
  for (const auto& c : recipe.classes) {
    if (!(c.d_min_mm > 0.0 && c.d_max_mm >= c.d_min_mm))
      throw InputError("surface: invalid size class of " + c.material.name);
    if (!(c.volume_fraction >= 0.0 && c.volume_fraction < 1.0)) throw InputError("surface: invalid volume fraction");
    T = std::max(T, c.d_max_mm);
  }
  if (T > L / 2) throw InputError("surface: the sample must be at least twice the largest grain size");
  return T;
}

// Packs all classes together, largest first at equal progress (packing.h), into out.grains with the
// target and achieved volume fractions, grain counts and a note when the packing jammed.
void pack_grains(const SampleRecipe& recipe, const GeneratorSettings& s, double L, double T, GeneratedSample& out) {
  const std::size_t K = recipe.classes.size();
  out.target_volume_fraction.resize(K);
  out.achieved_volume_fraction.assign(K, 0.0);
  out.grain_count.assign(K, 0);
  std::vector<std::size_t> order(K);
  for (std::size_t k = 0; k < K; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return recipe.classes[a].d_max_mm > recipe.classes[b].d_max_mm;
  });
  const double slab_volume = L * L * T;
  std::vector<PackingClass> pack_classes;
  pack_classes.reserve(K);
  for (std::size_t k : order) {
    const GrainClass& c = recipe.classes[k];
    out.target_volume_fraction[k] = c.volume_fraction;
    pack_classes.push_back({c.d_min_mm, c.d_max_mm, c.volume_fraction * slab_volume});
  }
  PackingSettings ps;
  ps.period_mm = L;
  ps.thickness_mm = T;
  ps.bottom_mm = -2.0 * T;  // room below the slab for the deposit to grow into
  ps.layer_bottom_mm = 0.0;
  ps.seed = s.seed;
  ps.elongation_min = s.elongation_min;
  ps.elongation_max = s.elongation_max;
  ps.flatness_min = s.flatness_min;
  ps.flatness_max = s.flatness_max;
  ps.insertion_attempts = s.max_failures;
  ps.deposition_tries = s.deposition_tries;
  ps.settle_moves = s.settle_moves;
  ps.progress = s.progress;
  const PackingResult packed = pack_ellipsoids(pack_classes, ps);
  // Grains entirely below the slab never reach the surface: dropped.
  for (Ellipsoid e : packed.grains) {
    if (e.z + std::sqrt(e.shape()[8]) <= 0.0) continue;
    e.cls = static_cast<int>(order[e.cls]);
    ++out.grain_count[e.cls];
    out.grains.push_back(e);
  }
  for (std::size_t p = 0; p < K; ++p) {
    out.achieved_volume_fraction[order[p]] = packed.layer_volume_mm3[p] / slab_volume;
  }
  out.targets_reached = packed.reached;
  out.deposition = packed.deposition;
  if (packed.reached) return;
  double target_total = 0.0, achieved_total = 0.0;
  for (std::size_t k = 0; k < K; ++k) {
    target_total += out.target_volume_fraction[k];
    achieved_total += out.achieved_volume_fraction[k];
  }
  std::ostringstream note;
  note << "packing jammed at grain volume fraction " << achieved_total << " of the slab (target " << target_total
       << "): all classes scaled down together, achieved / target:";
  for (std::size_t k = 0; k < K; ++k) {
    note << " " << recipe.classes[k].material.name << " " << out.achieved_volume_fraction[k] << " / "
         << out.target_volume_fraction[k] << (k + 1 < K ? ";" : "");
  }
  out.notes.push_back(note.str());
}

// The grain tops rasterised at the nodes (heights) and at the cell centres (materials): the highest
// grain surface there and its class (-1: no grain).
struct GrainTops {
  std::vector<double> nodes, centres;
  std::vector<int> node_class, centre_class;
};

GrainTops rasterise(const std::vector<Ellipsoid>& grains, int n, double h) {
  const double lowest = -std::numeric_limits<double>::infinity();
  const std::size_t cells = static_cast<std::size_t>(n) * n;
  GrainTops t{std::vector<double>(cells, lowest), std::vector<double>(cells, lowest), std::vector<int>(cells, -1),
              std::vector<int>(cells, -1)};
  for (const Ellipsoid& g : grains) {
    const Mat3 A = g.shape(), Q = g.inverse_shape();
    const double wx = std::sqrt(A[0]), wy = std::sqrt(A[4]);
    for (int pass = 0; pass < 2; ++pass) {
      const double off = pass == 0 ? 0.0 : 0.5;  // nodes, then cell centres
      std::vector<double>& top = pass == 0 ? t.nodes : t.centres;
      std::vector<int>& cls = pass == 0 ? t.node_class : t.centre_class;
      const long i0 = static_cast<long>(std::floor((g.x - wx) / h - off)),
                 i1 = static_cast<long>(std::ceil((g.x + wx) / h - off));
      const long j0 = static_cast<long>(std::floor((g.y - wy) / h - off)),
                 j1 = static_cast<long>(std::ceil((g.y + wy) / h - off));
      for (long j = j0; j <= j1; ++j) {
        for (long i = i0; i <= i1; ++i) {
          double dz;
          if (!top_offset(Q, (i + off) * h - g.x, (j + off) * h - g.y, dz)) continue;
          const long iw = ((i % n) + n) % n, jw = ((j % n) + n) % n;
          const std::size_t idx = static_cast<std::size_t>(jw) * n + iw;
          if (g.z + dz > top[idx]) {
            top[idx] = g.z + dz;
            cls[idx] = g.cls;
          }
        }
      }
    }
  }
  return t;
}

// Material map at a mastic level; returns the number of mastic cells. A cell is grain where a grain pokes
// out of the mastic at its centre; else, the mastic being the flat fill at the level, a cell whose mesh
// rises above it (a node on a grain) is the flank of that grain (class of the highest such node); else
// mastic. So a cell is mastic exactly when its centre and its 4 nodes are at or below the level (generate.h).
long label_cells(const GrainTops& tops, double level, HeightField& f) {
  long mastic_cells = 0;
  for (int j = 0; j < f.ny; ++j) {
    for (int i = 0; i < f.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * f.nx + i;
      int cls = tops.centres[k] > level ? tops.centre_class[k] : -1;
      if (cls < 0) {
        double highest = level;
        for (const std::size_t node : {f.index(i, j), f.index(i + 1, j), f.index(i, j + 1), f.index(i + 1, j + 1)}) {
          if (tops.nodes[node] > highest) {
            highest = tops.nodes[node];
            cls = tops.node_class[node];
          }
        }
      }
      f.material[k] = static_cast<std::uint16_t>(cls + 1);
      if (cls < 0) ++mastic_cells;
    }
  }
  return mastic_cells;
}

double mastic_fraction_at(const GrainTops& tops, double level, HeightField& f) {
  return static_cast<double>(label_cells(tops, level, f)) / (static_cast<double>(f.nx) * f.ny);
}

// The mastic level in [0, T] giving the target MPD (bisection: the MPD decreases as the mastic rises).
double level_for_mpd(const GrainTops& tops, double T, double target_mpd, HeightField& f) {
  double lo = 0.0, hi = T;
  const double mpd_lo = mpd_of_level(tops.nodes, lo, f);
  if (mpd_lo < target_mpd) {
    // Not clamped to the nearest reachable level: the user asked for a texture this packing cannot give.
    std::ostringstream e;
    e << "surface: target MPD " << target_mpd << " mm not reachable with this packing (at most " << mpd_lo
      << " mm, with the mastic at the bottom of the " << T << " mm slab; it decreases as the mastic rises)";
    throw InputError(e.str());
  }
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mpd_of_level(tops.nodes, mid, f) > target_mpd) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

// The mastic level in [0, T] whose exposed mastic fraction is within `tol` of the target (bisection:
// the fraction is non-decreasing in the level, generate.h); an error when no level reaches it.
double level_for_mastic_fraction(const GrainTops& tops, double T, double target, double tol, HeightField& f) {
  double lo = 0.0, hi = T;
  const double f_lo = mastic_fraction_at(tops, lo, f), f_hi = mastic_fraction_at(tops, hi, f);
  auto range = [&] {
    std::ostringstream r;
    r << "reachable with this packing: " << f_lo << " (mastic at the bottom of the " << T << " mm slab) to " << f_hi
      << " (at its top), tolerance " << tol;
    return r.str();
  };
  if (target < f_lo - tol || target > f_hi + tol) {
    std::ostringstream e;
    e << "surface: exposed mastic fraction " << target << " not reachable (" << range() << ")";
    throw InputError(e.str());
  }
  if (target <= f_lo) return lo;
  if (target >= f_hi) return hi;
  // Invariant: fraction(lo) < target <= fraction(hi).
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mastic_fraction_at(tops, mid, f) < target) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const double a_lo = mastic_fraction_at(tops, lo, f), a_hi = mastic_fraction_at(tops, hi, f);
  const double level = target - a_lo <= a_hi - target ? lo : hi;
  const double achieved = level == lo ? a_lo : a_hi;
  if (std::fabs(achieved - target) > tol) {
    std::ostringstream e;
    e << "surface: exposed mastic fraction " << target << " not reachable within " << tol
      << ": the fraction jumps from " << a_lo << " to " << a_hi << " at the mastic level " << level
      << " mm (cells whose grain tops are at equal heights; " << range() << ")";
    throw InputError(e.str());
  }
  return level;
}

std::string describe(const SampleRecipe& recipe, const GeneratorSettings& s, const GeneratedSample& out, double L) {
  const double T = out.slab_thickness_mm;
  std::ostringstream d;
  d << "virtual sample of " << recipe.name << ": " << out.grains.size()
    << " ellipsoidal grains (random orientation, b/a in [" << s.elongation_min << ", " << s.elongation_max
    << "], c/b in [" << s.flatness_min << ", " << s.flatness_max
    << "]) packed without overlap, all classes together in proportion, by "
    << (out.deposition ? "deposition against the roller's plane with settling (random sequential addition jammed)"
                       : "random sequential addition")
    << " in a " << T << " mm slab, periodic " << L << " mm x " << L << " mm, mastic level " << out.matrix_level_mm
    << " mm";
  if (s.mastic_fraction) {
    d << " (chosen for an exposed mastic fraction of " << *s.mastic_fraction << ": achieved " << out.mastic_fraction
      << ", tolerance " << out.mastic_fraction_tolerance << ")";
  }
  d << ", seed " << s.seed << ". Classes (target / achieved volume fraction of the slab"
    << (out.targets_reached ? "" : "; targets NOT reached, classes scaled down together") << "):";
  for (std::size_t k = 0; k < recipe.classes.size(); ++k) {
    d << " " << recipe.classes[k].material.name << " " << out.target_volume_fraction[k] << " / "
      << out.achieved_volume_fraction[k] << " (" << out.grain_count[k] << " grains);";
  }
  return d.str();
}

}  // namespace

GeneratedSample generate_sample(const SampleRecipe& recipe, const GeneratorSettings& s) {
  validate(s);
  const int n = static_cast<int>(std::lround(s.size_mm / s.cell_size_mm));
  const double L = n * s.cell_size_mm;
  GeneratedSample out;
  const double T = slab_thickness(recipe, L);
  out.slab_thickness_mm = T;
  pack_grains(recipe, s, L, T, out);
  const GrainTops tops = rasterise(out.grains, n, s.cell_size_mm);

  HeightField& f = out.field;
  f.name = recipe.name;
  f.cell_size_mm = s.cell_size_mm;
  f.nx = f.ny = n;
  f.heights.assign(tops.nodes.size(), 0.0);
  f.material.assign(tops.nodes.size(), 0);
  f.materials.push_back(recipe.matrix);
  for (const auto& c : recipe.classes) f.materials.push_back(c.material);

  double level = s.matrix_level * T;
  if (s.target_mpd_mm) level = level_for_mpd(tops, T, *s.target_mpd_mm, f);
  if (s.mastic_fraction) {
    out.mastic_fraction_tolerance = std::max(1e-3, 1.0 / (static_cast<double>(n) * n));
    level = level_for_mastic_fraction(tops, T, *s.mastic_fraction, out.mastic_fraction_tolerance, f);
  }
  out.matrix_level_mm = level;
  for (std::size_t k = 0; k < tops.nodes.size(); ++k) f.heights[k] = std::max(level, tops.nodes[k]);
  out.mastic_fraction = mastic_fraction_at(tops, level, f);
  f.description = describe(recipe, s, out, L);
  return out;
}

HeightField make_gaussian_slope_surface(const MaterialSpec& material, double sigma_rad, int n, double cell_size_mm,
                                        std::uint64_t seed, int waves) {
  if (!(sigma_rad > 0.0 && sigma_rad < 1.3)) throw InputError("surface: slope sigma must be in (0, 1.3) rad");
  if (n < 32) throw InputError("surface: the rough validation surface needs at least 32 cells");
  // Lattice wave vectors (p, q) with wavelength n / |(p, q)| between 6 and 14 cells.
  std::vector<std::pair<int, int>> lattice;
  const double kmin = n / 14.0, kmax = n / 6.0;
  const int r = static_cast<int>(std::ceil(kmax));
  for (int q = 0; q <= r; ++q) {
    for (int p = -r; p <= r; ++p) {
      if (q == 0 && p <= 0) continue;  // one of each +-k pair
      const double k = std::sqrt(double(p * p + q * q));
      if (k >= kmin && k <= kmax) lattice.emplace_back(p, q);
    }
  }
  Rng rng(seed);
  HeightField f;
  f.name = "gaussian-slopes " + material.name;
  f.cell_size_mm = cell_size_mm;
  f.nx = f.ny = n;
  f.heights.assign(static_cast<std::size_t>(n) * n, 0.0);
  f.material.assign(f.heights.size(), 0);
  f.materials = {material};
  for (int w = 0; w < waves; ++w) {
    const auto [p, q] = lattice[static_cast<std::size_t>(rng.below(lattice.size()))];
    const double phase = 2.0 * kPi * rng.uniform();
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        f.heights[static_cast<std::size_t>(j) * n + i] += std::cos(2.0 * kPi * (p * i + q * j) / n + phase);
      }
    }
  }
  double s2 = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double sx = f.height(i + 1, j) - f.height(i, j), sy = f.height(i, j + 1) - f.height(i, j);
      s2 += 0.5 * (sx * sx + sy * sy);
    }
  }
  const double scale = std::tan(sigma_rad) * cell_size_mm / std::sqrt(s2 / (double(n) * n));
  for (double& z : f.heights) z *= scale;
  std::ostringstream d;
  d << "isotropic random rough surface (spectral synthesis, " << waves << " waves of 6-14 cells), rms facet slope "
    << "tan(" << sigma_rad << " rad) along x and y, seed " << seed;
  f.description = d.str();
  return f;
}

nlohmann::json GeneratedSample::to_json() const {
  return {{"target_volume_fraction", target_volume_fraction},
          {"achieved_volume_fraction", achieved_volume_fraction},
          {"grain_count", grain_count},
          {"targets_reached", targets_reached},
          {"deposition", deposition},
          {"slab_thickness_mm", slab_thickness_mm},
          {"matrix_level_mm", matrix_level_mm},
          {"notes", notes}};
}

}  // namespace roadbrdf::surface
