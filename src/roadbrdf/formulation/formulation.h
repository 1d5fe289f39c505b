// Road formulations (report section 5.1, Table 5.1): the components of a mixed road sample, their
// proportions, densities, grain sizes and the fit files of their measured BRDFs.
//
// File format (JSON, "roadbrdf-formulation" version 1; see data/examples/formulations/README.md):
// {
//   "format": "roadbrdf-formulation", "version": 1,
//   "name": "F1",                                   // required
//   "description": "...", "source": "...",          // optional free text
//   "assumptions": ["...", ...],                    // optional free text (e.g. assumed densities)
//   "fraction_tolerance_percent": 0.5,              // optional: |sum of mass_percent - 100| allowed
//   "binder_coverage": 0.12,                        // optional, in [0, 1]: areal method (see mixing.h);
//                                                   //   default = volume fraction of binder + pigment
//   "mastic_area_fraction": 0.3,                    // optional, in [0, 1]: mastic method; default =
//                                                   //   volume fraction of the mastic's constituents
//   "binder_film_thickness_mm": 0.01,               // optional, > 0: size of binder and pigment
//                                                   //   components without a size class (hapke method)
//   "coarse_min_size_mm": 2.0,                      // optional, > 0: aggregates with d_min >= this
//                                                   //   are "coarse"; the rest belongs to the mastic
//   "mastic": { "name": "mastic 1", "fit": "../fits/mastic-1.fit.json", "fit_model": "..." },
//                                                   // optional; needed by the mastic method
//   "components": [                                 // required, at least one
//     { "name": "Bitumen",                          // required, unique
//       "kind": "binder",                           // binder, aggregate, filler or pigment (below)
//       "mass_percent": 5.2,                        // > 0, percent of the total mass
//       "density_g_cm3": 1.03,                      // > 0, solid (particle) density [g/cm^3]
//       "d_min_mm": 0, "d_max_mm": 2,               // grain size class [mm] (e.g. Garonne 0/2);
//                                                   //   required for aggregate and filler,
//                                                   //   optional for binder and pigment
//       "d_eff_mm": 0.5,                            // optional: effective grain diameter [mm]
//                                                   //   overriding the default from the class
//       "fit": "../fits/bitumen.fit.json",          // fit file (written by `roadbrdf fit`) of the
//                                                   //   component's measured BRDF, or of the mastic
//                                                   //   that contains it; relative to this file
//       "fit_model": "oren-nayar" }                 // optional: which fit in the file (default: best)
//   ]
// }
// Unknown keys are errors (they are usually typos). Every problem is a FileError naming the file
// and the key path, e.g. "F1.json: components[2] ("Garonne 0/2").density_g_cm3: must be > 0".
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/enum_names.h"

namespace roadbrdf {

enum class ComponentKind { kBinder, kAggregate, kFiller, kPigment };
inline constexpr EnumName<ComponentKind> kComponentKindNames[] = {
    {ComponentKind::kBinder, "binder", ""},
    {ComponentKind::kAggregate, "aggregate", ""},
    {ComponentKind::kFiller, "filler", ""},
    {ComponentKind::kPigment, "pigment", ""},
};
constexpr std::span<const EnumName<ComponentKind>> enum_names(ComponentKind) { return kComponentKindNames; }

struct Component {
  std::string name;
  ComponentKind kind = ComponentKind::kAggregate;
  double mass_percent = 0.0;    // percent of the total mass
  double density = 0.0;         // solid density [g/cm^3]
  std::optional<double> d_min;  // grain size class [mm]
  std::optional<double> d_max;  // [mm]
  std::optional<double> d_eff;  // explicit effective diameter [mm]
  std::string fit;              // fit file as written in the formulation
  std::string fit_path;         // resolved (relative to the formulation file's folder)
  std::string fit_model;        // selected fit inside the file ("" = best)
};

struct MasticSpec {
  std::string name;
  std::string fit;
  std::string fit_path;
  std::string fit_model;
};

struct Formulation {
  std::string path;  // file it was read from ("" when built in memory)
  std::string name;
  std::string description;
  std::vector<std::string> assumptions;
  std::vector<Component> components;
  std::optional<MasticSpec> mastic;
  std::optional<double> binder_coverage;       // [0, 1]
  std::optional<double> mastic_area_fraction;  // [0, 1]
  double binder_film_thickness_mm = 0.01;
  double coarse_min_size_mm = 2.0;
  double fraction_tolerance_percent = 0.5;
};

// Fine-particle cut [mm] used in place of d_min = 0 for a class reaching above it (EN 933-1 fines
// limit, 0.063 mm); a class entirely below it (filler) uses d_max / 10 instead.
inline constexpr double kFinesLimitMm = 0.063;

// Effective grain diameter D [mm] of a component: d_eff if given; else the logarithmic mean
// (d_max - d_min') / ln(d_max / d_min') of the size class: the inverse of the mass-weighted mean of
// 1/D when the class's mass is spread uniformly over [d_min', d_max] (projected area per unit mass of
// spheres is 3/(2 rho D), so this D gives the class's total projected area). d_min' is the lower size
// with 0 replaced as described at kFinesLimitMm; d_min' = d_max gives D = d_max. Binder and
// pigment without a size class use the formulation's binder_film_thickness_mm.
double effective_diameter_mm(const Formulation& formulation, const Component& component);

// True for an aggregate whose class lies entirely at or above coarse_min_size_mm.
bool is_coarse(const Formulation& formulation, const Component& component);

// Read, parse and validate a formulation file. Fit-file paths are resolved relative to the file's
// folder; check_files: they must exist (a sample can be generated before its fit files are, they
// are needed only to render it). Throws FileError naming the file and the key.
Formulation read_formulation(const std::string& path, bool check_files = true);

// Parse JSON text; `path` is used for error messages and to resolve fit files. check_files: fail
// when a fit file does not exist.
Formulation parse_formulation(const std::string& json_text, const std::string& path, bool check_files = true);

// Every file a formulation refers to (the mastic's and each component's fit file, resolved), named
// for messages, for check_distinct_files: a command that reads a formulation reads these too.
std::vector<FileArgument> formulation_input_files(const Formulation& formulation);

// Consistency checks shared by the reader and in-memory formulations (names unique, positive
// densities and fractions, fractions summing to 100 % within the tolerance, size classes ordered,
// sizes present where needed, parameters in range). Throws FileError (path, key) / InputError.
void validate_formulation(const Formulation& formulation);

}  // namespace roadbrdf
