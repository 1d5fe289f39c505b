#include "roadbrdf/lighting/installation.h"

#include <fmt/core.h>

#include <cctype>
#include <cmath>
#include <filesystem>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/lighting/road_surface.h"
#include "roadbrdf/photometry/rtable_io.h"

namespace roadbrdf::lighting {

namespace {

namespace fs = std::filesystem;

constexpr const char* kFormat = "roadbrdf-installation";
const std::vector<std::string> kStandardTables = {"R1", "R2", "R3", "R4", "C1", "C2"};

std::string resolve(const std::string& path, const std::string& base_dir) {
  if (path.empty() || path == "-" || fs::path(path).is_absolute() || base_dir.empty()) return path;
  return (fs::path(base_dir) / path).lexically_normal().string();
}

std::string standard_table_name(std::string name) {
  for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const std::string& known : kStandardTables) {
    if (known == name) return name;
  }
  return "";
}

// A number member: present -> checked against (lo, hi] style predicates by the caller.
double positive(const JsonNode& node) {
  const double x = node.number();
  if (!(x > 0.0)) node.fail("must be positive, got " + fmt::format("{:g}", x));
  return x;
}

template <typename Enum>
Enum enum_member(const JsonNode& node) {
  try {
    return parse_name<Enum>(node.string(), node.path());
  } catch (const FieldError& e) {
    node.fail(e.detail());
  }
}

Road read_road(const JsonNode& node) {
  node.check_keys({"lanes", "lane_width_m", "median_width_m"});
  Road road;
  road.lanes = static_cast<int>(node.at("lanes").integer(1, 20));
  const JsonNode lane_width = node.at("lane_width_m");
  road.lane_width_m = positive(lane_width);
  if (road.lane_width_m > 10.0) lane_width.fail("must not exceed 10 m");
  if (const auto median = node.find("median_width_m")) {
    road.median_width_m = median->number();
    if (road.median_width_m < 0.0 || road.median_width_m > 100.0) median->fail("must lie in [0, 100] m");
  }
  return road;
}

LuminaireLayout read_layout(const JsonNode& node, const std::string& base_dir, const Road& road) {
  node.check_keys({"file", "arrangement", "side", "spacing_m", "height_m", "overhang_m", "tilt_deg", "rotation_deg",
                   "maintenance_factor", "flux_lm", "power_w"});
  LuminaireLayout layout;
  const JsonNode file = node.at("file");
  layout.file = resolve(file.string(), base_dir);
  if (layout.file.empty()) file.fail("must name a luminaire file");
  if (const auto a = node.find("arrangement")) layout.arrangement = enum_member<Arrangement>(*a);
  if (const auto side = node.find("side")) {
    if (layout.arrangement != Arrangement::single_sided) {
      side->fail("applies to the single-sided arrangement only (this one is " + name_of(layout.arrangement) + ")");
    }
    layout.side = enum_member<RoadSide>(*side);
  }
  const JsonNode spacing = node.at("spacing_m");
  layout.spacing_m = positive(spacing);
  // The grid has one row per 3 m of spacing; beyond 300 m a road is no longer lit by one installation.
  if (layout.spacing_m > 300.0) spacing.fail("must not exceed 300 m");
  const JsonNode height = node.at("height_m");
  layout.height_m = height.number();
  // The observers' eyes are 1.5 m above the road; the threshold-increment screening needs the
  // luminaires above them.
  if (!(layout.height_m > 1.5)) height.fail("must exceed the observer's eye height of 1.5 m");
  if (layout.height_m > 100.0) height.fail("must not exceed 100 m");
  if (const auto o = node.find("overhang_m")) {
    layout.overhang_m = o->number();
    if (std::abs(layout.overhang_m) > road.width_m() + 50.0) o->fail("is farther from the road than 50 m");
  }
  if (const auto t = node.find("tilt_deg")) {
    layout.tilt_deg = t->number();
    if (!(std::abs(layout.tilt_deg) < 90.0)) t->fail("must lie in (-90, 90) deg");
  }
  if (const auto r = node.find("rotation_deg")) layout.rotation_deg = r->number();
  if (const auto mf = node.find("maintenance_factor")) {
    layout.maintenance_factor = mf->number();
    if (!(layout.maintenance_factor > 0.0 && layout.maintenance_factor <= 1.0)) mf->fail("must lie in (0, 1]");
  }
  if (const auto f = node.find("flux_lm")) layout.flux_lm = positive(*f);
  if (const auto p = node.find("power_w")) layout.power_w = positive(*p);
  return layout;
}

std::optional<double> optional_q0(const JsonNode& node) {
  const auto q0 = node.find("q0");
  if (!q0) return std::nullopt;
  const double value = q0->number();
  if (!(value > 0.0 && value < 1.0)) q0->fail("must lie in (0, 1) sr^-1, got " + fmt::format("{:g}", value));
  return value;
}

}  // namespace

SurfaceSpec surface_from_json(const JsonNode& node, const std::string& base_dir) {
  if (!node.is_object())
    node.fail(
        "must be an object: {\"rtable\": NAME}, {\"rtable_file\": PATH}, {\"file\": PATH} "
        "or {\"model\": NAME, \"parameters\": {...}}");
  SurfaceSpec spec;
  const int forms = node.has("rtable") + node.has("rtable_file") + node.has("file") + node.has("model");
  if (forms != 1) node.fail("needs exactly one of rtable, rtable_file, file, model");
  if (const auto name = node.find("rtable")) {
    node.check_keys({"rtable", "q0"});
    spec.kind = SurfaceSpec::Kind::standard_table;
    spec.name = standard_table_name(name->string());
    if (spec.name.empty()) name->fail("'" + name->string() + "' is not a CIE standard table (R1-R4, C1, C2)");
    spec.q0 = optional_q0(node);
  } else if (const auto table = node.find("rtable_file")) {
    node.check_keys({"rtable_file", "q0"});
    spec.kind = SurfaceSpec::Kind::rtable_file;
    spec.path = resolve(table->string(), base_dir);
    if (!photometry::rtable_format_from_path(spec.path)) table->fail("needs a .csv, .rtb or .dat r-table file");
    spec.q0 = optional_q0(node);
  } else if (const auto file = node.find("file")) {
    node.check_keys({"file", "select"});
    spec.kind = SurfaceSpec::Kind::model_file;
    spec.path = resolve(file->string(), base_dir);
    spec.selection = node.string_or("select", "");
  } else {
    node.check_keys({"model", "parameters", "options"});
    spec.kind = SurfaceSpec::Kind::model;
    spec.name = node.at("model").string();
    if (const auto p = node.find("parameters")) {
      for (const auto& [key, value] : p->members()) spec.parameters.emplace_back(key, value.number());
    }
    if (const auto o = node.find("options")) spec.options = o->string_map();
    try {
      model_with_parameters(spec);  // the model, its options and parameters, located here
    } catch (const FieldError& e) {
      node.fail(e.detail());
    } catch (const InputError& e) {
      node.fail(e.what());
    }
  }
  return spec;
}

SurfaceSpec surface_from_text(const std::string& text, const std::string& field) {
  if (text.empty()) throw FieldError(field, "is empty");
  SurfaceSpec spec;
  const auto colon = text.find(':');
  const std::string head = text.substr(0, colon);
  if (!standard_table_name(head).empty()) {
    spec.kind = SurfaceSpec::Kind::standard_table;
    spec.name = standard_table_name(head);
    if (colon != std::string::npos) {
      double q0 = 0.0;
      if (!parse_finite_double(text.substr(colon + 1), q0) || !(q0 > 0.0 && q0 < 1.0)) {
        throw FieldError(field, "'" + text + "': the Q0 after ':' must be a number in (0, 1) sr^-1");
      }
      spec.q0 = q0;
    }
    return spec;
  }
  if (photometry::rtable_format_from_path(text)) {
    spec.kind = SurfaceSpec::Kind::rtable_file;
    spec.path = text;
    return spec;
  }
  if (text.size() > 5 && text.substr(text.size() - 5) == ".json") {
    spec.kind = SurfaceSpec::Kind::model_file;
    spec.path = text;
    return spec;
  }
  throw FieldError(field, "'" + text +
                              "' is neither a CIE standard table (R1-R4, C1, C2, optionally with ':Q0'), an r-table "
                              "file (.csv, .rtb, .dat) nor a FIT.json / MIX.json");
}

Installation parse_installation(const Json& document, const std::string& file, const std::string& base_dir) {
  const JsonNode root(document, file);
  if (!root.is_object()) root.fail("an installation file is a JSON object");
  root.check_keys({"format", "version", "name", "road", "luminaires", "surface"});
  const JsonNode format = root.at("format");
  if (format.string() != kFormat) format.fail("must be \"" + std::string(kFormat) + "\"");
  root.at("version").integer(1, 1);
  Installation installation;
  installation.file = file;
  installation.road = read_road(root.at("road"));
  installation.luminaires = read_layout(root.at("luminaires"), base_dir, installation.road);
  if (installation.road.median_width_m > 0.0 && installation.luminaires.arrangement != Arrangement::twin_central) {
    root.at("road").at("median_width_m").fail("applies to the twin-central arrangement only");
  }
  installation.surface = surface_from_json(root.at("surface"), base_dir);
  return installation;
}

Installation read_installation(const std::string& path) {
  const Json document = parse_json_file(path);
  const std::string base_dir = path == "-" ? std::string() : fs::path(path).parent_path().string();
  return parse_installation(document, path, base_dir);
}

std::size_t luminaires_per_period(const LuminaireLayout& layout) {
  switch (layout.arrangement) {
    case Arrangement::staggered:
    case Arrangement::opposite:
      return 2;
    case Arrangement::single_sided:
    case Arrangement::twin_central:
      break;
  }
  return 1;
}

std::vector<PlacedLuminaire> luminaires_of_period(const Road& road, const LuminaireLayout& layout) {
  const double w = road.width_m();
  const double h = layout.height_m;
  const double rot = layout.rotation_deg;
  const PlacedLuminaire right{0.0, layout.overhang_m, h, rot, true};
  const PlacedLuminaire left{0.0, w - layout.overhang_m, h, 180.0 + rot, true};
  switch (layout.arrangement) {
    case Arrangement::single_sided:
      return {layout.side == RoadSide::right ? right : left};
    case Arrangement::opposite:
      return {right, left};
    case Arrangement::staggered: {
      PlacedLuminaire shifted = left;
      shifted.x = 0.5 * layout.spacing_m;
      return {right, shifted};
    }
    case Arrangement::twin_central: {
      // The pole in the middle of the central reserve; the partner faces the other carriageway.
      const PlacedLuminaire partner{0.0, w + road.median_width_m + layout.overhang_m, h, rot, false};
      return {left, partner};
    }
  }
  return {right};
}

std::vector<PlacedLuminaire> luminaires_between(const Road& road, const LuminaireLayout& layout, double x_lo,
                                                double x_hi) {
  const std::vector<PlacedLuminaire> period = luminaires_of_period(road, layout);
  std::vector<PlacedLuminaire> out;
  const double s = layout.spacing_m;
  const auto first = static_cast<long>(std::floor(x_lo / s)) - 1;
  const auto last = static_cast<long>(std::ceil(x_hi / s)) + 1;
  for (long k = first; k <= last; ++k) {
    for (PlacedLuminaire l : period) {
      l.x += static_cast<double>(k) * s;
      if (l.x >= x_lo && l.x <= x_hi) out.push_back(l);
    }
  }
  return out;
}

}  // namespace roadbrdf::lighting
