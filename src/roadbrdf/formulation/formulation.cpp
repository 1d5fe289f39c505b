#include "roadbrdf/formulation/formulation.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/json_input.h"

namespace roadbrdf {

namespace {

using nlohmann::json;

std::string number_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// Error for a key of the formulation file.
[[noreturn]] void fail(const std::string& path, const std::string& key, const std::string& what) {
  throw FileError(path.empty() ? std::string("<formulation>") : path, 0, 0, key + ": " + what);
}

std::string component_key(std::size_t index, const std::string& name) {
  std::string key = "components[" + std::to_string(index) + "]";
  if (!name.empty()) key += " (\"" + name + "\")";
  return key;
}

void check_keys(const json& object, const std::set<std::string>& allowed, const std::string& path,
                const std::string& where) {
  for (const auto& [key, value] : object.items()) {
    if (!allowed.count(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(path, where.empty() ? key : where + "." + key, "unknown key (allowed: " + list + ")");
    }
  }
}

double get_number(const json& object, const std::string& key, const std::string& path, const std::string& where) {
  const json& v = object.at(key);
  if (!v.is_number()) fail(path, where + key, "must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(path, where + key, "must be finite");
  return x;
}

std::string get_string(const json& object, const std::string& key, const std::string& path, const std::string& where) {
  const json& v = object.at(key);
  if (!v.is_string()) fail(path, where + key, "must be a string");
  return v.get<std::string>();
}

std::string resolve(const std::string& formulation_path, const std::string& relative) {
  namespace fs = std::filesystem;
  const fs::path p(relative);
  if (p.is_absolute() || formulation_path.empty()) return p.lexically_normal().string();
  return (fs::path(formulation_path).parent_path() / p).lexically_normal().string();
}

void check_fit_exists(const std::string& path, const std::string& key, const std::string& fit,
                      const std::string& resolved) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(resolved, ec)) {
    fail(path, key, "fit file '" + fit + "' not found (resolved to '" + resolved + "')");
  }
}

}  // namespace

double effective_diameter_mm(const Formulation& f, const Component& c) {
  if (c.d_eff) return *c.d_eff;
  if (!c.d_max) {
    if (c.kind == ComponentKind::kBinder || c.kind == ComponentKind::kPigment) return f.binder_film_thickness_mm;
    throw InputError("component '" + c.name + "' has no size class (d_min_mm/d_max_mm) nor d_eff_mm");
  }
  const double hi = *c.d_max;
  double lo = c.d_min.value_or(0.0);
  if (lo <= 0.0) lo = hi > kFinesLimitMm ? kFinesLimitMm : hi / 10.0;
  if (hi - lo <= 1e-12 * hi) return hi;
  return (hi - lo) / std::log(hi / lo);
}

bool is_coarse(const Formulation& f, const Component& c) {
  return c.kind == ComponentKind::kAggregate && c.d_min && *c.d_min >= f.coarse_min_size_mm;
}

void validate_formulation(const Formulation& f) {
  const std::string& path = f.path;
  if (f.name.empty()) fail(path, "name", "must not be empty");
  if (f.components.empty()) fail(path, "components", "at least one component is needed");
  if (!(f.fraction_tolerance_percent >= 0.0 && f.fraction_tolerance_percent <= 10.0)) {
    fail(path, "fraction_tolerance_percent",
         "must lie in [0, 10] (got " + number_text(f.fraction_tolerance_percent) + ")");
  }
  if (!(f.binder_film_thickness_mm > 0.0)) {
    fail(path, "binder_film_thickness_mm", "must be > 0 (got " + number_text(f.binder_film_thickness_mm) + ")");
  }
  if (!(f.coarse_min_size_mm > 0.0)) {
    fail(path, "coarse_min_size_mm", "must be > 0 (got " + number_text(f.coarse_min_size_mm) + ")");
  }
  if (f.binder_coverage && !(*f.binder_coverage >= 0.0 && *f.binder_coverage <= 1.0)) {
    fail(path, "binder_coverage", "must lie in [0, 1] (got " + number_text(*f.binder_coverage) + ")");
  }
  if (f.mastic_area_fraction && !(*f.mastic_area_fraction >= 0.0 && *f.mastic_area_fraction <= 1.0)) {
    fail(path, "mastic_area_fraction", "must lie in [0, 1] (got " + number_text(*f.mastic_area_fraction) + ")");
  }
  std::set<std::string> names;
  double total = 0.0;
  bool has_binder = false;
  for (std::size_t i = 0; i < f.components.size(); ++i) {
    const Component& c = f.components[i];
    const std::string key = component_key(i, c.name);
    if (c.name.empty()) fail(path, key + ".name", "must not be empty");
    if (!names.insert(c.name).second) fail(path, key + ".name", "duplicate component name '" + c.name + "'");
    if (!(c.mass_percent > 0.0 && c.mass_percent <= 100.0)) {
      fail(path, key + ".mass_percent", "must lie in (0, 100] (got " + number_text(c.mass_percent) + ")");
    }
    if (!(c.density > 0.0)) fail(path, key + ".density_g_cm3", "must be > 0 (got " + number_text(c.density) + ")");
    if (c.density > 25.0) {
      fail(path, key + ".density_g_cm3",
           "implausible density " + number_text(c.density) + " g/cm^3 (unit is g/cm^3, not kg/m^3)");
    }
    if (c.d_min.has_value() != c.d_max.has_value()) {
      fail(path, key + (c.d_min ? ".d_max_mm" : ".d_min_mm"), "d_min_mm and d_max_mm go together");
    }
    if (c.d_min) {
      if (!(*c.d_min >= 0.0)) fail(path, key + ".d_min_mm", "must be >= 0 (got " + number_text(*c.d_min) + ")");
      if (!(*c.d_max > 0.0)) fail(path, key + ".d_max_mm", "must be > 0 (got " + number_text(*c.d_max) + ")");
      if (*c.d_min > *c.d_max) {
        fail(path, key + ".d_min_mm",
             "d_min_mm " + number_text(*c.d_min) + " exceeds d_max_mm " + number_text(*c.d_max));
      }
    } else if ((c.kind == ComponentKind::kAggregate || c.kind == ComponentKind::kFiller) && !c.d_eff) {
      fail(path, key + ".d_max_mm", "an " + name_of(c.kind) + " needs its size class d_min_mm/d_max_mm");
    }
    if (c.d_eff && !(*c.d_eff > 0.0)) fail(path, key + ".d_eff_mm", "must be > 0 (got " + number_text(*c.d_eff) + ")");
    if (c.fit.empty() && c.fit_path.empty()) fail(path, key + ".fit", "every component needs a fit file");
    has_binder = has_binder || c.kind == ComponentKind::kBinder;
    total += c.mass_percent;
  }
  if (std::fabs(total - 100.0) > f.fraction_tolerance_percent) {
    std::ostringstream msg;
    msg << "mass fractions sum to " << total << " %, not 100 % (tolerance " << f.fraction_tolerance_percent << " %)";
    fail(path, "components[].mass_percent", msg.str());
  }
  if (f.binder_coverage && *f.binder_coverage > 0.0 && !has_binder) {
    fail(path, "binder_coverage", "is > 0 but the formulation has no binder component");
  }
}

namespace {

// "mastic": {name, fit, fit_model}.
MasticSpec parse_mastic(const json& m, const std::string& path, bool check_files) {
  if (!m.is_object()) fail(path, "mastic", "must be an object {name, fit, fit_model}");
  check_keys(m, {"name", "fit", "fit_model"}, path, "mastic");
  MasticSpec spec;
  if (!m.contains("fit")) fail(path, "mastic.fit", "missing");
  spec.fit = get_string(m, "fit", path, "mastic.");
  spec.name = m.contains("name") ? get_string(m, "name", path, "mastic.") : std::string("mastic");
  if (m.contains("fit_model")) spec.fit_model = get_string(m, "fit_model", path, "mastic.");
  spec.fit_path = resolve(path, spec.fit);
  if (check_files) check_fit_exists(path, "mastic.fit", spec.fit, spec.fit_path);
  return spec;
}

// One entry of "components" (index i), its errors named components[i] or components[i] (NAME).
Component parse_component(const json& cj, std::size_t i, const std::string& path, bool check_files) {
  std::string key = component_key(i, "");
  if (!cj.is_object()) fail(path, key, "must be an object");
  Component c;
  if (cj.contains("name") && cj.at("name").is_string()) c.name = cj.at("name").get<std::string>();
  key = component_key(i, c.name);
  check_keys(
      cj,
      {"name", "kind", "mass_percent", "density_g_cm3", "d_min_mm", "d_max_mm", "d_eff_mm", "fit", "fit_model", "note"},
      path, key);
  for (const char* required : {"name", "kind", "mass_percent", "density_g_cm3", "fit"}) {
    if (!cj.contains(required)) fail(path, key + "." + required, "missing");
  }
  c.name = get_string(cj, "name", path, key + ".");
  try {
    c.kind = parse_name<ComponentKind>(get_string(cj, "kind", path, key + "."), key + ".kind");
  } catch (const FieldError& e) {
    fail(path, e.field(), e.detail());
  }
  c.mass_percent = get_number(cj, "mass_percent", path, key + ".");
  c.density = get_number(cj, "density_g_cm3", path, key + ".");
  if (cj.contains("d_min_mm")) c.d_min = get_number(cj, "d_min_mm", path, key + ".");
  if (cj.contains("d_max_mm")) c.d_max = get_number(cj, "d_max_mm", path, key + ".");
  if (cj.contains("d_eff_mm")) c.d_eff = get_number(cj, "d_eff_mm", path, key + ".");
  if (cj.contains("note") && !cj.at("note").is_string()) fail(path, key + ".note", "must be a string");
  c.fit = get_string(cj, "fit", path, key + ".");
  if (c.fit.empty()) fail(path, key + ".fit", "must not be empty");
  if (cj.contains("fit_model")) c.fit_model = get_string(cj, "fit_model", path, key + ".");
  c.fit_path = resolve(path, c.fit);
  if (check_files) check_fit_exists(path, key + ".fit", c.fit, c.fit_path);
  return c;
}

}  // namespace

Formulation parse_formulation(const std::string& text, const std::string& path, bool check_files) {
  const json j = parse_json_text(text, path.empty() ? std::string("<formulation>") : path);
  if (!j.is_object()) fail(path, "(top level)", "must be a JSON object");
  Formulation f;
  f.path = path;
  try {
    check_keys(j,
               {"format", "version", "name", "description", "source", "assumptions", "fraction_tolerance_percent",
                "binder_coverage", "mastic_area_fraction", "binder_film_thickness_mm", "coarse_min_size_mm", "mastic",
                "components"},
               path, "");
    if (!j.contains("format") || j.at("format") != "roadbrdf-formulation") {
      fail(path, "format", "must be \"roadbrdf-formulation\"");
    }
    if (!j.contains("version") || !j.at("version").is_number_integer() || j.at("version").get<std::int64_t>() != 1) {
      fail(path, "version", "must be 1");
    }
    if (!j.contains("name")) fail(path, "name", "missing");
    f.name = get_string(j, "name", path, "");
    if (j.contains("description")) f.description = get_string(j, "description", path, "");
    if (j.contains("source") && !j.at("source").is_string()) fail(path, "source", "must be a string");
    if (j.contains("assumptions")) {
      if (!j.at("assumptions").is_array()) fail(path, "assumptions", "must be an array of strings");
      for (std::size_t i = 0; i < j.at("assumptions").size(); ++i) {
        const json& a = j.at("assumptions")[i];
        if (!a.is_string()) fail(path, "assumptions[" + std::to_string(i) + "]", "must be a string");
        f.assumptions.push_back(a.get<std::string>());
      }
    }
    if (j.contains("fraction_tolerance_percent")) {
      f.fraction_tolerance_percent = get_number(j, "fraction_tolerance_percent", path, "");
    }
    if (j.contains("binder_coverage") && !j.at("binder_coverage").is_null()) {
      f.binder_coverage = get_number(j, "binder_coverage", path, "");
    }
    if (j.contains("mastic_area_fraction") && !j.at("mastic_area_fraction").is_null()) {
      f.mastic_area_fraction = get_number(j, "mastic_area_fraction", path, "");
    }
    if (j.contains("binder_film_thickness_mm")) {
      f.binder_film_thickness_mm = get_number(j, "binder_film_thickness_mm", path, "");
    }
    if (j.contains("coarse_min_size_mm")) f.coarse_min_size_mm = get_number(j, "coarse_min_size_mm", path, "");
    if (j.contains("mastic")) f.mastic = parse_mastic(j.at("mastic"), path, check_files);
    if (!j.contains("components")) fail(path, "components", "missing");
    const json& list = j.at("components");
    if (!list.is_array()) fail(path, "components", "must be an array");
    for (std::size_t i = 0; i < list.size(); ++i)
      f.components.push_back(parse_component(list[i], i, path, check_files));
  } catch (const json::exception& e) {
    throw FileError(path, 0, 0, std::string("malformed formulation: ") + e.what());
  }
  validate_formulation(f);
  return f;
}

Formulation read_formulation(const std::string& path, bool check_files) {
  InputLimits limits;
  limits.what = "a formulation file";
  limits.max_bytes = std::uintmax_t{16} << 20;  // a few components: a few kB
  return parse_formulation(read_text_file(path, limits), path, check_files);
}

}  // namespace roadbrdf

namespace roadbrdf {

std::vector<FileArgument> formulation_input_files(const Formulation& formulation) {
  std::vector<FileArgument> files;
  if (formulation.mastic) files.push_back({"mastic.fit of " + formulation.path, formulation.mastic->fit_path});
  for (const Component& c : formulation.components) files.push_back({"fit of component '" + c.name + "'", c.fit_path});
  return files;
}

}  // namespace roadbrdf
