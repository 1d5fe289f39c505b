#include "roadbrdf/io/model_export.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <cmath>

#include "roadbrdf/core/coverage.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/openmaterial3d.h"

namespace roadbrdf {

namespace {

using Field = RequestField<ExportRequest>;

const Field kFields[] = {
    {"source", "SOURCE", "", "FIT.json, MIX.json or a model name (with parameters)", &ExportRequest::source,
     FileRole::input, true},
    {"parameters", "-p,--parameter", "", "Model parameter NAME=VALUE (repeatable); defaults otherwise",
     &ExportRequest::parameters},
    {"options", "--option", "", "Model option NAME=VALUE (repeatable)", &ExportRequest::options},
    {"fit", "--fit", "", "Which fit of a fit file (its model) or method of a MIX.json; default: the best",
     &ExportRequest::fit},
    {"format", "--format", "", "openmaterial3d, csv or alta", &ExportRequest::format},
    {"preset", "--preset", "", "Sensor wavelengths: none, camera (380-780 nm by 10 nm) or lidar (905, 1550 nm)",
     &ExportRequest::preset},
    {"wavelengths", "--wavelengths", "nm", "Wavelengths (list or START:STOP:STEP); default: the preset's or the fit's",
     &ExportRequest::wavelengths},
    {"theta_i", "--theta-i", "deg", "Incident zenith angles (default 0:89:1)", &ExportRequest::theta_i},
    {"theta_r", "--theta-r", "deg", "Exit zenith angles (default 0:89:1)", &ExportRequest::theta_r},
    {"phi", "--phi", "deg", "Exit azimuths relative to the incident one, 0 retro side (default 0:180:5)",
     &ExportRequest::phi},
    {"output", "-o,--output", "", "Output file ('-' = standard output)", &ExportRequest::output, FileRole::output,
     true},
    {"name", "--name", "", "Material name (default: from the source's file name)", &ExportRequest::name},
    {"description", "--description", "", "Material description (default: made from the source)",
     &ExportRequest::description},
    {"uuid", "--uuid", "", "Material uuid (default: a new random one)", &ExportRequest::uuid},
    {"material_version", "--material-version", "", "Material version MAJOR.MINOR.PATCH",
     &ExportRequest::material_version},
    {"authors", "--author", "", "Author (repeatable; default: unknown)", &ExportRequest::authors},
    {"copyrights", "--copyright", "", "Copyright line (repeatable; default: unknown)", &ExportRequest::copyrights},
    {"license", "--license", "", "License, an SPDX identifier or a URL (default NOASSERTION)", &ExportRequest::license},
    {"sensor", "--sensor", "", "Typical sensor technology (default: from the preset: camera, lidar)",
     &ExportRequest::sensor},
};

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> out;
  for (int k = 0; from + k * step <= to + 1e-9; ++k) out.push_back(from + k * step);
  return out;
}

void check_angles(const std::vector<double>& values, const char* field, double max) {
  if (values.empty()) throw FieldError(field, "give at least one angle");
  for (const double a : values) {
    if (!(a >= 0.0 && a <= max)) throw FieldError(field, fmt::format("{} deg lies outside [0, {}] deg", a, max));
  }
  for (std::size_t k = 1; k < values.size(); ++k) {
    if (!(values[k] > values[k - 1])) throw FieldError(field, "the angles must be strictly increasing");
  }
}

std::string file_stem(const std::string& path) {
  std::string name = path.substr(path.find_last_of('/') + 1);
  for (const char* suffix : {".json", ".fit", ".mix"}) {
    const std::string s(suffix);
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) {
      name.resize(name.size() - s.size());
    }
  }
  return name;
}

}  // namespace

std::vector<double> ExportRequest::default_zeniths() { return steps(0.0, 89.0, 1.0); }
std::vector<double> ExportRequest::default_azimuths() { return steps(0.0, 180.0, 5.0); }

std::span<const RequestField<ExportRequest>> ExportRequest::fields() { return kFields; }

ExportFormat ExportRequest::output_format() const { return parse_name<ExportFormat>(format, "format"); }
SensorPreset ExportRequest::sensor_preset() const { return parse_name<SensorPreset>(preset, "preset"); }

void ExportRequest::validate() const {
  if (source.empty()) throw FieldError("source", "give a fit file, a MIX.json or a model name");
  if (source_kind(source) == "data") {
    throw FieldError("source", "'" + source +
                                   "' is neither a fit file (.json) nor a model name; a measured dataset "
                                   "is converted by `roadbrdf convert`");
  }
  if (output.empty()) throw FieldError("output", "give the file to write");
  output_format();
  if (sensor_preset() != SensorPreset::kNone && !wavelengths.empty()) {
    throw FieldError("wavelengths", "excludes a `preset`: give one of the two");
  }
  for (std::size_t k = 0; k < wavelengths.size(); ++k) {
    if (!(wavelengths[k] > 0.0)) throw FieldError("wavelengths", fmt::format("{} nm is not positive", wavelengths[k]));
    if (k > 0 && !(wavelengths[k] > wavelengths[k - 1])) {
      throw FieldError("wavelengths", "the wavelengths must be strictly increasing");
    }
  }
  check_angles(theta_i, "theta_i", 90.0);
  check_angles(theta_r, "theta_r", 90.0);
  check_angles(phi, "phi", 360.0);
  if (phi.back() >= 360.0) throw FieldError("phi", "360 deg is the azimuth 0: give angles in [0, 360) deg");
  if (source_kind(source) != "model" && (!parameters.empty() || !options.empty())) {
    throw FieldError(parameters.empty() ? "options" : "parameters", "apply to a model given by its name");
  }
  if (source_kind(source) != "fit" && !fit.empty()) {
    throw FieldError("fit", "selects a fit of a fit file or a method of a MIX.json");
  }
}

SpectralDataset export_grid(const ExportRequest& request, const SpectralModel& model, Diagnostics& diagnostics) {
  std::vector<double> wavelengths = request.wavelengths;
  switch (request.sensor_preset()) {
    case SensorPreset::kCamera:
      wavelengths = steps(380.0, 780.0, 10.0);
      break;
    case SensorPreset::kLidar:
      wavelengths = {905.0, 1550.0};
      break;
    case SensorPreset::kNone:
      break;
  }
  if (wavelengths.empty()) {
    if (!model.is_spectral()) {
      throw FieldError("wavelengths",
                       "the model does not depend on wavelength: give the `wavelengths` to tabulate "
                       "or a `preset`");
    }
    wavelengths = model.wavelengths();
  }
  SpectralDataset d;
  d.wavelengths = wavelengths;
  for (const double ti : request.theta_i) {
    for (const double tr : request.theta_r) {
      for (const double phi : request.phi) {
        d.geometries.push_back(geometry_from_degrees(ti, 0.0, tr, phi));
        if (tr == 0.0) break;  // along the normal the azimuth is undefined: one direction, one row
      }
    }
  }
  if (d.geometries.size() * wavelengths.size() > kMaxExportValues) {
    throw FieldError("wavelengths", fmt::format("{} geometries x {} wavelengths exceed the {} values written at most",
                                                d.geometries.size(), wavelengths.size(), kMaxExportValues));
  }
  const Model& m = model.model();
  std::vector<double> params;
  for (const double wl : wavelengths) {
    std::vector<double> p;
    try {
      p = model.is_spectral() ? model.parameters_at(wl) : model.parameter_table();
    } catch (const InputError& e) {
      throw FieldError(request.wavelengths.empty() ? "preset" : "wavelengths", e.what());
    }
    params.insert(params.end(), p.begin(), p.end());
    if (m.delta_reflectance(p.data(), 1.0) > 0.0 && params.size() == p.size()) {
      diagnostics.note("delta_left_out",
                       "the model's ideal specular (mirror) part has no value on a grid and is not in the table");
    }
  }
  d.brdf.resize(d.geometries.size() * wavelengths.size());
  m.evaluate_batch(d.geometries.data(), d.geometries.size(), params.data(), wavelengths.size(), d.brdf.data());
  if (model.coverage()) {
    std::size_t outside = 0;
    for (const Geometry& g : d.geometries) outside += model.coverage()->covers(g) ? 0 : 1;
    if (outside > 0) {
      diagnostics.note("extrapolated", fmt::format("{} of the {} geometries lie outside the fitted data's coverage: "
                                                   "there the table holds the model's extrapolation",
                                                   outside, d.geometries.size()));
    }
  }
  return d;
}

ExportResult export_model(const ExportRequest& request) {
  request.validate();
  ExportResult result;
  const SpectralModel model = spectral_model_of(request.source, request.parameters, request.options, request.fit);
  SpectralDataset d = export_grid(request, model, result.diagnostics);
  const bool fitted = source_kind(request.source) == "fit" && model.coverage().has_value();
  result.model = model.model().name();
  result.sources = fitted ? "measurement, roadbrdf fit" : "simulation";
  result.output = request.output;
  result.format = request.format;
  result.geometries = d.geometry_count();
  result.wavelengths = d.wavelengths;
  d.metadata["model"] = result.model;
  d.metadata["source"] = request.source;
  switch (request.output_format()) {
    case ExportFormat::kCsv:
      write_dataset(d, request.output);
      break;
    case ExportFormat::kAlta:
      if (d.wavelength_count() != 1) {
        throw FieldError("wavelengths", "ALTA text data hold one wavelength: give one (one file per wavelength)");
      }
      write_alta(d, request.output);
      break;
    case ExportFormat::kOpenMaterial3d: {
      OpenMaterialMetadata meta;
      meta.name = request.name.empty() ? file_stem(request.source) : request.name;
      meta.description = !request.description.empty() ? request.description
                         : fitted
                             ? fmt::format("BRDF of the {} model fitted by roadbrdf to measurements (fit file {}).",
                                           result.model, request.source)
                             : fmt::format("BRDF of the {} model (roadbrdf).", result.model);
      meta.uuid = request.uuid.empty() ? random_uuid() : request.uuid;
      meta.material_version = request.material_version;
      meta.authors = request.authors.empty() ? std::vector<std::string>{"unknown"} : request.authors;
      meta.copyrights = request.copyrights.empty() ? std::vector<std::string>{"unknown"} : request.copyrights;
      meta.license = request.license;
      meta.creation_date = utc_timestamp();
      meta.sources = result.sources;
      meta.typical_sensor_technology = request.sensor;
      if (meta.typical_sensor_technology.empty() && request.sensor_preset() != SensorPreset::kNone) {
        meta.typical_sensor_technology = name_of(request.sensor_preset());
      }
      write_openmaterial3d(d, meta, request.output);
      result.metadata = {{"name", meta.name},       {"description", meta.description},
                         {"uuid", meta.uuid},       {"materialVersion", meta.material_version},
                         {"authors", meta.authors}, {"copyrights", meta.copyrights},
                         {"license", meta.license}, {"creationDate", meta.creation_date},
                         {"sources", meta.sources}, {"typicalSensorTechnology", meta.typical_sensor_technology}};
      break;
    }
  }
  return result;
}

nlohmann::json ExportResult::to_json() const {
  return {{"output", output},
          {"format", format},
          {"model", model},
          {"sources", sources},
          {"geometries", geometries},
          {"wavelengths", wavelengths},
          {"rows", geometries * wavelengths.size()},
          {"metadata", metadata},
          {"units", {{"wavelengths", "nm"}}},
          {"diagnostics", diagnostics.to_json()}};
}

std::string ExportResult::summary_text() const {
  return fmt::format("wrote {} ({}): {} geometries x {} wavelengths of model {} ({})\n", output, format, geometries,
                     wavelengths.size(), model, sources);
}

}  // namespace roadbrdf
