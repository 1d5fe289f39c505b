#include "roadbrdf/cli/instruments.h"

#include <fmt/core.h>

#include <map>

#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/io/instrument.h"
#include "roadbrdf/io/manifest.h"
#include "roadbrdf/io/usgs.h"

namespace roadbrdf::cli {

namespace {

void warn(const std::string& message) { fmt::print(stderr, "roadbrdf: warning: {}\n", message); }

// "theta_i=0,phi_i=0,theta_r=30,phi_r=180" (or the road angles) -> geometry and convention.
Geometry parse_geometry(const std::string& text, AngleConvention& convention) {
  if (text.empty()) {
    throw InputError(
        "an instrument file has no geometry: give --geometry theta_i=D,phi_i=D,theta_r=D,phi_r=D (or "
        "gamma=D,alpha=D,beta=D,delta=D), or convert a manifest with --from manifest");
  }
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find(',', start);
    items.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  const std::map<std::string, double> values = parse_numeric_assignments(items, "--geometry");
  std::vector<std::string> header;
  header.reserve(values.size());
  for (const auto& [name, value] : values) header.push_back(name);
  if (header.size() != 4) throw InputError("--geometry: give exactly four angles (degrees)");
  const auto columns = find_angle_columns(header, "--geometry", 0, convention);
  double a[4];
  for (int k = 0; k < 4; ++k) a[k] = values.at(header[columns[static_cast<std::size_t>(k)]]);
  return geometry_from_angle_values(convention, a);
}

ManifestOptions manifest_options(const InstrumentArgs& args) {
  ManifestOptions o;
  run_request<InstrumentOptions>([&] { o = args.manifest_options(); });
  o.warn = warn;
  return o;
}

}  // namespace

void add_instrument_flags(CLI::App* c, InstrumentArgs& args) {
  c->add_option("--geometry", args.geometry,
                "Geometry of a single instrument file: theta_i=D,phi_i=D,theta_r=D,phi_r=D or "
                "gamma=D,alpha=D,beta=D,delta=D [deg]");
  // One --quantity for both kinds of input: an instrument file's signal to store, or what a dataset
  // CSV's values are (DatasetReadFields::quantity).
  c->add_option("--quantity", args.quantity,
                "Instrument signal to store: " + described_names_text<InstrumentQuantity>() +
                    " (default target); for a dataset CSV what its values are, converted to BRDF: " +
                    described_names_text<DatasetQuantity>() + " (default brdf)");
  c->add_option("--usgs-wavelengths", args.usgs_wavelengths,
                "--from usgs: the splib07a wavelength file of the spectrum's instrument, e.g. "
                "splib07a_Wavelengths_ASD_0.35-2.5_microns_2151_ch.txt (micrometres)");
  InstrumentOptions& shared = args;
  for (const RequestField<InstrumentOptions>& field : InstrumentOptions::fields()) detail::add_field(c, shared, field);
  add_field_table(c, table_flag<InstrumentOptions>);
}

bool is_instrument_input(ConvertSource from, const std::string& input) {
  switch (from) {
    case ConvertSource::kAsd:
    case ConvertSource::kSed:
    case ConvertSource::kSig:
    case ConvertSource::kInstrument:
    case ConvertSource::kManifest:
    case ConvertSource::kUsgs:
      return true;
    case ConvertSource::kAuto:
      return has_instrument_extension(input);
    case ConvertSource::kWide:
    case ConvertSource::kLong:
    case ConvertSource::kCuret:
    case ConvertSource::kAlta:
      return false;
  }
  return false;
}

namespace {

// The manifest, after its listed files are checked against the outputs.
Manifest read_checked_manifest(const std::string& path, std::vector<FileArgument> inputs,
                               const std::vector<FileArgument>& outputs) {
  Manifest manifest = read_manifest(path);
  const std::vector<FileArgument> listed = manifest_input_files(manifest);
  inputs.insert(inputs.end(), listed.begin(), listed.end());
  check_distinct_files(inputs, outputs);
  return manifest;
}

}  // namespace

SpectralDataset convert_instrument_input(ConvertSource from, const std::string& input, const InstrumentArgs& args,
                                         const std::vector<FileArgument>& inputs,
                                         const std::vector<FileArgument>& outputs) {
  const InstrumentQuantity quantity =
      parse_name<InstrumentQuantity>(args.quantity.empty() ? "target" : args.quantity, "quantity");
  const ManifestOptions options = manifest_options(args);
  if (from == ConvertSource::kManifest) {
    if (!args.geometry.empty())
      throw InputError("--geometry is for a single instrument file: a manifest gives its own");
    return manifest_dataset(read_checked_manifest(input, inputs, outputs), quantity, options);
  }
  if (from == ConvertSource::kUsgs) {
    if (args.usgs_wavelengths.empty())
      throw InputError("--from usgs needs --usgs-wavelengths FILE (the splib07a wavelength file of the spectrum)");
    // The file holds the reflectance only (target and reflectance mean the same here); no panel signal.
    if (quantity == InstrumentQuantity::kReference)
      throw InputError("--quantity reference: a USGS splib07a file holds no reference signal");
    AngleConvention convention = AngleConvention::kZenithAzimuth;
    const Geometry geometry = parse_geometry(args.geometry, convention);
    std::vector<FileArgument> read = inputs;
    read.push_back({"--usgs-wavelengths", args.usgs_wavelengths});
    check_distinct_files(read, outputs);
    const UsgsSpectrum s = read_usgs_spectrum(input, args.usgs_wavelengths);
    if (s.missing > 0) warn(fmt::format("{}: {} missing channels (-1.23e+34) left out", input, s.missing));
    return usgs_dataset(s, geometry, convention);
  }
  if (!args.usgs_wavelengths.empty()) throw InputError("--usgs-wavelengths is for --from usgs");
  AngleConvention convention = AngleConvention::kZenithAzimuth;
  const Geometry geometry = parse_geometry(args.geometry, convention);
  InstrumentSpectrum s = read_instrument_file(input, options.read);
  if (from != ConvertSource::kAuto && from != ConvertSource::kInstrument && name_of(s.format) != name_of(from)) {
    throw InputError(fmt::format("{}: --from {} but the file is a .{} file", input, name_of(from), name_of(s.format)));
  }
  for (const auto& note : s.notes) warn(note);
  return instrument_dataset(s, geometry, convention, quantity);
}

}  // namespace roadbrdf::cli
