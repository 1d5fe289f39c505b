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

bool HeightFieldTracer::intersect(const Vec3& o, const Vec3& d, SurfaceHit& hit) const {
  // Rays above the highest point: escape if not going down, else start at the top plane.
  double t = 0.0;
  if (o.z > hmax_) {
    if (d.z >= 0.0) return false;
    t = (o.z - hmax_) / (-d.z);
  }
  const double ax = o.x * inv_h_, ay = o.y * inv_h_;  // position in cell units
  const double bx = d.x * inv_h_, by = d.y * inv_h_;
  const double x0 = ax + t * bx, y0 = ay + t * by;
  long i = static_cast<long>(std::floor(x0)), j = static_cast<long>(std::floor(y0));
  long iw = i % nx_, jw = j % ny_;
  if (iw < 0) iw += nx_;
  if (jw < 0) jw += ny_;
  const double inf = std::numeric_limits<double>::infinity();
  const int step_x = bx > 0 ? 1 : (bx < 0 ? -1 : 0);
  const int step_y = by > 0 ? 1 : (by < 0 ? -1 : 0);
  double t_max_x =
      step_x > 0 ? (static_cast<double>(i + 1) - ax) / bx : (step_x < 0 ? (static_cast<double>(i) - ax) / bx : inf);
  double t_max_y =
      step_y > 0 ? (static_cast<double>(j + 1) - ay) / by : (step_y < 0 ? (static_cast<double>(j) - ay) / by : inf);
  const double t_delta_x = step_x != 0 ? 1.0 / std::fabs(bx) : inf;
  const double t_delta_y = step_y != 0 ? 1.0 / std::fabs(by) : inf;
  const double dbxy = bx - by;
  // Every ray starts above the surface (camera rays above the highest point, secondary rays raised
  // vertically by eps above a surface point, which is above the height field whatever the local
  // shape), so g = z_ray - z_surface > 0 at the start and the first crossing to g <= 0 is the hit.
  bool armed = true;
  // A ray climbing so slowly that it needs more steps than this is treated as escaping.
  constexpr long kMaxSteps = 1L << 22;
  for (long step = 0; step < kMaxSteps; ++step) {
    double t_exit = std::min(t_max_x, t_max_y);
    if (!(t_exit < inf)) {
      // Vertical ray: it leaves the height range within this distance.
      t_exit = t + (hmax_ - hmin_ + 1.0) / std::max(std::fabs(d.z), 1e-300);
    }
    const Cell& c = cells_[static_cast<std::size_t>(jw) * nx_ + iw];
    const double z_enter = o.z + t * d.z, z_exit = o.z + t_exit * d.z;
    if (std::min(z_enter, z_exit) > c.zmax) {
      armed = true;
    } else {
      // Pieces of the ray inside the cell: split where it crosses the diagonal u = v.
      double ts[3] = {t, t_exit, t_exit};
      int n_pts = 2;
      if (dbxy != 0.0) {
        const double td = ((static_cast<double>(i) - ax) - (static_cast<double>(j) - ay)) / dbxy;
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
        if (ga > 0.0) armed = true;
        if (armed && gb <= 0.0) {
          const double th = ga > 0.0 ? ta + (tb - ta) * (ga / (ga - gb)) : ta;
          hit.t = th;
          hit.p = o + th * d;
          hit.n = normalize(Vec3{-gu * inv_h_, -gv * inv_h_, 1.0});
          hit.material = c.material;
          return true;
        }
        if (gb > 0.0) armed = true;
      }
    }
    if (d.z > 0.0 && z_exit > hmax_) return false;
    // Next cell.
    if (t_max_x < t_max_y) {
      t = t_max_x;
      t_max_x += t_delta_x;
      i += step_x;
      iw += step_x;
      if (iw == nx_) iw = 0;
      if (iw < 0) iw = nx_ - 1;
    } else {
      if (!(t_max_y < inf)) return false;  // vertical ray that did not hit: cannot happen
      t = t_max_y;
      t_max_y += t_delta_y;
      j += step_y;
      jw += step_y;
      if (jw == ny_) jw = 0;
      if (jw < 0) jw = ny_ - 1;
    }
  }
  return false;
}

}  // namespace roadbrdf::surface
