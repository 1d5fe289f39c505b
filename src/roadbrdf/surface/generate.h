// Virtual sample generation: coarse aggregates of each size class of a formulation as
// random convex grains set in a mastic matrix, rasterised into a periodic height field with a
// material map (height_field.h). Also simple analytic surfaces for validation.
//
// Model of a road surface layer (assumptions, stated in the SURFACE file's description):
//  - Volume fractions: the solid volume of a component is M/rho (mass fraction over solid density);
//    the coarse class k (aggregate with d_min >= coarse_min_size_mm, formulation.h) occupies
//    phi_k = (M_k/rho_k) / sum_j (M_j/rho_j) of the mix (air voids neglected). Everything else
//    (binder, fines, filler, pigment) is the mastic matrix, with the formulation's "mastic" fit.
//  - Layer: a periodic slab of side L and thickness T = the largest d_max of the coarse classes;
//    its top z = T is the roller's plane. Class k gets the grain volume budget phi_k L^2 T.
//    Packing (packing.h): all classes together, always the class furthest behind its target, so the
//    class proportions follow the formulation whatever the density; random sequential addition in
//    the slab, and when that jams, deposition against the roller's plane with settling moves into a
//    box reaching 2T below the slab (grains entirely below the slab are then dropped). The achieved
//    fraction of a class is its grain volume inside the slab. When the targets cannot all be reached
//    every class stands at the same fraction of its target (within one grain); achieved vs target per
//    class are reported (notes and the SURFACE description).
//  - Grains: ellipsoids, orientation drawn uniformly (deposition keeps the trial that rests highest,
//    so the kept orientations are not uniform), semi-axes a >= b >= c with intermediate
//    diameter 2b = d (the sieve size), b/a ~ U(0.6, 0.9) (elongation), c/b ~ U(0.5, 0.85)
//    (flatness); d distributed so that the class's mass is uniform over [d_min, d_max]
//    (number density ~ d^-3).
//  - Non-overlap: exact Perram-Wertheim test (packing.h); touching pairs count as overlapping.
//  - Matrix: the mastic fills everything below the level z_m = matrix_level T; the surface is
//    z = max(z_m, top of the highest grain), and a cell's material is the grain's class where a
//    grain pokes out of the matrix at the cell centre; else, where one of the cell's nodes is on a
//    grain above the matrix (the cell is that grain's flank rising out of the flat mastic), the class
//    of the highest such node; else the mastic. So every mastic cell is flat at z_m. The level sets the
//    texture depth; with `target_mpd_mm` the level is found by bisection so that the MPD
//    (height_field.h) matches.
//  - Exposed mastic fraction: with `mastic_fraction` the level is found by bisection on [0, T] so that the
//    projected (plan) area fraction of the mastic cells equals it within max(0.001, 1 / cells). It is
//    monotone in the level: by the rule above a cell is mastic exactly when m_c = max(grain top at its
//    centre, grain tops at its 4 nodes) <= z_m, so the fraction is the empirical distribution function of
//    m_c over the cells, non-decreasing in z_m. A fraction outside [fraction at z_m = 0, fraction at
//    z_m = T] (within the tolerance), or inside a jump of the distribution wider than the tolerance
//    (cells with equal m_c), is an InputError naming the reachable range; never clamped.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/formulation/formulation.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/packing.h"

namespace roadbrdf::surface {

struct GrainClass {
  MaterialSpec material;  // the class's material (its name is the component name)
  double d_min_mm = 2.0, d_max_mm = 6.0;
  double volume_fraction = 0.2;  // phi_k, target fraction of the slab volume
};

struct SampleRecipe {
  std::string name;
  MaterialSpec matrix;              // material index 0
  std::vector<GrainClass> classes;  // material indices 1..K
};

// Recipe from a formulation (volume fractions as above). Throws InputError when the formulation
// has no coarse class or no mastic fit.
SampleRecipe recipe_from_formulation(const roadbrdf::Formulation& formulation);

struct GeneratorSettings {
  double size_mm = 60.0;      // period L
  double cell_size_mm = 0.1;  // grid spacing h
  std::uint64_t seed = 1;
  double matrix_level = 0.7;              // z_m / T
  std::optional<double> target_mpd_mm;    // overrides matrix_level (bisection)
  std::optional<double> mastic_fraction;  // exposed (projected) mastic area fraction in (0, 1); overrides
                                          // matrix_level (bisection); excludes target_mpd_mm
  long max_failures = 2000;               // random sequential addition: positions tried for one grain before jamming
  long deposition_tries = 128;            // deposition: vertical lines tried per grain (packing.h)
  long settle_moves = 500;                // deposition: settling moves per grain
  double elongation_min = 0.6, elongation_max = 0.9;  // b/a
  double flatness_min = 0.5, flatness_max = 0.85;     // c/b
  ProgressCallback progress;                          // the packing's (packing.h PackingSettings::progress)
};

struct GeneratedSample {
  HeightField field;
  std::vector<double> target_volume_fraction;    // per class
  std::vector<double> achieved_volume_fraction;  // per class (grain volume / slab volume)
  std::vector<long> grain_count;                 // per class
  bool targets_reached = false;                  // every class reached its target
  bool deposition = false;                       // random sequential addition jammed: packed by deposition
  std::vector<Ellipsoid> grains;                 // the placed grains (class = index into the recipe's classes)
  double slab_thickness_mm = 0.0;
  double matrix_level_mm = 0.0;
  double mastic_fraction = 0.0;            // achieved exposed (projected) area fraction of the mastic
  double mastic_fraction_tolerance = 0.0;  // with settings.mastic_fraction: max(0.001, 1 / cells); else 0
  std::vector<std::string> notes;          // jamming etc.

  // The packing report (not the field or the grains). Keys: target_volume_fraction,
  // achieved_volume_fraction, grain_count, targets_reached, deposition, slab_thickness_mm,
  // matrix_level_mm, notes.
  nlohmann::json to_json() const;
};

// Throws FieldError naming the SurfaceRequest field (surface_request.h): cell_mm, size_mm (at least
// 8 and at most 4e7 cells, a whole number of cells), matrix_level, target_mpd, mastic_fraction.
void validate(const GeneratorSettings& settings);

// Validates `settings` first.
GeneratedSample generate_sample(const SampleRecipe& recipe, const GeneratorSettings& settings);

// Validation surface: an isotropic random rough surface of one material whose facet slopes are
// close to Gaussian, with rms slope tan(sigma) along every direction of the plane (sigma [rad]:
// the Oren-Nayar roughness, standard deviation of the facet slope angle, for small angles).
// Built by spectral synthesis on the periodic grid (sum of `waves` cosines with wave vectors of
// the grid's lattice in an annulus of 6-14 cells wavelength and random phases), then scaled so
// that the rms of the finite-difference slopes of the mesh along x and y is tan(sigma).
HeightField make_gaussian_slope_surface(const MaterialSpec& material, double sigma_rad, int n = 128,
                                        double cell_size_mm = 0.1, std::uint64_t seed = 1, int waves = 256);

}  // namespace roadbrdf::surface
