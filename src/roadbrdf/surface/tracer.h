// Ray casting against a periodic height field (height_field.h): the first point where a ray meets
// the surface of two planar triangles per cell.
//
// Exact traversal: the ray's projection on the plane is followed cell by cell over the periodic grid
// (2-D DDA; a ray leaving one side of the period re-enters on the other). Inside a cell the ray is
// split where it crosses the cell's diagonal; on each piece both the ray and the triangle are linear
// in t, so the height of the ray above the surface, g(t) = z_ray(t) - z_surface(t), is linear and its
// first zero is found exactly (up to rounding). Every ray starts above the surface (primary rays above
// the highest point, secondary rays raised vertically above a surface point), so the first piece with
// g <= 0 at its end holds the hit.
#pragma once

#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/surface/height_field.h"

namespace roadbrdf::surface {

struct SurfaceHit {
  double t = 0.0;  // ray parameter [mm] (unit direction)
  Vec3 p, n;       // point and unit upward facet normal
  int material = 0;
};

namespace detail {
// One cell of the tracer's grid: the heights of its corners (i, j), (i+1, j), (i, j+1), (i+1, j+1)
// [mm], the highest of them, and its material.
struct TracerCell {
  double z00, z10, z01, z11, zmax;
  int material;
};
}  // namespace detail

class HeightFieldTracer {
 public:
  explicit HeightFieldTracer(const HeightField& field);

  // First intersection of the ray o + t d (t > 0, d unit) with the surface; false if it escapes.
  bool intersect(const Vec3& o, const Vec3& d, SurfaceHit& hit) const;

  double highest() const { return hmax_; }
  // The point above the highest point of the surface over (u1, u2) x the period, u in [0, 1).
  Vec3 point_above(double u1, double u2) const { return {u1 * nx_ * h_, u2 * ny_ * h_, hmax_ + 1e-3 * h_}; }
  // Vertical offset of a secondary ray's origin above its surface point [mm].
  double offset() const { return eps_; }

 private:
  using Cell = detail::TracerCell;
  int nx_ = 0, ny_ = 0;
  double h_ = 0.1, inv_h_ = 10.0;
  double hmax_ = 0.0, hmin_ = 0.0;
  double eps_ = 1e-6;
  std::vector<Cell> cells_;
};

}  // namespace roadbrdf::surface
