// A road-lighting installation (EN 13201-3:2015, CIE 140-2000): a straight carriageway of equal lanes,
// one row or two rows of identical luminaires at a regular spacing, and the pavement's reflection.
// Read from a JSON file ("format": "roadbrdf-installation", "version": 1; docs/lighting.md), every
// error located by its key path.
//
// Road coordinates [m]: x along the road axis, in the direction the observers look (they stand at
// x < 0 and look towards +x); y across the road, from the right-hand edge of the carriageway (y = 0)
// to its left-hand edge (y = W = lanes x lane width), "right" and "left" as the observers see them;
// z up from the road surface. The field of calculation starts at x = 0, where a luminaire of the
// reference row stands.
//
// Orientation of a luminaire (luminaire.h C-planes): a luminaire on the right-hand side has its C0
// plane pointing along +x and its C90 plane towards +y, i.e. across the carriageway: the usual
// convention of road luminaire photometry. A luminaire on the left-hand side is the same luminaire
// turned by 180 deg about its vertical axis (C0 along -x, C90 towards -y, again across the road).
// `rotation_deg` turns every luminaire further, counter-clockwise seen from above, for files whose
// C90 plane is not the road side. `tilt_deg` raises the luminaire's C90 side: the downward axis is
// turned by tilt_deg towards the carriageway (a rotation about the C0-C180 axis).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/core/parameters.h"

namespace roadbrdf::lighting {

enum class Arrangement { single_sided, staggered, opposite, twin_central };
inline constexpr EnumName<Arrangement> kArrangementNames[] = {
    {Arrangement::single_sided, "single-sided", "one row on the `side` of the carriageway"},
    {Arrangement::staggered, "staggered", "a row on each side, shifted by half the spacing"},
    {Arrangement::opposite, "opposite", "a row on each side, face to face"},
    {Arrangement::twin_central, "twin-central",
     "back-to-back pairs in a central reserve on the left-hand side, one lighting each carriageway"},
};
constexpr std::span<const EnumName<Arrangement>> enum_names(Arrangement) { return kArrangementNames; }

enum class RoadSide { right, left };
inline constexpr EnumName<RoadSide> kRoadSideNames[] = {
    {RoadSide::right, "right", "the observers' right-hand side (y = 0)"},
    {RoadSide::left, "left", "the observers' left-hand side (y = W)"},
};
constexpr std::span<const EnumName<RoadSide>> enum_names(RoadSide) { return kRoadSideNames; }

struct Road {
  int lanes = 2;
  double lane_width_m = 3.5;
  double median_width_m = 0.0;  // central reserve (twin-central only): poles stand in its middle
  double width_m() const { return lanes * lane_width_m; }
};

struct LuminaireLayout {
  std::string file;  // the photometry file, as resolved (relative to the installation file)
  Arrangement arrangement = Arrangement::single_sided;
  RoadSide side = RoadSide::right;  // single-sided only
  double spacing_m = 30.0;          // between consecutive luminaires of one row
  double height_m = 10.0;           // light centre above the road
  double overhang_m = 0.0;          // from the near edge of the carriageway towards its middle (negative: outside)
  double tilt_deg = 0.0;
  double rotation_deg = 0.0;
  double maintenance_factor = 1.0;
  std::optional<double> flux_lm;  // replaces the file's rated flux (the distribution is scaled)
  std::optional<double> power_w;  // replaces the file's system power
};

// The pavement: exactly one of the forms below.
struct SurfaceSpec {
  enum class Kind { standard_table, rtable_file, model_file, model };
  Kind kind = Kind::standard_table;
  std::string name;          // standard_table: R1-R4, C1, C2; model: the model name
  std::string path;          // rtable_file, model_file (a FIT.json or MIX.json), resolved
  std::string selection;     // model_file: the fit's model / the mixture's method ("" = the file's best)
  std::optional<double> q0;  // tables: scale the table to this Q0 [sr^-1]
  OptionSet options;         // model: its options
  std::vector<std::pair<std::string, double>> parameters;  // model: given parameters (others default)
};

// A surface given on its own (the request's `surface` field): a CIE standard table name ("R3",
// optionally ":Q0", e.g. "R3:0.07"), an r-table file (.csv, .rtb, .dat), or a FIT.json / MIX.json.
// Throws FieldError(field, ...).
SurfaceSpec surface_from_text(const std::string& text, const std::string& field);

// A surface object of an installation file (the forms of docs/lighting.md); paths relative to `base_dir`.
SurfaceSpec surface_from_json(const JsonNode& node, const std::string& base_dir);

struct Installation {
  std::string file;  // where it was read from ("" when built in memory)
  Road road;
  LuminaireLayout luminaires;
  SurfaceSpec surface;
};

// Reads and checks an installation file; relative paths inside it are resolved against its folder.
// Throws FileError naming the file and the key path.
Installation read_installation(const std::string& path);
Installation parse_installation(const Json& document, const std::string& file, const std::string& base_dir);

// One luminaire where it stands.
struct PlacedLuminaire {
  double x = 0.0, y = 0.0, z = 0.0;     // light centre [m]
  double azimuth_deg = 0.0;             // plan direction of its C0 plane, counter-clockwise from +x
  bool lights_this_carriageway = true;  // false: the other half of a twin-central pair
};

// Luminaires of one period of the installation [0, spacing) per row; `luminaires_between` repeats them.
std::vector<PlacedLuminaire> luminaires_of_period(const Road& road, const LuminaireLayout& layout);
// Every luminaire with x in [x_lo, x_hi].
std::vector<PlacedLuminaire> luminaires_between(const Road& road, const LuminaireLayout& layout, double x_lo,
                                                double x_hi);
// Luminaires per spacing that light this carriageway (counted for power and energy).
std::size_t luminaires_per_period(const LuminaireLayout& layout);

}  // namespace roadbrdf::lighting
