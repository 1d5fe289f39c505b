#include "roadbrdf/surface/tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roadbrdf::surface {

HeightFieldTracer::HeightFieldTracer(const HeightField& field)
    : nx_(field.nx), ny_(field.ny), h_(field.cell_size_mm), inv_h_(1.0 / field.cell_size_mm) {
  cells_.resize(static_cast<std::size_t>(nx_) * ny_);
  hmax_ = -1e300;
  hmin_ = 1e300;
  for (int j = 0; j < ny_; ++j) {
    for (int i = 0; i < nx_; ++i) {
      Cell& c = cells_[static_cast<std::size_t>(j) * nx_ + i];
      c.z00 = field.height(i, j);
      c.z10 = field.height(i + 1, j);
      c.z01 = field.height(i, j + 1);
      c.z11 = field.height(i + 1, j + 1);
      c.zmax = std::max(std::max(c.z00, c.z10), std::max(c.z01, c.z11));
      c.material = field.material_at(i, j);
      hmax_ = std::max(hmax_, c.zmax);
      hmin_ = std::min(hmin_, c.zmax);
    }
  }
  for (double z : field.heights) hmin_ = std::min(hmin_, z);
  eps_ = 1e-6 * h_ + 1e-9 * (hmax_ - hmin_);
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The walk of a ray's projection over the periodic grid (2-D DDA in cell units): the cell (i, j) of
// the unbounded plane, whose corner the in-cell coordinates u = x - i, v = y - j are measured from,
// the same cell (iw, jw) inside the period, and the ray parameters t at which the ray crosses the
// next cell boundary in x and in y.
struct GridWalk {
  long i = 0, j = 0;
  long iw = 0, jw = 0;
  int step_x = 0, step_y = 0;
  double t_max_x = kInfinity, t_max_y = kInfinity;
  double t_delta_x = kInfinity, t_delta_y = kInfinity;

  // The walk of the ray a + t b (cell units) from its point at parameter t.
  GridWalk(double ax, double ay, double bx, double by, double t, int nx, int ny) {
    const double x0 = ax + t * bx, y0 = ay + t * by;
    i = static_cast<long>(std::floor(x0));
    j = static_cast<long>(std::floor(y0));
    iw = i % nx;
    jw = j % ny;
    if (iw < 0) iw += nx;
    if (jw < 0) jw += ny;
    step_x = bx > 0 ? 1 : (bx < 0 ? -1 : 0);
    step_y = by > 0 ? 1 : (by < 0 ? -1 : 0);
    if (step_x != 0) {
      t_max_x = (static_cast<double>(step_x > 0 ? i + 1 : i) - ax) / bx;
      t_delta_x = 1.0 / std::fabs(bx);
    }
    if (step_y != 0) {
      t_max_y = (static_cast<double>(step_y > 0 ? j + 1 : j) - ay) / by;
      t_delta_y = 1.0 / std::fabs(by);
    }
  }

  // Step into the neighbour across the nearer boundary, setting t to the parameter of the crossing;
  // false when there is none (a vertical ray never leaves its cell).
  bool advance(double& t, int nx, int ny) {
    if (t_max_x < t_max_y) {
      t = t_max_x;
      t_max_x += t_delta_x;
      i += step_x;
      iw += step_x;
      if (iw == nx) iw = 0;
      if (iw < 0) iw = nx - 1;
      return true;
    }
    if (!(t_max_y < kInfinity)) return false;
    t = t_max_y;
    t_max_y += t_delta_y;
    j += step_y;
    jw += step_y;
    if (jw == ny) jw = 0;
    if (jw < 0) jw = ny - 1;
    return true;
  }
};

// The ray o + t d, and its projection a + t b on the grid in cell units.
struct CellRay {
  const Vec3& o;
  const Vec3& d;
  double ax, ay, bx, by;
  double dbxy;  // bx - by: the rate at which the ray crosses the diagonals u = v
};

// The first hit of the ray on the two triangles of cell c = (i, j) between t and t_exit, if any
// (hit.material is left to the caller). inv_h: 1 / cell size [1/mm].
bool hit_in_cell(const detail::TracerCell& c, const CellRay& r, long i, long j, double t, double t_exit, double inv_h,
                 SurfaceHit& hit) {
  const Vec3& o = r.o;
  const Vec3& d = r.d;
  const double ax = r.ax, ay = r.ay, bx = r.bx, by = r.by;
  // Pieces of the ray inside the cell: split where it crosses the diagonal u = v.
  double ts[3] = {t, t_exit, t_exit};
  int n_pts = 2;
  if (r.dbxy != 0.0) {
    const double td = ((static_cast<double>(i) - ax) - (static_cast<double>(j) - ay)) / r.dbxy;
    if (td > t && td < t_exit) {
      ts[1] = td;
      ts[2] = t_exit;
      n_pts = 3;
    }
  }
  for (int k = 0; k + 1 < n_pts; ++k) {
    const double ta = ts[k], tb = ts[k + 1];
    const double tm = 0.5 * (ta + tb);
    const double um = ax + tm * bx - static_cast<double>(i), vm = ay + tm * by - static_cast<double>(j);
    // Triangle: u >= v -> (00, 10, 11), z = z00 + (z10-z00) u + (z11-z10) v;
    //           u <  v -> (00, 11, 01), z = z00 + (z11-z01) u + (z01-z00) v.
    const bool lower = um >= vm;
    const double gu = lower ? c.z10 - c.z00 : c.z11 - c.z01;
    const double gv = lower ? c.z11 - c.z10 : c.z01 - c.z00;
    auto g_at = [&](double tt) {
      const double u = ax + tt * bx - static_cast<double>(i), v = ay + tt * by - static_cast<double>(j);
      return (o.z + tt * d.z) - (c.z00 + gu * u + gv * v);
    };
    const double ga = g_at(ta), gb = g_at(tb);
    // The ray is above the surface where it enters the piece (it starts above the surface and the
    // earlier pieces ended above it), so g <= 0 at the end is the first crossing; on this piece g is
    // linear in t, its zero found by interpolation (ta itself when rounding put g <= 0 at the entry).
    if (gb <= 0.0) {
      const double th = ga > 0.0 ? ta + (tb - ta) * (ga / (ga - gb)) : ta;
      hit.t = th;
      hit.p = o + th * d;
      hit.n = normalize(Vec3{-gu * inv_h, -gv * inv_h, 1.0});
      return true;
    }
  }
  return false;
}

}  // namespace

bool HeightFieldTracer::intersect(const Vec3& o, const Vec3& d, SurfaceHit& hit) const {
  // Rays above the highest point: escape if not going down, else start at the top plane.
  double t = 0.0;
  if (o.z > hmax_) {
    if (d.z >= 0.0) return false;
    t = (o.z - hmax_) / (-d.z);
  }
  const double ax = o.x * inv_h_, ay = o.y * inv_h_;  // position in cell units
  const double bx = d.x * inv_h_, by = d.y * inv_h_;
  const CellRay ray{o, d, ax, ay, bx, by, bx - by};
  GridWalk walk(ax, ay, bx, by, t, nx_, ny_);
  // Every ray starts above the surface (camera rays above the highest point, secondary rays raised
  // vertically by eps above a surface point, which is above the height field whatever the local
  // shape), so g = z_ray - z_surface > 0 at the start and the first crossing to g <= 0 is the hit.
  // A ray climbing so slowly that it needs more steps than this is treated as escaping.
  constexpr long kMaxSteps = 1L << 22;
  for (long step = 0; step < kMaxSteps; ++step) {
    double t_exit = std::min(walk.t_max_x, walk.t_max_y);
    if (!(t_exit < kInfinity)) {
      // Vertical ray: it leaves the height range within this distance.
      t_exit = t + (hmax_ - hmin_ + 1.0) / std::max(std::fabs(d.z), 1e-300);
    }
    const Cell& c = cells_[static_cast<std::size_t>(walk.jw) * nx_ + walk.iw];
    const double z_enter = o.z + t * d.z, z_exit = o.z + t_exit * d.z;
    // A cell whose highest corner is below the ray all through it cannot hold the hit.
    if (!(std::min(z_enter, z_exit) > c.zmax) && hit_in_cell(c, ray, walk.i, walk.j, t, t_exit, inv_h_, hit)) {
      hit.material = c.material;
      return true;
    }
    if (d.z > 0.0 && z_exit > hmax_) return false;
    if (!walk.advance(t, nx_, ny_)) return false;  // vertical ray that did not hit: cannot happen
  }
  return false;
}

}  // namespace roadbrdf::surface
