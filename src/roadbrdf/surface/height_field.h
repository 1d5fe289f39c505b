// Virtual road samples: a periodic height field with a material map.
//
// Representation. Heights are given at the nodes of an nx x ny grid of spacing `cell_size_mm`;
// node (i, j) sits at (x, y) = (i h, j h). The sample is PERIODIC in x and y (period nx h by
// ny h): node nx is node 0. Cell (i, j) spans [i h, (i+1) h] x [j h, (j+1) h] and is split along
// its diagonal from (i, j) to (i+1, j+1) into two planar triangles, so the surface is continuous
// and piecewise planar. Each cell carries one material index (material of the whole cell).
// Heights in mm, z up; the mean plane is z = mean of the node heights.
//
// Periodic boundaries are what the virtual gonioreflectometer uses instead of a central footprint:
// every point of the period is equivalent, there is no edge, and a ray leaving one side re-enters
// on the other (render.h).
//
// SURFACE file (JSON, "roadbrdf-surface" version 1), written by `roadbrdf surface`:
// {
//   "format": "roadbrdf-surface", "version": 1,
//   "name": "F1",                       // sample name (the formulation's)
//   "description": "...",               // free text: how it was made
//   "cell_size_mm": 0.1,                // grid spacing h [mm]
//   "nx": 600, "ny": 600,               // nodes (= cells: periodic)
//   "periodic": true,                   // always true in version 1
//   "materials": [                      // indexed by the material map
//     { "name": "mastic 1", "fit": "../fits/mastic-1.fit.json", "fit_model": "" },   // a fit file
//                                       //   (path relative to the SURFACE file's folder), or
//     { "name": "white", "model": "lambert", "parameters": {"albedo": 1}, "options": {} } // a model
//   ],
//   "heights_mm": [ ... nx*ny numbers, node (i, j) at index j*nx + i ... ],   // [mm]
//   "material": [ ... nx*ny integers, cell (i, j) at index j*nx + i ... ],
//   "statistics": { ... }               // informative only (texture_statistics), ignored on reading
// }
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace roadbrdf::surface {

// A surface material: either a fit file (SpectralModel) or a model with fixed parameters.
struct MaterialSpec {
  std::string name;
  std::string fit;                             // fit file as written in the SURFACE file ("" when `model` is used)
  std::string fit_path;                        // resolved path (relative to the current directory or absolute)
  std::string fit_model;                       // selected fit inside the file ("" = best)
  std::string fit_text;                        // the fit file's content when given as a value (fit_path names it)
  std::string model;                           // model name when no fit file
  std::map<std::string, double> parameters;    // model parameters (defaults for the rest)
  std::map<std::string, std::string> options;  // model options

  // Keys: name, and model, parameters, options, or fit (the resolved path, else as written) and
  // fit_model; the SURFACE file's entry.
  nlohmann::json to_json() const;
};

struct HeightField {
  std::string name;
  std::string description;
  double cell_size_mm = 0.1;
  int nx = 0, ny = 0;
  std::vector<double> heights;          // nx*ny node heights [mm], index j*nx + i
  std::vector<std::uint16_t> material;  // nx*ny cell materials, index j*nx + i
  std::vector<MaterialSpec> materials;

  double size_x_mm() const { return nx * cell_size_mm; }
  double size_y_mm() const { return ny * cell_size_mm; }
  // Periodic access.
  double height(long i, long j) const { return heights[index(i, j)]; }
  std::uint16_t material_at(long i, long j) const { return material[index(i, j)]; }
  std::size_t index(long i, long j) const {
    long a = i % nx, b = j % ny;
    if (a < 0) a += nx;
    if (b < 0) b += ny;
    return static_cast<std::size_t>(b) * nx + a;
  }
  // Surface height at any (x, y) [mm] (piecewise-linear on the two triangles of each cell).
  double height_at(double x, double y) const;
};

// Checks sizes, finite heights, material indices; throws InputError.
void validate(const HeightField& field);

// Flat sample z = 0 of one material (nx = ny = n cells of size h).
HeightField make_flat(const MaterialSpec& material, int n = 16, double cell_size_mm = 0.1);

// Texture statistics, as road engineers characterise texture.
struct TextureStatistics {
  // Mean profile depth [mm], ISO 13473-1 style: every grid row (profile along x) and every column
  // (along y) is one baseline of length L (the period: the sample is shorter than the standard's
  // 100 mm; this is stated in the output); the linear trend is removed, the baseline is halved,
  // MPD of the profile = mean of the two half-segment peak levels - mean level of the profile;
  // reported as the mean over all profiles of both directions.
  double mpd_mm = 0.0;
  // Estimated texture depth ETD = 0.2 mm + 0.8 MPD (ISO 13473-1 relation to the sand-patch MTD).
  double etd_mm = 0.0;
  double rms_height_mm = 0.0;  // standard deviation of the node heights
  double mean_height_mm = 0.0;
  double max_height_mm = 0.0, min_height_mm = 0.0;
  // Fraction of the horizontal (projected) area of each material: count of cells / total.
  std::vector<double> exposed_area_fraction;
  // Fraction of the true (tilted facet) area of each material.
  std::vector<double> exposed_true_area_fraction;
  double surface_area_ratio = 1.0;  // true area / projected area

  // Keys: the members' names.
  nlohmann::json to_json() const;
};
TextureStatistics texture_statistics(const HeightField& field);

// Read / write the SURFACE file (format above). Writing is atomic. Fit paths of materials are
// written relative to the SURFACE file's folder and resolved against it on reading.
HeightField read_surface(const std::string& path);
void write_surface(const HeightField& field, const std::string& path, const TextureStatistics* statistics = nullptr);

// PNG preview: height map shaded by material (one hue per material, brightness by height).
// Uncompressed (stored) deflate blocks: no image library needed.
void write_preview_png(const HeightField& field, const std::string& path);

}  // namespace roadbrdf::surface
