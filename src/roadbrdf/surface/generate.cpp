#include "roadbrdf/surface/generate.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

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

class Uniform {
 public:
  explicit Uniform(std::uint64_t seed) : engine_(seed) {}
  double operator()() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

 private:
  std::mt19937_64 engine_;
};

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

GeneratedSample generate_sample(const SampleRecipe& recipe, const GeneratorSettings& s) {
  validate(s);
  const int n = static_cast<int>(std::lround(s.size_mm / s.cell_size_mm));
  if (recipe.classes.empty()) throw InputError("surface: no grain class");
  if (recipe.classes.size() > 60000) throw InputError("surface: too many classes");
  const double L = n * s.cell_size_mm;
  double T = 0.0;
  for (const auto& c : recipe.classes) {
    if (!(c.d_min_mm > 0.0 && c.d_max_mm >= c.d_min_mm))
      throw InputError("surface: invalid size class of " + c.material.name);
    if (!(c.volume_fraction >= 0.0 && c.volume_fraction < 1.0)) throw InputError("surface: invalid volume fraction");
    T = std::max(T, c.d_max_mm);
  }
  if (T > L / 2) throw InputError("surface: the sample must be at least twice the largest grain size");

  GeneratedSample out;
  out.slab_thickness_mm = T;
  const std::size_t K = recipe.classes.size();
  out.target_volume_fraction.resize(K);
  out.achieved_volume_fraction.assign(K, 0.0);
  out.grain_count.assign(K, 0);
  // Pack all classes together, largest first at equal progress (packing.h).
  std::vector<std::size_t> order(K);
  for (std::size_t k = 0; k < K; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return recipe.classes[a].d_max_mm > recipe.classes[b].d_max_mm;
  });
  const double slab_volume = L * L * T;
  std::vector<PackingClass> pack_classes;
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
  std::vector<Ellipsoid> grains;
  for (Ellipsoid e : packed.grains) {
    if (e.z + std::sqrt(e.shape()[8]) <= 0.0) continue;
    e.cls = static_cast<int>(order[e.cls]);
    ++out.grain_count[e.cls];
    grains.push_back(e);
  }
  for (std::size_t p = 0; p < K; ++p) {
    out.achieved_volume_fraction[order[p]] = packed.layer_volume_mm3[p] / slab_volume;
  }
  out.targets_reached = packed.reached;
  out.deposition = packed.deposition;
  if (!packed.reached) {
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
  out.grains = grains;

  // Rasterise the grain tops at the nodes (heights) and at the cell centres (materials).
  const double h = s.cell_size_mm;
  const double lowest = -std::numeric_limits<double>::infinity();
  std::vector<double> top_nodes(static_cast<std::size_t>(n) * n, lowest), top_centres(top_nodes.size(), lowest);
  std::vector<int> centre_class(top_nodes.size(), -1), node_class(top_nodes.size(), -1);
  for (const Ellipsoid& g : grains) {
    const Mat3 A = g.shape(), Q = g.inverse_shape();
    const double wx = std::sqrt(A[0]), wy = std::sqrt(A[4]);
    for (int pass = 0; pass < 2; ++pass) {
      const double off = pass == 0 ? 0.0 : 0.5;  // nodes, then cell centres
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
          const double z = g.z + dz;
          if (pass == 0) {
            if (z > top_nodes[idx]) {
              top_nodes[idx] = z;
              node_class[idx] = g.cls;
            }
          } else if (z > top_centres[idx]) {
            top_centres[idx] = z;
            centre_class[idx] = g.cls;
          }
        }
      }
    }
  }

  HeightField& f = out.field;
  f.name = recipe.name;
  f.cell_size_mm = h;
  f.nx = f.ny = n;
  f.heights.assign(top_nodes.size(), 0.0);
  f.material.assign(top_nodes.size(), 0);
  f.materials.push_back(recipe.matrix);
  for (const auto& c : recipe.classes) f.materials.push_back(c.material);

  // Material map at a mastic level; returns the number of mastic cells. A cell is grain where a grain pokes
  // out of the mastic at its centre; else, the mastic being the flat fill at the level, a cell whose mesh
  // rises above it (a node on a grain) is the flank of that grain (class of the highest such node); else
  // mastic. So a cell is mastic exactly when its centre and its 4 nodes are at or below the level (generate.h).
  auto label_cells = [&](double level) {
    long mastic_cells = 0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * n + i;
        int cls = top_centres[k] > level ? centre_class[k] : -1;
        if (cls < 0) {
          double highest = level;
          for (const std::size_t node : {f.index(i, j), f.index(i + 1, j), f.index(i, j + 1), f.index(i + 1, j + 1)}) {
            if (top_nodes[node] > highest) {
              highest = top_nodes[node];
              cls = node_class[node];
            }
          }
        }
        f.material[k] = static_cast<std::uint16_t>(cls + 1);
        if (cls < 0) ++mastic_cells;
      }
    }
    return mastic_cells;
  };
  const double cells = static_cast<double>(n) * n;
  auto mastic_fraction_at = [&](double level) { return static_cast<double>(label_cells(level)) / cells; };

  double level = s.matrix_level * T;
  if (s.target_mpd_mm) {
    double lo = 0.0, hi = T;  // MPD decreases as the matrix rises
    const double mpd_lo = mpd_of_level(top_nodes, lo, f);
    if (mpd_lo < *s.target_mpd_mm) {
      // Not clamped to the nearest reachable level: the user asked for a texture this packing cannot give.
      std::ostringstream e;
      e << "surface: target MPD " << *s.target_mpd_mm << " mm not reachable with this packing (at most " << mpd_lo
        << " mm, with the mastic at the bottom of the " << T << " mm slab; it decreases as the mastic rises)";
      throw InputError(e.str());
    } else {
      for (int it = 0; it < 50; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mpd_of_level(top_nodes, mid, f) > *s.target_mpd_mm) {
          lo = mid;
        } else {
          hi = mid;
        }
      }
      level = 0.5 * (lo + hi);
    }
  }
  if (s.mastic_fraction) {
    const double target = *s.mastic_fraction;
    const double tol = std::max(1e-3, 1.0 / cells);
    out.mastic_fraction_tolerance = tol;
    double lo = 0.0, hi = T;  // the fraction is non-decreasing in the level (generate.h)
    const double f_lo = mastic_fraction_at(lo), f_hi = mastic_fraction_at(hi);
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
    if (target <= f_lo) {
      level = lo;
    } else if (target >= f_hi) {
      level = hi;
    } else {
      // Invariant: fraction(lo) < target <= fraction(hi).
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mastic_fraction_at(mid) < target) {
          lo = mid;
        } else {
          hi = mid;
        }
      }
      const double a_lo = mastic_fraction_at(lo), a_hi = mastic_fraction_at(hi);
      level = target - a_lo <= a_hi - target ? lo : hi;
      const double achieved = level == lo ? a_lo : a_hi;
      if (std::fabs(achieved - target) > tol) {
        std::ostringstream e;
        e << "surface: exposed mastic fraction " << target << " not reachable within " << tol
          << ": the fraction jumps from " << a_lo << " to " << a_hi << " at the mastic level " << level
          << " mm (cells whose grain tops are at equal heights; " << range() << ")";
        throw InputError(e.str());
      }
    }
  }
  out.matrix_level_mm = level;
  for (std::size_t k = 0; k < top_nodes.size(); ++k) f.heights[k] = std::max(level, top_nodes[k]);
  out.mastic_fraction = mastic_fraction_at(level);
  std::ostringstream d;
  d << "virtual sample of " << recipe.name << ": " << grains.size()
    << " ellipsoidal grains (random orientation, b/a in [" << s.elongation_min << ", " << s.elongation_max
    << "], c/b in [" << s.flatness_min << ", " << s.flatness_max
    << "]) packed without overlap, all classes together in proportion, by "
    << (out.deposition ? "deposition against the roller's plane with settling (random sequential addition jammed)"
                       : "random sequential addition")
    << " in a " << T << " mm slab, periodic " << L << " mm x " << L << " mm, mastic level " << level << " mm";
  if (s.mastic_fraction) {
    d << " (chosen for an exposed mastic fraction of " << *s.mastic_fraction << ": achieved " << out.mastic_fraction
      << ", tolerance " << out.mastic_fraction_tolerance << ")";
  }
  d << ", seed " << s.seed << ". Classes (target / achieved volume fraction of the slab"
    << (out.targets_reached ? "" : "; targets NOT reached, classes scaled down together") << "):";
  for (std::size_t k = 0; k < K; ++k) {
    d << " " << recipe.classes[k].material.name << " " << out.target_volume_fraction[k] << " / "
      << out.achieved_volume_fraction[k] << " (" << out.grain_count[k] << " grains);";
  }
  f.description = d.str();
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
  Uniform u(seed);
  HeightField f;
  f.name = "gaussian-slopes " + material.name;
  f.cell_size_mm = cell_size_mm;
  f.nx = f.ny = n;
  f.heights.assign(static_cast<std::size_t>(n) * n, 0.0);
  f.material.assign(f.heights.size(), 0);
  f.materials = {material};
  for (int w = 0; w < waves; ++w) {
    const auto [p, q] = lattice[static_cast<std::size_t>(u() * lattice.size()) % lattice.size()];
    const double phase = 2.0 * kPi * u();
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

}  // namespace roadbrdf::surface
