// Dense packing of ellipsoidal grains in a periodic box: placed without overlap at the packing the
// mass fractions imply. Used by generate.h.
//
// Box: periodic in x and y with period L, B <= z <= T. The plane z = T is the roller's plane. The
// targets are grain volumes inside the layer layer_bottom <= z <= T (the part of each grain inside it,
// ellipsoid_volume_below); the box may reach deeper (B < layer_bottom) to give a deposit room to grow.
// A grain lies inside the box (B + hz <= z <= T - hz, hz = its vertical half-extent); a grain taller
// than the box touches the plane (z = T - hz) and reaches below it.
//
// Algorithm (deterministic for a seed). The next grain is always of the class furthest behind its
// target (smallest layer volume / target; ties: the caller's order), so the classes grow in proportion
// whatever the final density; its size is drawn once (class mass uniform over [d_min, d_max]), then:
//  Phase 0, random sequential addition in the layer: up to `insertion_attempts` random positions
//     (x, y, z uniform) and orientations. Reaches loose targets (grains floating in the mastic); jams
//     around 0.3 of the volume for these grains.
//  Phase 1, if phase 0 jams: restart by deposition against the roller's plane ("drop and settle" in
//     the roller's frame, the plane being the base). The grain is tried on `deposition_tries` random
//     verticals with random orientations; on each it is lowered from the plane until it fits (steps of
//     c/2, then 30 bisections of the contact), and the highest rest wins (it rolls into the deepest
//     nook nearby). Then `settle_moves` zero-temperature Monte Carlo moves of that grain: a random
//     displacement with a non-negative component towards the plane and, every other move, a small
//     rotation, accepted when it stays free (gravity-biased Monte Carlo as in Rosato, Strandburg, Prinz
//     & Swendsen, Phys. Rev. Lett. 58 (1987) 1038); the step adapts. Earlier grains never move, so the
//     composition at every depth follows the insertion order (no size segregation). Stops when the
//     targets are reached or `patience` grains in a row land entirely below the layer (the deposit has
//     grown through it: jammed, every class at the same fraction of its target within one grain).
// Sequential deposition with rolling packs equal spheres at about 0.58 (Visscher & Bolsterli, Nature
// 239 (1972) 504); here the layer reaches 0.56-0.57 for the F1-F4 gradings (docs/surface.md), less in
// the top 2 mm where the plane excludes volume (wall effect).
//
// Non-overlap test: exact, by the Perram-Wertheim contact function (J. W. Perram and M. S. Wertheim,
// J. Comput. Phys. 58 (1985) 409-416): with shape matrices A_i = R_i diag(a^2, b^2, c^2) R_i^T and
// centre difference r, F(lambda) = lambda (1 - lambda) r^T [(1 - lambda) A_1 + lambda A_2]^-1 r is
// concave on [0, 1] and the ellipsoids are disjoint iff max F > 1. A pair is declared disjoint only on a
// certificate F(lambda) > 1 + 1e-9 at some lambda (golden-section search), so touching or
// numerically ambiguous pairs count as overlapping (conservative).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "roadbrdf/core/progress.h"

namespace roadbrdf::surface {

using Mat3 = std::array<double, 9>;  // row-major

struct Ellipsoid {
  double x = 0.0, y = 0.0, z = 0.0;          // centre [mm]
  Mat3 rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};  // columns: unit directions of the semi-axes a, b, c
  double a = 1.0, b = 1.0, c = 1.0;          // semi-axes [mm]
  int cls = 0;                               // class index (the caller's)

  Mat3 shape() const;          // R diag(a^2, b^2, c^2) R^T: support function h(u) = sqrt(u^T S u)
  Mat3 inverse_shape() const;  // R diag(1/a^2, 1/b^2, 1/c^2) R^T: surface d^T Q d = 1
  double volume() const;       // 4/3 pi a b c
};

// Perram-Wertheim separation certificate for two ellipsoids with shape matrices A1, A2 (shape()) and
// centre difference r: true when some lambda gives F(lambda) > 1 + 1e-9 (disjoint).
bool ellipsoids_separated(const Mat3& A1, const Mat3& A2, double rx, double ry, double rz);

// Non-periodic overlap test of two ellipsoids (the negation of the certificate above).
bool ellipsoids_overlap(const Ellipsoid& p, const Ellipsoid& q);

// Volume of the part of the ellipsoid below the plane z = z0 [mm^3].
double ellipsoid_volume_below(const Ellipsoid& e, double z0);

struct PackingClass {
  double d_min_mm = 2.0, d_max_mm = 6.0;  // sieve sizes (intermediate diameter 2b)
  double layer_volume_mm3 = 0.0;          // target grain volume inside the layer [layer_bottom, T]
};

struct PackingSettings {
  double period_mm = 60.0;       // L
  double thickness_mm = 10.0;    // T: z of the roller's plane (the top of the box)
  double bottom_mm = 0.0;        // z of the floor of the box (< T)
  double layer_bottom_mm = 0.0;  // the targets are grain volumes in the layer layer_bottom <= z <= T
  std::uint64_t seed = 1;
  double elongation_min = 0.6, elongation_max = 0.9;  // b/a
  double flatness_min = 0.5, flatness_max = 0.85;     // c/b
  long insertion_attempts = 2000;  // random sequential addition: positions tried for one grain before jamming
  long deposition_tries = 16;      // deposition: random vertical lines tried per grain (the highest rest wins)
  long settle_moves = 0;           // deposition: settling moves of each deposited grain
  long patience = 50;              // deposition stops after this many grains in a row entirely below the layer
  // Share of the target volumes placed in the layer, in units of 1/1000: random sequential
  // addition reports 0..500 and, when it jams, deposition 500..1000 (it starts again from an
  // empty box); reaching the targets reports 1000.
  ProgressCallback progress;
};

struct PackingResult {
  std::vector<Ellipsoid> grains;
  std::vector<double> placed_volume_mm3;  // per class, whole grains in the box
  std::vector<double> layer_volume_mm3;   // per class, grain volume inside the layer
  std::vector<long> grain_count;          // per class
  bool reached = false;                   // every class reached its target in the layer
  bool deposition = false;                // the targets needed the deposition phase
};

PackingResult pack_ellipsoids(const std::vector<PackingClass>& classes, const PackingSettings& settings);

}  // namespace roadbrdf::surface
