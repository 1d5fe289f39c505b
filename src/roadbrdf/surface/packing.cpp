#include "roadbrdf/surface/packing.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"

namespace roadbrdf::surface {

namespace {

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

double quad(const Mat3& M, double x, double y, double z) {
  return x * (M[0] * x + M[1] * y + M[2] * z) + y * (M[3] * x + M[4] * y + M[5] * z) +
         z * (M[6] * x + M[7] * y + M[8] * z);
}

// Random rotation matrix (uniform quaternion, Shoemake 1992).
Mat3 random_rotation(Rng& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double qx = a * std::sin(2 * kPi * u2), qy = a * std::cos(2 * kPi * u2);
  const double qz = b * std::sin(2 * kPi * u3), qw = b * std::cos(2 * kPi * u3);
  return {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw),     2 * (qx * qz + qy * qw),
          2 * (qx * qy + qz * qw),     1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw),
          2 * (qx * qz - qy * qw),     2 * (qy * qz + qx * qw),     1 - 2 * (qx * qx + qy * qy)};
}

Mat3 multiply(const Mat3& A, const Mat3& B) {
  Mat3 M{};
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c) {
      M[r * 3 + c] = A[r * 3] * B[c] + A[r * 3 + 1] * B[3 + c] + A[r * 3 + 2] * B[6 + c];
    }
  }
  return M;
}

// Rotation by `angle` about a uniformly random axis (Rodrigues' formula).
Mat3 small_rotation(Rng& rng, double angle) {
  const double cz = 2.0 * rng.uniform() - 1.0, ph = 2.0 * kPi * rng.uniform(),
               sz = std::sqrt(std::max(0.0, 1.0 - cz * cz));
  const double x = sz * std::cos(ph), y = sz * std::sin(ph), z = cz;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  return {c + t * x * x,     t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, c + t * y * y,
          t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, c + t * z * z};
}

double wrap(double x, double L) { return x - L * std::floor(x / L); }

// lambda (1 - lambda) r^T C^-1 r with C = (1 - lambda) A1 + lambda A2 (symmetric positive definite).
double pw_function(const Mat3& A1, const Mat3& A2, double rx, double ry, double rz, double lambda) {
  Mat3 C;
  for (int k = 0; k < 9; ++k) C[k] = (1.0 - lambda) * A1[k] + lambda * A2[k];
  // Adjugate of the symmetric C.
  const double c00 = C[4] * C[8] - C[5] * C[7], c01 = C[2] * C[7] - C[1] * C[8], c02 = C[1] * C[5] - C[2] * C[4];
  const double c11 = C[0] * C[8] - C[2] * C[6], c12 = C[2] * C[3] - C[0] * C[5], c22 = C[0] * C[4] - C[1] * C[3];
  const double det = C[0] * c00 + C[1] * (C[5] * C[6] - C[3] * C[8]) + C[2] * (C[3] * C[7] - C[4] * C[6]);
  const double q =
      rx * rx * c00 + ry * ry * c11 + rz * rz * c22 + 2.0 * (rx * ry * c01 + rx * rz * c02 + ry * rz * c12);
  return lambda * (1.0 - lambda) * q / det;
}

struct Item {
  Ellipsoid e;
  Mat3 A{};
  double bound = 0.0, inner = 0.0, hx = 0.0, hy = 0.0, hz = 0.0;
};

void refresh(Item& it) {
  it.A = it.e.shape();
  it.bound = std::max({it.e.a, it.e.b, it.e.c});
  it.inner = std::min({it.e.a, it.e.b, it.e.c});
  it.hx = std::sqrt(it.A[0]);
  it.hy = std::sqrt(it.A[4]);
  it.hz = std::sqrt(it.A[8]);
}

// Does `c` overlap `o` or one of its periodic images in x and y?
bool overlap_periodic(const Item& c, const Item& o, double L) {
  const double dz = o.e.z - c.e.z;
  if (std::fabs(dz) >= c.hz + o.hz) return false;
  for (int sy = -1; sy <= 1; ++sy) {
    const double dy = o.e.y - c.e.y + sy * L;
    if (std::fabs(dy) >= c.hy + o.hy) continue;
    for (int sx = -1; sx <= 1; ++sx) {
      const double dx = o.e.x - c.e.x + sx * L;
      if (std::fabs(dx) >= c.hx + o.hx) continue;
      const double d2 = dx * dx + dy * dy + dz * dz;
      const double rb = c.bound + o.bound, ri = c.inner + o.inner;
      if (d2 >= rb * rb) continue;
      if (d2 < ri * ri) return true;  // the inscribed spheres overlap
      // Separating axis along the centre line (cheap, sufficient for disjointness).
      const double dist = std::sqrt(d2), ux = dx / dist, uy = dy / dist, uz = dz / dist;
      if (dist > std::sqrt(quad(c.A, ux, uy, uz)) + std::sqrt(quad(o.A, ux, uy, uz))) continue;
      if (!ellipsoids_separated(c.A, o.A, dx, dy, dz)) return true;
    }
  }
  return false;
}

// Grains registered in every bin of a periodic 2-D grid that their x-y bounding box covers.
class Bins {
 public:
  Bins(double L, double bin) {
    nb_ = std::clamp(static_cast<int>(std::floor(L / bin)), 1, 256);
    size_ = L / nb_;
    cells_.resize(static_cast<std::size_t>(nb_) * nb_);
  }
  template <typename F>
  void for_each_bin(const Item& it, F&& f) const {
    int i0, i1, j0, j1;
    range(it.e.x, it.hx, i0, i1);
    range(it.e.y, it.hy, j0, j1);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) f(static_cast<std::size_t>(mod(j)) * nb_ + mod(i));
    }
  }
  void insert(const Item& it, int id) {
    for_each_bin(it, [&](std::size_t b) { cells_[b].push_back(id); });
  }
  void remove(const Item& it, int id) {
    for_each_bin(it, [&](std::size_t b) {
      auto& v = cells_[b];
      v.erase(std::find(v.begin(), v.end(), id));
    });
  }
  const std::vector<int>& cell(std::size_t b) const { return cells_[b]; }

 private:
  void range(double c, double h, int& lo, int& hi) const {
    lo = static_cast<int>(std::floor((c - h) / size_));
    hi = static_cast<int>(std::floor((c + h) / size_));
    if (hi - lo + 1 >= nb_) {
      lo = 0;
      hi = nb_ - 1;
    }
  }
  int mod(int i) const { return ((i % nb_) + nb_) % nb_; }
  int nb_ = 1;
  double size_ = 1.0;
  std::vector<std::vector<int>> cells_;
};

class Packer {
 public:
  Packer(const PackingSettings& s, double floor, double bin) : s_(s), floor_(floor), bins_(s.period_mm, bin) {}

  bool fits(const Item& c, int skip) {
    ++stamp_;
    bool ok = true;
    bins_.for_each_bin(c, [&](std::size_t b) {
      if (!ok) return;
      for (int id : bins_.cell(b)) {
        if (id == skip || mark_[id] == stamp_) continue;
        mark_[id] = stamp_;
        if (overlap_periodic(c, items_[id], s_.period_mm)) {
          ok = false;
          return;
        }
      }
    });
    return ok;
  }
  // Vertical placement rule of the slab; false when the grain is outside it.
  bool in_slab(Item& it) const {
    const double T = s_.thickness_mm, B = floor_;
    if (2.0 * it.hz >= T - B) {
      it.e.z = T - it.hz;  // taller than the box: touches the roller's plane
      return true;
    }
    return it.e.z >= B + it.hz && it.e.z <= T - it.hz;
  }
  void add(const Item& it) {
    items_.push_back(it);
    mark_.push_back(0);
    bins_.insert(it, static_cast<int>(items_.size()) - 1);
  }
  std::vector<Item>& items() { return items_; }

 private:
  const PackingSettings& s_;
  double floor_;
  Bins bins_;
  std::vector<Item> items_;
  std::vector<long> mark_;
  long stamp_ = 0;
};

}  // namespace

Mat3 Ellipsoid::shape() const { return r_diag_rt(rotation, a * a, b * b, c * c); }
Mat3 Ellipsoid::inverse_shape() const { return r_diag_rt(rotation, 1.0 / (a * a), 1.0 / (b * b), 1.0 / (c * c)); }
double Ellipsoid::volume() const { return 4.0 / 3.0 * kPi * a * b * c; }

bool ellipsoids_separated(const Mat3& A1, const Mat3& A2, double rx, double ry, double rz) {
  // F is concave on [0, 1] (Perram & Wertheim 1985): golden-section search for its maximum, stopping
  // as soon as a value above the threshold proves disjointness.
  constexpr double kThreshold = 1.0 + 1e-9;
  constexpr double g = 0.6180339887498949;
  double lo = 0.0, hi = 1.0;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = pw_function(A1, A2, rx, ry, rz, x1), f2 = pw_function(A1, A2, rx, ry, rz, x2);
  for (int it = 0; it < 60; ++it) {
    if (f1 > kThreshold || f2 > kThreshold) return true;
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = pw_function(A1, A2, rx, ry, rz, x2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = pw_function(A1, A2, rx, ry, rz, x1);
    }
  }
  return f1 > kThreshold || f2 > kThreshold;
}

double ellipsoid_volume_below(const Ellipsoid& e, double z0) {
  // An affine map sends the ellipsoid to the unit ball and horizontal planes to parallel planes at the
  // same relative offset t = (z0 - z) / hz (hz: vertical half-extent); the unit ball has the fraction
  // (1 + t)^2 (2 - t) / 4 of its volume below offset t (spherical cap).
  const double hz = std::sqrt(e.shape()[8]);
  const double t = std::clamp((z0 - e.z) / hz, -1.0, 1.0);
  return e.volume() * (1.0 + t) * (1.0 + t) * (2.0 - t) / 4.0;
}

bool ellipsoids_overlap(const Ellipsoid& p, const Ellipsoid& q) {
  return !ellipsoids_separated(p.shape(), q.shape(), q.x - p.x, q.y - p.y, q.z - p.z);
}

namespace {

// Checks of the box, shapes and classes (InputError); returns the largest bounding radius a grain can
// have (half the largest sieve size over the smallest b/a).
double checked_max_bound(const std::vector<PackingClass>& classes, const PackingSettings& s) {
  const double L = s.period_mm, T = s.thickness_mm, B = s.bottom_mm;
  if (!(L > 0.0 && T > B)) throw InputError("packing: period must be > 0 and the top above the floor");
  if (!(s.elongation_min > 0.0 && s.elongation_max <= 1.0 && s.elongation_min <= s.elongation_max) ||
      !(s.flatness_min > 0.0 && s.flatness_max <= 1.0 && s.flatness_min <= s.flatness_max)) {
    throw InputError("packing: shape ratios must satisfy 0 < min <= max <= 1");
  }
  double max_bound = 0.0;
  for (const auto& c : classes) {
    if (!(c.d_min_mm > 0.0 && c.d_max_mm >= c.d_min_mm)) throw InputError("packing: invalid size class");
    if (!(c.layer_volume_mm3 >= 0.0) || !std::isfinite(c.layer_volume_mm3)) {
      throw InputError("packing: invalid target volume");
    }
    max_bound = std::max(max_bound, 0.5 * c.d_max_mm / s.elongation_min);
  }
  if (!(s.layer_bottom_mm >= B && s.layer_bottom_mm < T)) throw InputError("packing: the layer must lie in the box");
  return max_bound;
}

// One call of pack_ellipsoids: the settings, the random stream and the progress shared by its phases
// (packing.h: random sequential addition, then, if it jams, deposition from an empty box).
class PackingRun {
 public:
  PackingRun(const std::vector<PackingClass>& classes, const PackingSettings& s, double bin)
      : classes_(classes), s_(s), L_(s.period_mm), T_(s.thickness_mm), B_(s.bottom_mm), bin_(bin), rng_(s.seed) {
    for (const auto& c : classes) target_total_ += c.layer_volume_mm3;
  }

  // Phase 0: random sequential addition in the layer; phase 1: deposition.
  PackingResult run_phase(int phase) {
    const bool deposit = phase == 1;
    const std::size_t K = classes_.size();
    PackingResult out;
    out.placed_volume_mm3.assign(K, 0.0);
    out.layer_volume_mm3.assign(K, 0.0);
    out.grain_count.assign(K, 0);
    out.deposition = deposit;
    Packer packer(s_, deposit ? B_ : s_.layer_bottom_mm, bin_);
    double placed = 0.0;  // sum over classes of min(layer volume, target): what the progress counts
    long useless = 0;     // consecutive deposited grains entirely below the layer
    while (true) {
      const int k = next_class(out);
      if (k < 0) {
        out.reached = true;
        break;
      }
      const Item grain = new_grain(k);
      const std::optional<Item> placed_grain = deposit ? deposited(packer, grain) : inserted(packer, grain);
      if (!placed_grain) break;  // jammed (random sequential addition) or the box is full (deposition)
      const Item& best = *placed_grain;
      packer.add(best);
      out.placed_volume_mm3[k] += best.e.volume();
      const double in_layer = layer_volume(best);
      const double target = classes_[k].layer_volume_mm3;
      placed += std::min(out.layer_volume_mm3[k] + in_layer, target) - std::min(out.layer_volume_mm3[k], target);
      out.layer_volume_mm3[k] += in_layer;
      ++out.grain_count[k];
      useless = in_layer > 0.0 ? 0 : useless + 1;
      report_progress(phase, placed);
      if (useless >= s_.patience) break;  // the deposit has grown below the layer
    }
    out.grains.reserve(packer.items().size());
    for (const Item& it : packer.items()) out.grains.push_back(it.e);
    return out;
  }

  void finish() { progress_.finish(); }

 private:
  static constexpr std::size_t kProgressUnits = 1000;

  double layer_volume(const Item& it) const {
    return ellipsoid_volume_below(it.e, T_) - ellipsoid_volume_below(it.e, s_.layer_bottom_mm);
  }

  // A grain of class k with its size and semi-axis ratios drawn (position and orientation not yet).
  Item new_grain(int k) {
    const PackingClass& c = classes_[k];
    // Sieve size with the class mass uniform over [d_min, d_max]: number density ~ d^-3.
    const double v = rng_.uniform();
    const double d = c.d_max_mm > c.d_min_mm
                         ? 1.0 / std::sqrt(1.0 / (c.d_min_mm * c.d_min_mm) -
                                           v * (1.0 / (c.d_min_mm * c.d_min_mm) - 1.0 / (c.d_max_mm * c.d_max_mm)))
                         : c.d_min_mm;
    Item it;
    it.e.b = 0.5 * d;
    it.e.a = it.e.b / (s_.elongation_min + (s_.elongation_max - s_.elongation_min) * rng_.uniform());
    it.e.c = it.e.b * (s_.flatness_min + (s_.flatness_max - s_.flatness_min) * rng_.uniform());
    it.e.cls = k;
    return it;
  }

  // The class furthest behind its target in the layer (-1: all reached).
  int next_class(const PackingResult& out) const {
    int best = -1;
    double best_ratio = 0.0;
    for (std::size_t k = 0; k < classes_.size(); ++k) {
      const double target = classes_[k].layer_volume_mm3;
      if (!(target > 0.0) || out.layer_volume_mm3[k] >= target) continue;
      const double ratio = out.layer_volume_mm3[k] / target;
      if (best < 0 || ratio < best_ratio) {
        best = static_cast<int>(k);
        best_ratio = ratio;
      }
    }
    return best;
  }

  // `grain` at a random orientation and x-y position (the random draws of every attempt).
  Item at_random_vertical(const Item& grain) {
    Item it = grain;
    it.e.rotation = random_rotation(rng_);
    refresh(it);
    it.e.x = rng_.uniform() * L_;
    it.e.y = rng_.uniform() * L_;
    return it;
  }

  // Random sequential addition: the first of `insertion_attempts` random positions in the layer
  // where the grain is free; none when it jams.
  std::optional<Item> inserted(Packer& packer, const Item& grain) {
    for (long attempt = 0; attempt < s_.insertion_attempts; ++attempt) {
      Item it = at_random_vertical(grain);
      it.e.z = s_.layer_bottom_mm + it.hz + rng_.uniform() * std::max(0.0, T_ - s_.layer_bottom_mm - 2.0 * it.hz);
      if (!packer.in_slab(it) || !packer.fits(it, -1)) continue;
      return it;
    }
    return std::nullopt;
  }

  // Deposition: the grain dropped on `deposition_tries` random verticals settles at the highest of
  // its rests, then moves by settling; none when it fits on no vertical (the box is full).
  std::optional<Item> deposited(Packer& packer, const Item& grain) {
    std::optional<Item> best;
    for (long attempt = 0; attempt < s_.deposition_tries; ++attempt) {
      Item it = at_random_vertical(grain);
      if (!drop(packer, it)) continue;
      if (!best || it.e.z > best->e.z) best = it;
    }
    if (best) settle(packer, *best);
    return best;
  }

  // The highest free position of `it` on its vertical (its centre lowered from the roller's plane in
  // steps of c/2 until it fits, then the contact refined by bisection); false when it fits nowhere.
  bool drop(Packer& packer, Item& it) const {
    const double top = T_ - it.hz, bottom = B_ + it.hz;
    if (!(top > bottom)) return false;
    double blocked = top;
    for (double z = top;; z -= 0.5 * it.e.c) {
      if (z < bottom) return false;
      it.e.z = z;
      if (packer.fits(it, -1)) {
        if (z == top) return true;
        double free = z;
        for (int k = 0; k < 30; ++k) {
          it.e.z = 0.5 * (free + blocked);
          if (packer.fits(it, -1)) {
            free = it.e.z;
          } else {
            blocked = it.e.z;
          }
        }
        it.e.z = free;
        return true;
      }
      blocked = z;
    }
  }

  // Settling: small random displacements with a non-negative z component (towards the roller's
  // plane) and small rotations, accepted when the grain stays free (zero-temperature Monte Carlo
  // with a gravity bias, Rosato et al. 1987); the step adapts to the acceptance.
  void settle(Packer& packer, Item& best) {
    double step = 0.3;
    for (long m = 0; m < s_.settle_moves; ++m) {
      Item t = best;
      const double delta = step * t.e.c;
      t.e.x = wrap(t.e.x + delta * (2.0 * rng_.uniform() - 1.0), L_);
      t.e.y = wrap(t.e.y + delta * (2.0 * rng_.uniform() - 1.0), L_);
      t.e.z += delta * rng_.uniform();
      if (m & 1) t.e.rotation = multiply(small_rotation(rng_, step * (2.0 * rng_.uniform() - 1.0)), t.e.rotation);
      refresh(t);
      t.e.z = std::min(t.e.z, T_ - t.hz);  // stops at the roller's plane
      if (t.e.z >= best.e.z && t.e.z >= B_ + t.hz && packer.fits(t, -1)) {
        best = t;
        step = std::min(1.0, step * 1.2);
      } else {
        step = std::max(0.01, step * 0.9);
      }
    }
  }

  // Progress: half of the units per phase, in proportion to the placed share of the targets.
  void report_progress(int phase, double placed) {
    if (!s_.progress || !(target_total_ > 0.0)) return;
    const auto units = static_cast<std::size_t>(0.5 * static_cast<double>(kProgressUnits) *
                                                (static_cast<double>(phase) + std::min(1.0, placed / target_total_)));
    if (units > reported_) {
      progress_.add(units - reported_);
      reported_ = units;
    }
  }

  const std::vector<PackingClass>& classes_;
  const PackingSettings& s_;
  const double L_, T_, B_;
  const double bin_;
  Rng rng_;
  double target_total_ = 0.0;
  ProgressCounter progress_{s_.progress, kProgressUnits};
  std::size_t reported_ = 0;
};

}  // namespace

PackingResult pack_ellipsoids(const std::vector<PackingClass>& classes, const PackingSettings& s) {
  const double max_bound = checked_max_bound(classes, s);
  const double bin = std::max(max_bound, s.period_mm / 256.0);
  PackingRun run(classes, s, bin);
  PackingResult out;
  for (int phase = 0; phase < 2; ++phase) {
    out = run.run_phase(phase);
    if (out.reached) break;
  }
  run.finish();
  return out;
}

}  // namespace roadbrdf::surface
