#include "roadbrdf/surface/generate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::surface {

SampleRecipe recipe_from_formulation(const mixing::Formulation& f) {
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
    if (!mixing::is_coarse(f, c)) continue;
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

using Mat3 = std::array<double, 9>;  // row-major

struct Grain {
  double x, y, z;
  Mat3 A;  // R diag(a^2, b^2, c^2) R^T  (support function: h(u) = sqrt(u^T A u))
  Mat3 Q;  // R diag(1/a^2, 1/b^2, 1/c^2) R^T  (implicit surface: d^T Q d = 1)
  double bound;  // largest semi-axis
  int cls;
};

class Uniform {
 public:
  explicit Uniform(std::uint64_t seed) : engine_(seed) {}
  double operator()() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

 private:
  std::mt19937_64 engine_;
};

double quad(const Mat3& M, double x, double y, double z) {
  return x * (M[0] * x + M[1] * y + M[2] * z) + y * (M[3] * x + M[4] * y + M[5] * z) +
         z * (M[6] * x + M[7] * y + M[8] * z);
}

// Random rotation matrix (uniform quaternion, Shoemake 1992).
Mat3 random_rotation(Uniform& u) {
  const double u1 = u(), u2 = u(), u3 = u();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double qx = a * std::sin(2 * kPi * u2), qy = a * std::cos(2 * kPi * u2);
  const double qz = b * std::sin(2 * kPi * u3), qw = b * std::cos(2 * kPi * u3);
  return {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw),
          2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw),
          2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)};
}

Mat3 r_diag_rt(const Mat3& R, double d0, double d1, double d2) {
  Mat3 M{};
  const double d[3] = {d0, d1, d2};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k) s += R[r * 3 + k] * d[k] * R[c * 3 + k];
      M[r * 3 + c] = s;
    }
  }
  return M;
}

double wrap_delta(double d, double L) {
  d = std::fmod(d, L);
  if (d > 0.5 * L) d -= L;
  if (d < -0.5 * L) d += L;
  return d;
}

bool overlaps(const Grain& a, const Grain& b, double L) {
  const double dx = wrap_delta(b.x - a.x, L), dy = wrap_delta(b.y - a.y, L), dz = b.z - a.z;
  const double dist2 = dx * dx + dy * dy + dz * dz;
  const double rb = a.bound + b.bound;
  if (dist2 > rb * rb) return false;
  if (dist2 < 1e-24) return true;
  const double dist = std::sqrt(dist2);
  const double ux = dx / dist, uy = dy / dist, uz = dz / dist;
  const double ha = std::sqrt(quad(a.A, ux, uy, uz)), hb = std::sqrt(quad(b.A, ux, uy, uz));
  return dist <= ha + hb;
}

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

GeneratedSample generate_sample(const SampleRecipe& recipe, const GeneratorSettings& s) {
  if (!(s.size_mm > 0.0) || !(s.cell_size_mm > 0.0)) throw InputError("surface: size and cell size must be > 0");
  const int n = static_cast<int>(std::lround(s.size_mm / s.cell_size_mm));
  if (n < 8) throw InputError("surface: the sample must span at least 8 cells");
  if (std::fabs(n * s.cell_size_mm - s.size_mm) > 1e-6 * s.size_mm) {
    throw InputError("surface: the size must be a whole number of cells");
  }
  if (static_cast<long>(n) * n > 40'000'000L) throw InputError("surface: more than 4e7 cells; use a larger --cell");
  if (!(s.matrix_level >= 0.0 && s.matrix_level <= 1.0)) throw InputError("surface: matrix level must be in [0, 1]");
  if (recipe.classes.empty()) throw InputError("surface: no grain class");
  if (recipe.classes.size() > 60000) throw InputError("surface: too many classes");
  const double L = n * s.cell_size_mm;
  double T = 0.0;
  for (const auto& c : recipe.classes) {
    if (!(c.d_min_mm > 0.0 && c.d_max_mm >= c.d_min_mm)) throw InputError("surface: invalid size class of " + c.material.name);
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
  Uniform u(s.seed);
  std::vector<Grain> grains;
  // Largest class first (random sequential addition packs polydisperse grains better that way).
  std::vector<std::size_t> order(K);
  for (std::size_t k = 0; k < K; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return recipe.classes[a].d_max_mm > recipe.classes[b].d_max_mm; });
  const double slab_volume = L * L * T;
  for (std::size_t k : order) {
    const GrainClass& c = recipe.classes[k];
    out.target_volume_fraction[k] = c.volume_fraction;
    const double target = c.volume_fraction * slab_volume;
    double placed = 0.0;
    long failures = 0;
    while (placed < target) {
      // Sieve size with the class mass uniform over [d_min, d_max]: number density ~ d^-3.
      const double v = u();
      const double d = c.d_max_mm > c.d_min_mm
                           ? 1.0 / std::sqrt(1.0 / (c.d_min_mm * c.d_min_mm) -
                                             v * (1.0 / (c.d_min_mm * c.d_min_mm) - 1.0 / (c.d_max_mm * c.d_max_mm)))
                           : c.d_min_mm;
      const double b = 0.5 * d;
      const double a = b / (s.elongation_min + (s.elongation_max - s.elongation_min) * u());
      const double cc = b * (s.flatness_min + (s.flatness_max - s.flatness_min) * u());
      const Mat3 R = random_rotation(u);
      Grain g;
      g.A = r_diag_rt(R, a * a, b * b, cc * cc);
      g.Q = r_diag_rt(R, 1.0 / (a * a), 1.0 / (b * b), 1.0 / (cc * cc));
      g.bound = a;
      g.cls = static_cast<int>(k);
      g.x = u() * L;
      g.y = u() * L;
      // Inside the slab vertically (compaction by the roller: no grain above the top plane z = T);
      // a grain taller than the slab touches the top plane and reaches below the slab.
      const double hz = std::sqrt(g.A[8]);
      g.z = hz >= 0.5 * T ? T - hz : hz + u() * (T - 2.0 * hz);
      bool ok = true;
      for (const Grain& o : grains) {
        if (overlaps(o, g, L)) {
          ok = false;
          break;
        }
      }
      if (!ok) {
        if (++failures >= s.max_failures) break;
        continue;
      }
      failures = 0;
      grains.push_back(g);
      placed += 4.0 / 3.0 * kPi * a * b * cc;
      ++out.grain_count[k];
    }
    out.achieved_volume_fraction[k] = placed / slab_volume;
    if (placed < target) {
      std::ostringstream note;
      note << c.material.name << ": packing jammed at volume fraction " << placed / slab_volume << " (target "
           << c.volume_fraction << ")";
      out.notes.push_back(note.str());
    }
  }

  // Rasterise the grain tops at the nodes (heights) and at the cell centres (materials).
  const double h = s.cell_size_mm;
  const double lowest = -std::numeric_limits<double>::infinity();
  std::vector<double> top_nodes(static_cast<std::size_t>(n) * n, lowest), top_centres(top_nodes.size(), lowest);
  std::vector<int> centre_class(top_nodes.size(), -1), node_class(top_nodes.size(), -1);
  for (const Grain& g : grains) {
    const double wx = std::sqrt(g.A[0]), wy = std::sqrt(g.A[4]);
    for (int pass = 0; pass < 2; ++pass) {
      const double off = pass == 0 ? 0.0 : 0.5;  // nodes, then cell centres
      const long i0 = static_cast<long>(std::floor((g.x - wx) / h - off)), i1 = static_cast<long>(std::ceil((g.x + wx) / h - off));
      const long j0 = static_cast<long>(std::floor((g.y - wy) / h - off)), j1 = static_cast<long>(std::ceil((g.y + wy) / h - off));
      for (long j = j0; j <= j1; ++j) {
        for (long i = i0; i <= i1; ++i) {
          double dz;
          if (!top_offset(g.Q, (i + off) * h - g.x, (j + off) * h - g.y, dz)) continue;
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

  double level = s.matrix_level * T;
  if (s.target_mpd_mm) {
    if (!(*s.target_mpd_mm > 0.0)) throw InputError("surface: target MPD must be > 0");
    double lo = 0.0, hi = T;  // MPD decreases as the matrix rises
    const double mpd_lo = mpd_of_level(top_nodes, lo, f);
    if (mpd_lo < *s.target_mpd_mm) {
      std::ostringstream note;
      note << "target MPD " << *s.target_mpd_mm << " mm not reachable (at most " << mpd_lo
           << " mm with the matrix at the bottom of the slab); matrix level set to 0";
      out.notes.push_back(note.str());
      level = 0.0;
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
  out.matrix_level_mm = level;
  for (std::size_t k = 0; k < top_nodes.size(); ++k) f.heights[k] = std::max(level, top_nodes[k]);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * n + i;
      int cls = top_centres[k] > level ? centre_class[k] : -1;
      if (cls < 0) {
        // The mastic is the flat fill at the level: a cell whose mesh rises above it (a node on a grain)
        // is the flank of that grain, not mastic. Class of the highest such node.
        double highest = level;
        for (const std::size_t node : {f.index(i, j), f.index(i + 1, j), f.index(i, j + 1), f.index(i + 1, j + 1)}) {
          if (top_nodes[node] > highest) {
            highest = top_nodes[node];
            cls = node_class[node];
          }
        }
      }
      f.material[k] = static_cast<std::uint16_t>(cls + 1);
    }
  }
  std::ostringstream d;
  d << "virtual sample of " << recipe.name << ": " << grains.size()
    << " ellipsoidal grains (random orientation, b/a in [" << s.elongation_min << ", " << s.elongation_max
    << "], c/b in [" << s.flatness_min << ", " << s.flatness_max << "]) placed by random sequential addition in a "
    << T << " mm slab, periodic " << L << " mm x " << L << " mm, mastic level " << level << " mm, seed " << s.seed
    << ". Classes (target / achieved volume fraction of the slab):";
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
