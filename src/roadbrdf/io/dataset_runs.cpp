#include "roadbrdf/io/dataset_runs.h"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <unordered_map>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/core/text.h"
#include "roadbrdf/io/dataset_dialect.h"
#include "roadbrdf/io/dataset_read_support.h"

namespace roadbrdf {

namespace {

const RequestField<DatasetReadFields> kFields[] = {
    {"delimiter", "--delimiter", "", "Dataset cell delimiter: auto (from the header line), ',', ';' or tab",
     &DatasetReadFields::delimiter},
    {"decimal", "--decimal", "", "Dataset decimal separator: auto (from the numbers), '.' or ',' (with ';' or tab)",
     &DatasetReadFields::decimal},
    {"average_duplicates", "--average-duplicates", "",
     "Average dataset rows (and runs) with the same geometry (else an error)", &DatasetReadFields::average_duplicates},
    {"quantity", "--quantity", "",
     "What the dataset's values are, converted to BRDF on reading: brdf (sr^-1), brf (pi x BRDF), brdf-cos (BRDF x "
     "cos theta_i), percent-brf (100 x BRF)",
     &DatasetReadFields::quantity},
    {"columns", "--column", "",
     "Dataset column mapping [FILE:]FIELD=HEADER_NAME, e.g. theta_r=True_Average_View_Zenith (repeatable; fields: "
     "the angles, wavelength, brdf, sigma)",
     &DatasetReadFields::columns},
    {"set", "--set", "deg",
     "An angle the dataset has no column for, [FILE:]ANGLE=VALUE, e.g. theta_i=30 or run2.csv:theta_i=45 "
     "(repeatable)",
     &DatasetReadFields::set},
};

bool is_angle_field(const std::string& name) {
  static const std::vector<std::string> angles = {"theta_i", "phi_i", "theta_r", "phi_r",
                                                  "gamma",   "alpha", "beta",    "delta"};
  return std::find(angles.begin(), angles.end(), name) != angles.end();
}

// One [FILE:]FIELD=VALUE item, split.
struct Item {
  std::string file, field, value;
};

Item split_item(const std::string& text, const std::string& field_name) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw FieldError(field_name, fmt::format("'{}' is not [FILE:]FIELD=VALUE", text));
  }
  Item item;
  std::string left = trimmed_copy(std::string_view(text).substr(0, eq));
  item.value = trimmed_copy(std::string_view(text).substr(eq + 1));
  const auto colon = left.rfind(':');
  if (colon != std::string::npos) {
    item.file = left.substr(0, colon);
    left = left.substr(colon + 1);
  }
  item.field = left;
  if (item.value.empty()) throw FieldError(field_name, fmt::format("'{}' gives no value after '='", text));
  return item;
}

bool names_file(const std::string& prefix, const std::string& file) {
  return prefix == file || prefix == std::filesystem::path(file).filename().string();
}

// The items of `items` that apply to `file`: those for every file, then those for this file (which
// override), as field -> value. A FILE: prefix naming none of `files` is an error.
std::map<std::string, std::string> items_for(const std::vector<std::string>& items, const std::string& field_name,
                                             const std::string& file, const std::vector<std::string>& files) {
  std::map<std::string, std::string> general, specific;
  for (const std::string& text : items) {
    const Item item = split_item(text, field_name);
    if (!item.file.empty()) {
      const bool known =
          std::any_of(files.begin(), files.end(), [&](const std::string& f) { return names_file(item.file, f); }) ||
          names_file(item.file, file);
      if (!known) {
        throw FieldError(field_name, fmt::format("'{}' names file '{}', which is not an input{}", text, item.file,
                                                 did_you_mean(item.file, files)));
      }
    }
    auto& into = item.file.empty() ? general : specific;
    if (!item.file.empty() && !names_file(item.file, file)) continue;
    if (!into.emplace(item.field, item.value).second) {
      throw FieldError(field_name, fmt::format("'{}': {} is given twice", text, item.field));
    }
  }
  for (auto& [k, v] : specific) general[k] = v;
  return general;
}

}  // namespace

RequestFields<DatasetReadFields> DatasetReadFields::fields() { return kFields; }

const std::vector<std::string>& mappable_dataset_fields() {
  static const std::vector<std::string> names = {"theta_i", "phi_i", "theta_r",    "phi_r", "gamma", "alpha",
                                                 "beta",    "delta", "wavelength", "brdf",  "sigma"};
  return names;
}

DatasetReadOptions DatasetReadFields::options_for(const std::string& file,
                                                  const std::vector<std::string>& files) const {
  DatasetReadOptions o;
  o.delimiter = delimiter_from_name(delimiter);
  o.decimal = decimal_from_name(decimal);
  o.average_duplicates = average_duplicates;
  o.quantity = parse_name<DatasetQuantity>(quantity, "quantity");
  for (const auto& [field, name] : items_for(columns, "columns", file, files)) o.columns[field] = name;
  for (const auto& [field, text] : items_for(set, "set", file, files)) {
    double value = 0.0;
    if (!parse_finite_double(text, value)) {
      throw FieldError("set", fmt::format("{}={}: '{}' is not a number of degrees", field, text, text));
    }
    o.fixed_angles[field] = value;
  }
  validate_read_options(o);
  return o;
}

void validate_mapping_options(const DatasetReadOptions& o) {
  const auto& fields = mappable_dataset_fields();
  for (const auto& [field, name] : o.columns) {
    if (std::find(fields.begin(), fields.end(), field) == fields.end()) {
      throw FieldError("columns", fmt::format("'{}' is no dataset field{} (fields: {})", field,
                                              did_you_mean(field, fields), fmt::join(fields, ", ")));
    }
    if (trimmed_copy(name).empty()) throw FieldError("columns", fmt::format("{}: the header name is empty", field));
  }
  for (const auto& [field, value] : o.fixed_angles) {
    if (!is_angle_field(field)) {
      throw FieldError("set", fmt::format("'{}' is no angle{} (theta_i, phi_i, theta_r, phi_r or gamma, alpha, "
                                          "beta, delta)",
                                          field, did_you_mean(field, fields)));
    }
    if (!std::isfinite(value)) throw FieldError("set", fmt::format("{} = {} deg is not finite", field, value));
    const bool zenith = field == "theta_i" || field == "theta_r" || field == "gamma" || field == "alpha";
    if (zenith && (value < 0.0 || value > 90.0)) {
      throw FieldError("set", fmt::format("{} = {:g} deg is outside [0, 90] deg (a zenith angle)", field, value));
    }
    if (o.columns.count(field)) {
      throw FieldError("set", fmt::format("{} is both fixed and mapped to column '{}' (`columns`): give one of them",
                                          field, o.columns.at(field)));
    }
  }
}

double quantity_factor(DatasetQuantity quantity, double cos_theta_i) {
  switch (quantity) {
    case DatasetQuantity::kBrf:
      return kPi;
    case DatasetQuantity::kBrdfCos:
      return cos_theta_i;
    case DatasetQuantity::kPercentBrf:
      return 100.0 * kPi;
    case DatasetQuantity::kBrdf:
      break;
  }
  return 1.0;
}

void convert_to_brdf(SpectralDataset& d, DatasetQuantity quantity, const std::string& source,
                     const std::function<void(const std::string&)>& warn) {
  if (quantity == DatasetQuantity::kBrdf) return;
  if (const auto it = d.metadata.find("quantity_read"); it != d.metadata.end()) {
    throw FieldError("quantity", fmt::format("{}: the values were converted to BRDF already (metadata quantity_read: "
                                             "{}); read it as brdf",
                                             source, it->second));
  }
  const std::size_t m = d.wavelengths.size();
  std::size_t grazing = 0;
  for (std::size_t g = 0; g < d.geometries.size(); ++g) {
    const double f = quantity_factor(quantity, std::cos(d.geometries[g].theta_i));
    // BRDF cos(theta_i) at grazing incidence is the product of an undefined BRDF with 0.
    const bool undefined = std::fabs(f) <= 1e-12;
    for (std::size_t j = 0; j < m; ++j) {
      double& v = d.brdf[g * m + j];
      if (undefined) {
        if (!std::isnan(v)) ++grazing;
        v = std::numeric_limits<double>::quiet_NaN();
        if (d.has_sigma()) d.sigma[g * m + j] = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      v /= f;
      if (d.has_sigma()) d.sigma[g * m + j] /= f;
    }
  }
  if (grazing > 0) {
    const std::string message = fmt::format(
        "{}: {} BRDF x cos(theta_i) values at theta_i = 90 deg (no irradiance) have no BRDF and are kept as missing",
        source, grazing);
    if (warn) {
      warn(message);
    } else {
      route_warning(message);
    }
  }
  d.metadata["quantity_read"] = name_of(quantity);
  if (const auto it = d.metadata.find("units"); it != d.metadata.end() && it->second != "sr^-1") {
    d.metadata["source_units"] = it->second;
  }
  d.metadata["units"] = "sr^-1";
}

SpectralDataset combine_runs(const std::vector<DatasetRun>& runs, bool average_duplicates,
                             const std::function<void(const std::string&)>& warn, Repeatability* repeatability) {
  if (runs.empty()) throw InputError("no dataset to combine");
  auto say = [&](const std::string& message) { warn ? warn(message) : route_warning(message); };
  const SpectralDataset& first = runs.front().data;
  const std::size_t m = first.wavelengths.size();
  const bool with_sigma = std::any_of(runs.begin(), runs.end(), [](const DatasetRun& r) { return r.data.has_sigma(); });
  SpectralDataset out;
  out.convention = first.convention;
  out.wavelengths = first.wavelengths;
  out.metadata = first.metadata;
  out.comments = first.comments;
  std::unordered_map<dataset_read::GeometryKey, std::size_t, dataset_read::GeometryKeyHash> seen;
  std::vector<std::string> origin;  // run and row of each geometry's first appearance
  std::vector<int> count;           // per cell: the runs that measured it
  std::map<std::size_t, std::vector<std::pair<double, double>>> ranges;
  std::size_t averaged = 0;
  std::string listed;
  for (const DatasetRun& run : runs) {
    const SpectralDataset& d = run.data;
    if (d.wavelengths != first.wavelengths) {
      throw InputError(
          fmt::format("{} has {} wavelengths ({:g}-{:g} nm) and {} has {} ({:g}-{:g} nm): runs combine "
                      "only with the same wavelengths (resample them first)",
                      runs.front().path, m, first.wavelengths.front(), first.wavelengths.back(), run.path,
                      d.wavelengths.size(), d.wavelengths.front(), d.wavelengths.back()));
    }
    listed += (listed.empty() ? "" : "; ") + run.path;
    if (const auto it = d.metadata.find("averaged_duplicate_rows"); it != d.metadata.end()) {
      double rows = 0.0;
      if (parse_finite_double(it->second, rows) && rows >= 0.0) averaged += static_cast<std::size_t>(rows);
    }
    for (const auto& [key, value] : d.metadata) {
      if (key == "averaged_duplicate_rows") continue;
      const auto it = out.metadata.find(key);
      if (it == out.metadata.end()) {
        out.metadata[key] = value;
      } else if (it->second != value) {
        say(fmt::format("metadata '{}' is '{}' in {} and '{}' in {}: the first is kept", key, it->second,
                        runs.front().path, value, run.path));
      }
    }
    for (std::size_t g = 0; g < d.geometries.size(); ++g) {
      const double* v = &d.brdf[g * m];
      const double* s = d.has_sigma() ? &d.sigma[g * m] : nullptr;
      const auto [it, inserted] = seen.emplace(dataset_read::key_of(d.geometries[g]), out.geometries.size());
      if (inserted) {
        out.geometries.push_back(d.geometries[g]);
        origin.push_back(fmt::format("{} row {}", run.path, g + 1));
        for (std::size_t j = 0; j < m; ++j) {
          out.brdf.push_back(v[j]);
          count.push_back(std::isnan(v[j]) ? 0 : 1);
          // Summed squares while averaging, as the reader does.
          const double sj = s ? s[j] : std::numeric_limits<double>::quiet_NaN();
          if (with_sigma) out.sigma.push_back(average_duplicates ? sj * sj : sj);
        }
        continue;
      }
      const std::size_t n = it->second;
      if (!average_duplicates) {
        throw InputError(fmt::format("{} row {} repeats the geometry of {} ({})", run.path, g + 1, origin[n],
                                     dataset_read::duplicates_hint()));
      }
      ++averaged;  // one more row of a geometry, as the reader counts duplicate rows
      auto [range, fresh] = ranges.try_emplace(n);
      if (fresh) {
        for (std::size_t j = 0; j < m; ++j) range->second.emplace_back(out.brdf[n * m + j], out.brdf[n * m + j]);
      }
      for (std::size_t j = 0; j < m; ++j) {
        if (std::isnan(v[j])) continue;
        auto& [lo, hi] = range->second[j];
        lo = std::isnan(lo) ? v[j] : std::min(lo, v[j]);
        hi = std::isnan(hi) ? v[j] : std::max(hi, v[j]);
        double& sum = out.brdf[n * m + j];
        const double sj = s ? s[j] : std::numeric_limits<double>::quiet_NaN();
        if (count[n * m + j]++ == 0) {
          sum = v[j];
          if (with_sigma) out.sigma[n * m + j] = sj * sj;
        } else {
          sum += v[j];
          if (with_sigma) out.sigma[n * m + j] += sj * sj;
        }
      }
    }
  }
  if (average_duplicates) {
    for (std::size_t k = 0; k < out.brdf.size(); ++k) {
      const double c = std::max(1, count[k]);
      out.brdf[k] /= c;
      if (with_sigma) out.sigma[k] = std::sqrt(out.sigma[k]) / c;
    }
    std::vector<std::vector<double>> spreads(m);
    for (const auto& [n, range] : ranges) {
      for (std::size_t j = 0; j < m; ++j) {
        if (count[n * m + j] < 2) continue;
        spreads[j].push_back(dataset_read::relative_spread(range[j].first, range[j].second, out.brdf[n * m + j]));
      }
    }
    if (repeatability) *repeatability = dataset_read::repeatability_of(spreads, ranges.size());
    if (averaged > 0) out.metadata["averaged_duplicate_rows"] = std::to_string(averaged);
    if (!ranges.empty()) say(fmt::format("{} geometries measured in several runs were averaged", ranges.size()));
  }
  if (runs.size() > 1) out.metadata["runs"] = listed;
  return out;
}

SpectralDataset read_dataset_runs(const std::vector<std::string>& paths, const DatasetReadFields& fields,
                                  const std::function<void(const std::string&)>& warn, bool allow_missing) {
  if (paths.size() == 1) {
    DatasetReadOptions options = fields.options_for(paths.front(), paths);
    options.warn = warn;
    options.allow_missing = allow_missing;
    return read_dataset(paths.front(), options);
  }
  std::vector<DatasetRun> runs;
  runs.reserve(paths.size());
  for (const std::string& path : paths) {
    DatasetReadOptions options = fields.options_for(path, paths);
    options.warn = warn;
    options.allow_missing = allow_missing;
    runs.push_back({path, read_dataset(path, options)});
  }
  return combine_runs(runs, fields.average_duplicates, warn);
}

}  // namespace roadbrdf
