#include "roadbrdf/surface/tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roadbrdf::surface {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The smallest float >= z (a top that a skip test may trust).
float float_at_or_above(double z) {
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  if (z > kFloatMax) return std::numeric_limits<float>::infinity();
  if (z < -kFloatMax) return -std::numeric_limits<float>::max();
  float f = static_cast<float>(z);
  if (static_cast<double>(f) < z) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// Index of the plane's cell c inside a period of n cells.
long wrap(long c, long n) {
  const long w = c % n;
  return w < 0 ? w + n : w;
}

}  // namespace

HeightFieldTracer::HeightFieldTracer(const HeightField& field)
    : nx_(field.nx),
      ny_(field.ny),
      blocks_x_((field.nx + kBlock - 1) / kBlock),
      blocks_y_((field.ny + kBlock - 1) / kBlock),
      h_(field.cell_size_mm),
      inv_h_(1.0 / field.cell_size_mm) {
  // Whole tiles, also for the narrower last blocks (their unused cells are never read).
  const std::size_t tiles = static_cast<std::size_t>(blocks_x_) * blocks_y_;
  cells_.resize(tiles * kBlock * kBlock);
  material_.resize(cells_.size());
  cell_top_.resize(cells_.size());
  block_top_.assign(tiles, -std::numeric_limits<float>::max());
  hmax_ = -1e300;
  hmin_ = 1e300;
  for (int j = 0; j < ny_; ++j) {
    for (int i = 0; i < nx_; ++i) {
      const std::size_t k = cell_index(i, j);
      Cell& c = cells_[k];
      c.z00 = field.height(i, j);
      c.z10 = field.height(i + 1, j);
      c.z01 = field.height(i, j + 1);
      c.z11 = field.height(i + 1, j + 1);
      material_[k] = field.material_at(i, j);
      const double top = std::max(std::max(c.z00, c.z10), std::max(c.z01, c.z11));
      cell_top_[k] = float_at_or_above(top);
      float& block = block_top_[static_cast<std::size_t>(j / kBlock) * blocks_x_ + i / kBlock];
      block = std::max(block, cell_top_[k]);
      hmax_ = std::max(hmax_, top);
    }
  }
  for (double z : field.heights) hmin_ = std::min(hmin_, z);
  eps_ = 1e-6 * h_ + 1e-9 * (hmax_ - hmin_);
}

// The ray o + t d, and its projection a + t b on the grid in cell units.
struct HeightFieldTracer::Ray {
  Vec3 o, d;
  double ax, ay, bx, by;
  double inv_bx, inv_by;  // 1 / bx, 1 / by (unused along an axis the ray does not move on)
  double dbxy;            // bx - by: the rate at which the ray crosses the diagonals u = v
  int step_x, step_y;     // direction of the walk along x and y: -1, 0 or +1

  Ray(const Vec3& origin, const Vec3& direction, double inv_h)
      : o(origin),
        d(direction),
        ax(origin.x * inv_h),
        ay(origin.y * inv_h),
        bx(direction.x * inv_h),
        by(direction.y * inv_h),
        inv_bx(1.0 / bx),
        inv_by(1.0 / by),
        dbxy(bx - by),
        step_x(bx > 0 ? 1 : (bx < 0 ? -1 : 0)),
        step_y(by > 0 ? 1 : (by < 0 ? -1 : 0)) {}

  double z(double t) const { return o.z + t * d.z; }
  // Parameters at which the ray meets the grid lines x = line and y = line (cell units); infinity
  // along an axis the ray does not move on.
  double t_x(long line) const { return step_x != 0 ? (static_cast<double>(line) - ax) * inv_bx : kInfinity; }
  double t_y(long line) const { return step_y != 0 ? (static_cast<double>(line) - ay) * inv_by : kInfinity; }
  // The grid line ahead of cell c along an axis walked in direction `step`.
  static long line_ahead(long c, int step) { return step > 0 ? c + 1 : c; }
};

// The first hit of the ray on the two triangles of cell (i, j) (stored at `index`) between t and
// t_exit, if any.
bool HeightFieldTracer::hit_cell(const Ray& r, long i, long j, std::size_t index, double t, double t_exit,
                                 SurfaceHit& hit) const {
  const Cell& c = cells_[index];
  // Pieces of the ray inside the cell: split where it crosses the diagonal u = v.
  double ts[3] = {t, t_exit, t_exit};
  int n_pts = 2;
  if (r.dbxy != 0.0) {
    const double td = ((static_cast<double>(i) - r.ax) - (static_cast<double>(j) - r.ay)) / r.dbxy;
    if (td > t && td < t_exit) {
      ts[1] = td;
      ts[2] = t_exit;
      n_pts = 3;
    }
  }
  for (int k = 0; k + 1 < n_pts; ++k) {
    const double ta = ts[k], tb = ts[k + 1];
    const double tm = 0.5 * (ta + tb);
    const double um = r.ax + tm * r.bx - static_cast<double>(i), vm = r.ay + tm * r.by - static_cast<double>(j);
    // Triangle: u >= v -> (00, 10, 11), z = z00 + (z10-z00) u + (z11-z10) v;
    //           u <  v -> (00, 11, 01), z = z00 + (z11-z01) u + (z01-z00) v.
    const bool lower = um >= vm;
    const double gu = lower ? c.z10 - c.z00 : c.z11 - c.z01;
    const double gv = lower ? c.z11 - c.z10 : c.z01 - c.z00;
    auto g_at = [&](double tt) {
      const double u = r.ax + tt * r.bx - static_cast<double>(i), v = r.ay + tt * r.by - static_cast<double>(j);
      return r.z(tt) - (c.z00 + gu * u + gv * v);
    };
    const double ga = g_at(ta), gb = g_at(tb);
    // The ray is above the surface where it enters the piece (it starts above the surface and the
    // earlier pieces ended above it), so g <= 0 at the end is the first crossing; on this piece g is
    // linear in t, its zero found by interpolation (ta itself when rounding put g <= 0 at the entry).
    if (gb <= 0.0) {
      const double th = ga > 0.0 ? ta + (tb - ta) * (ga / (ga - gb)) : ta;
      hit.t = th;
      hit.p = r.o + th * r.d;
      hit.n = normalize(Vec3{-gu * inv_h_, -gv * inv_h_, 1.0});
      hit.material = material_[index];
      return true;
    }
  }
  return false;
}

namespace {

// The cell along one axis at parameter t of a ray that was in cell c at an earlier parameter and
// walked on without stepping along this axis: c moved past every grid line the ray crossed by t.
// At a tie the cell walk steps along y first (it steps along x only when x's line comes strictly
// earlier), so y's lines are crossed at t itself (`crossed_at_t`) and x's are not.
long catch_up(long c, int step, double a, double inv_b, double t, bool crossed_at_t) {
  if (step == 0) return c;
  for (;;) {
    const double t_line = (static_cast<double>(step > 0 ? c + 1 : c) - a) * inv_b;
    if (crossed_at_t ? t_line > t : t_line >= t) return c;
    c += step;
  }
}

}  // namespace

bool HeightFieldTracer::intersect(const Vec3& o, const Vec3& d, SurfaceHit& hit) const {
  // Rays above the highest point: escape if not going down, else start at the top plane.
  double t = 0.0;
  if (o.z > hmax_) {
    if (d.z >= 0.0) return false;
    t = (o.z - hmax_) / (-d.z);
  }
  const Ray ray(o, d, inv_h_);
  long i = static_cast<long>(std::floor(ray.ax + t * ray.bx));
  long j = static_cast<long>(std::floor(ray.ay + t * ray.by));
  long iw = wrap(i, nx_), jw = wrap(j, ny_);
  // Every ray starts above the surface (camera rays above the highest point, secondary rays raised
  // vertically by eps above a surface point, which is above the height field whatever the local
  // shape), so g = z_ray - z_surface > 0 at the start and the first crossing to g <= 0 is the hit.
  if (ray.step_x == 0 && ray.step_y == 0) {
    // Vertical ray: it never leaves its cell, and leaves the height range within this distance.
    const double t_exit = t + (hmax_ - hmin_ + 1.0) / std::max(std::fabs(d.z), 1e-300);
    return hit_cell(ray, i, j, cell_index(iw, jw), t, t_exit, hit);
  }
  // A ray climbing so slowly that it needs more steps than this is treated as escaping.
  constexpr long kMaxSteps = 1L << 22;
  for (long steps = 0; steps < kMaxSteps; ++steps) {
    // The block of cell (iw, jw), and the grid lines (in the plane) where the ray leaves it.
    const long bi = iw / kBlock, bj = jw / kBlock;
    const long block_x_line = i - iw + (ray.step_x > 0 ? std::min<long>((bi + 1) * kBlock, nx_) : bi * kBlock);
    const long block_y_line = j - jw + (ray.step_y > 0 ? std::min<long>((bj + 1) * kBlock, ny_) : bj * kBlock);
    const double t_block_x = ray.t_x(block_x_line), t_block_y = ray.t_y(block_y_line);
    const double t_block = std::min(t_block_x, t_block_y);
    const double z_block = ray.z(t_block);
    if (std::min(ray.z(t), z_block) > block_top_[static_cast<std::size_t>(bj) * blocks_x_ + bi]) {
      // Above the whole block: cross it in one step (the same cells as the cell walk would reach).
      if (d.z > 0.0 && z_block > hmax_) return false;
      if (t_block_x < t_block_y) {
        i = ray.step_x > 0 ? block_x_line : block_x_line - 1;
        j = catch_up(j, ray.step_y, ray.ay, ray.inv_by, t_block, true);
      } else {
        j = ray.step_y > 0 ? block_y_line : block_y_line - 1;
        i = catch_up(i, ray.step_x, ray.ax, ray.inv_bx, t_block, false);
      }
      t = t_block;
      iw = wrap(i, nx_);
      jw = wrap(j, ny_);
      continue;
    }
    // Cell by cell through the block. The cells the ray crosses are listed first (arithmetic only)
    // and their data requested from memory together; testing them one after the other would wait
    // for each cell's cache line in turn (the grid of a 60 mm sample is 12 MB). Inside the block the
    // walk uses the block's own coordinates (lx, ly) and storage index; the block is left when one of
    // them leaves [0, width) (the outer loop then finds the next block, wrapping around the period).
    struct Visit {
      long i, j;
      std::size_t index;
      double t_exit;
    };
    constexpr int kMaxVisits = 2 * kBlock;  // a line crosses at most 2 kBlock - 1 cells of a block
    Visit visits[kMaxVisits];
    int count = 0;
    {
      const long width_x = std::min<long>(kBlock, nx_ - bi * kBlock),
                 width_y = std::min<long>(kBlock, ny_ - bj * kBlock);
      long lx = iw - bi * kBlock, ly = jw - bj * kBlock;
      std::size_t index = cell_index(iw, jw);
      double t_x = ray.t_x(Ray::line_ahead(i, ray.step_x)), t_y = ray.t_y(Ray::line_ahead(j, ray.step_y));
      while (count < kMaxVisits) {
        __builtin_prefetch(&cells_[index]);
        __builtin_prefetch(&cell_top_[index]);
        visits[count++] = {i, j, index, std::min(t_x, t_y)};
        if (t_x < t_y) {  // only reached when the ray moves along x (t_x is infinite otherwise)
          i += ray.step_x;
          lx += ray.step_x;
          index += static_cast<std::size_t>(ray.step_x);
          t_x = (static_cast<double>(Ray::line_ahead(i, ray.step_x)) - ray.ax) * ray.inv_bx;
          if (lx < 0 || lx >= width_x) break;
        } else {
          j += ray.step_y;
          ly += ray.step_y;
          index += static_cast<std::size_t>(ray.step_y * kBlock);
          t_y = (static_cast<double>(Ray::line_ahead(j, ray.step_y)) - ray.ay) * ray.inv_by;
          if (ly < 0 || ly >= width_y) break;
        }
      }
      iw = wrap(i, nx_);
      jw = wrap(j, ny_);
    }
    steps += count;
    double z_enter = ray.z(t);
    for (int k = 0; k < count; ++k) {
      const Visit& v = visits[k];
      const double z_exit = ray.z(v.t_exit);
      // A cell whose highest corner is below the ray all through it cannot hold the hit.
      if (!(std::min(z_enter, z_exit) > cell_top_[v.index]) && hit_cell(ray, v.i, v.j, v.index, t, v.t_exit, hit)) {
        return true;
      }
      if (d.z > 0.0 && z_exit > hmax_) return false;
      t = v.t_exit;
      z_enter = z_exit;
    }
  }
  return false;
}

}  // namespace roadbrdf::surface
