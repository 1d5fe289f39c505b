#include "roadbrdf/io/convert_request.h"

#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/io/curet.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_read_fields.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/io/instrument.h"
#include "roadbrdf/io/manifest.h"
#include "roadbrdf/io/usgs.h"

namespace roadbrdf {

RequestFields<ConvertRequest> ConvertRequest::fields() {
  using R = ConvertRequest;
  static const std::string from_help = "Input format: " + described_names_text<ConvertSource>();
  static const std::string to_help = "Output format: " + names_text<DatasetFormat>() + " (default wide)";
  static const std::string alta_help =
      "ALTA output unit when the file lacks #PARAM_OUT: " + described_names_text<AltaOutput>();
  static const std::string convention_help =
      "Angle columns of the output: " + described_names_text<AngleConvention>() + " (default: as read)";
  // One quantity for both kinds of input: an instrument file's signal to store, or what a dataset
  // CSV's values are (the DatasetReadFields row, with this help).
  static const std::string quantity_help =
      "Instrument signal to store: " + described_names_text<InstrumentQuantity>() +
      " (default target); for a dataset CSV what its values are, converted to BRDF: " +
      described_names_text<DatasetQuantity>() + " (default brdf)";
  static const std::vector<RequestField<R>> rows = [] {
    std::vector<RequestField<R>> all = {
        {"inputs", "INPUT", "",
         "Input file (for CUReT: abrdf.dat); several dataset CSV files (runs of one sample) are combined", &R::inputs,
         FileRole::input, true},
        {"source", "--from", "", from_help, &R::source},
        {"to", "--to", "", to_help, &R::to},
        {"curet_table", "--curet-table", "", "CUReT geometry table (default: table.txt next to the input)",
         &R::curet_table, FileRole::input},
        {"sample", "--sample", "", "CUReT sample number (first column of abrdf.dat)", &R::sample},
        {"wavelength", "--wavelength", "nm",
         "Wavelength to store single-channel data at (ALTA: required; CUReT: "
         "default 550)",
         &R::wavelength},
        {"alta_output", "--alta-output", "", alta_help, &R::alta_output},
        {"exclude_grazing", "--exclude-grazing", "",
         "ALTA BRDF x cos(theta_v): leave out (and report) rows at grazing view, which cannot be converted",
         &R::exclude_grazing},
    };
    for (RequestField<R> row : dataset_read_fields<R>()) {
      if (row.name == "quantity") row.help = quantity_help;
      all.push_back(row);
    }
    const RequestField<R> own[] = {
        {"convention", "--convention", "", convention_help, &R::convention},
        {"geometry", "--geometry", "deg",
         "Geometry of a single instrument file: theta_i=D,phi_i=D,theta_r=D,phi_r=D or gamma=D,alpha=D,beta=D,delta=D",
         &R::geometry},
        {"usgs_wavelengths", "--usgs-wavelengths", "",
         "For a USGS spectrum: the splib07a wavelength file of the spectrum's instrument, e.g. "
         "splib07a_Wavelengths_ASD_0.35-2.5_microns_2151_ch.txt (micrometres)",
         &R::usgs_wavelengths, FileRole::input},
    };
    all.insert(all.end(), std::begin(own), std::end(own));
    const std::vector<RequestField<R>> instrument = instrument_fields<R>();
    all.insert(all.end(), instrument.begin(), instrument.end());
    all.push_back(
        {"output", "-o,--output", "", "Output dataset CSV (default: standard output)", &R::output, FileRole::output});
    return all;
  }();
  return rows;
}

namespace {

// "theta_i=0,phi_i=0,theta_r=30,phi_r=180" (or the road angles) -> geometry and convention.
Geometry parse_geometry(const std::string& text, AngleConvention& convention) {
  if (text.empty()) {
    throw InputError(
        "an instrument file has no geometry: give `geometry` theta_i=D,phi_i=D,theta_r=D,phi_r=D (or "
        "gamma=D,alpha=D,beta=D,delta=D), or convert a manifest with `source` manifest");
  }
  std::map<std::string, double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find(',', start);
    const std::string item = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw FieldError("geometry", "expects NAME=DEGREES, got '" + item + "'");
    const std::string name = item.substr(0, eq);
    double value = 0.0;
    if (!parse_finite_double(item.substr(eq + 1), value)) {
      throw FieldError("geometry", name + ": '" + item.substr(eq + 1) + "' is not a finite number");
    }
    if (!values.emplace(name, value).second) throw FieldError("geometry", name + " is given twice");
    if (end == std::string::npos) break;
    start = end + 1;
  }
  static const std::vector<std::string> zenith = {"theta_i", "phi_i", "theta_r", "phi_r"};
  static const std::vector<std::string> road = {"gamma", "alpha", "beta", "delta"};
  for (const auto* names : {&zenith, &road}) {
    if (values.size() != 4) break;
    bool all = true;
    for (const std::string& n : *names) all = all && values.count(n) == 1;
    if (!all) continue;
    convention = names == &zenith ? AngleConvention::kZenithAzimuth : AngleConvention::kRoad;
    double a[4];
    for (std::size_t k = 0; k < 4; ++k) a[k] = values.at((*names)[k]);
    return geometry_from_angle_values(convention, a);
  }
  throw FieldError("geometry",
                   "give exactly four angles (degrees): theta_i, phi_i, theta_r, phi_r or gamma, alpha, "
                   "beta, delta");
}

// True when `from` is an instrument format, a manifest or USGS, or is auto and the input has an
// instrument file extension (.asd, .sed, .sig).
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

// An instrument file (one row at `geometry`), a manifest (one row per sample) or a USGS spectrum.
// The files a manifest lists are added to `inputs` and checked against `outputs` before any is read.
SpectralDataset convert_instrument_input(const ConvertRequest& request, ConvertSource from,
                                         std::vector<FileArgument> inputs, const std::vector<FileArgument>& outputs) {
  const std::string& input = request.inputs.front();
  const InstrumentQuantity quantity =
      parse_name<InstrumentQuantity>(request.quantity.empty() ? "target" : request.quantity, "quantity");
  const ManifestOptions options = request.manifest_options();
  if (from == ConvertSource::kManifest) {
    if (!request.geometry.empty())
      throw InputError("`geometry` is for a single instrument file: a manifest gives its own");
    const Manifest manifest = read_manifest(input);
    const std::vector<FileArgument> listed = manifest_input_files(manifest);
    inputs.insert(inputs.end(), listed.begin(), listed.end());
    check_distinct_files(inputs, outputs);
    return manifest_dataset(manifest, quantity, options);
  }
  if (from == ConvertSource::kUsgs) {
    if (request.usgs_wavelengths.empty()) {
      throw InputError("`source` usgs needs `usgs_wavelengths` FILE (the splib07a wavelength file of the spectrum)");
    }
    // The file holds the reflectance only (target and reflectance mean the same here); no panel signal.
    if (quantity == InstrumentQuantity::kReference)
      throw InputError("`quantity` reference: a USGS splib07a file holds no reference signal");
    AngleConvention convention = AngleConvention::kZenithAzimuth;
    const Geometry geometry = parse_geometry(request.geometry, convention);
    const UsgsSpectrum s = read_usgs_spectrum(input, request.usgs_wavelengths);
    if (s.missing > 0) route_warning(fmt::format("{}: {} missing channels (-1.23e+34) left out", input, s.missing));
    return usgs_dataset(s, geometry, convention);
  }
  if (!request.usgs_wavelengths.empty()) throw InputError("`usgs_wavelengths` is for `source` usgs");
  AngleConvention convention = AngleConvention::kZenithAzimuth;
  const Geometry geometry = parse_geometry(request.geometry, convention);
  InstrumentSpectrum s = read_instrument_file(input, options.read);
  if (from != ConvertSource::kAuto && from != ConvertSource::kInstrument && name_of(s.format) != name_of(from)) {
    throw InputError(
        fmt::format("{}: `source` {} but the file is a .{} file", input, name_of(from), name_of(s.format)));
  }
  for (const auto& note : s.notes) route_warning(note);
  return instrument_dataset(s, geometry, convention, quantity);
}

}  // namespace

SpectralDataset convert(const ConvertRequest& request) {
  std::vector<FileArgument> inputs, outputs;
  file_arguments(request, ConvertRequest::fields(), inputs, outputs);
  check_distinct_files(inputs, outputs);
  if (request.inputs.empty()) throw FieldError("inputs", "give an input file");
  const std::string& input = request.inputs.front();
  const ConvertSource from = parse_name<ConvertSource>(request.source, "source");
  // Bad output names are refused before any work.
  static_cast<void>(parse_name<DatasetFormat>(request.to, "to"));
  if (!request.alta_output.empty()) static_cast<void>(parse_name<AltaOutput>(request.alta_output, "alta_output"));
  std::optional<AngleConvention> convention;
  if (!request.convention.empty()) convention = parse_name<AngleConvention>(request.convention, "convention");
  const bool runs = from == ConvertSource::kAuto || from == ConvertSource::kWide || from == ConvertSource::kLong;
  if (request.inputs.size() > 1 && !(runs && !is_instrument_input(from, input))) {
    throw InputError("several `inputs` files combine only as dataset CSV files (wide or long)");
  }
  SpectralDataset d;
  if (is_instrument_input(from, input)) {
    d = convert_instrument_input(request, from, inputs, outputs);
  } else if (from == ConvertSource::kCuret) {
    if (!request.sample) {
      std::string list;
      for (int s : curet_sample_numbers(input)) list += fmt::format("{}{}", list.empty() ? "" : " ", s);
      throw InputError("give `sample` N for a CUReT file (samples present: " + list + ")");
    }
    const std::string table = request.curet_table.empty()
                                  ? (std::filesystem::path(input).parent_path() / "table.txt").string()
                                  : request.curet_table;
    check_distinct_files({{"`inputs`", input}, {"`curet_table`", table}}, outputs);
    CuretReadOptions o;
    if (request.wavelength) {
      if (!(std::isfinite(*request.wavelength) && *request.wavelength > 0.0)) {
        throw InputError(fmt::format("`wavelength` {} nm: must be finite and > 0", *request.wavelength));
      }
      o.nominal_wavelength_nm = *request.wavelength;
    }
    d = read_curet(input, table, *request.sample, o);
  } else if (from == ConvertSource::kAlta) {
    AltaReadOptions o;
    o.wavelength_nm = request.wavelength.value_or(0.0);
    o.assumed_output = request.alta_output;
    o.exclude_grazing = request.exclude_grazing;
    o.average_duplicates = request.average_duplicates;
    d = read_alta(input, o);
  } else {  // auto (not an instrument file), wide or long: the CSV reader tells wide from long
    DatasetReadFields read = request;
    if (read.quantity.empty()) read.quantity = "brdf";
    static_cast<void>(read.options_for(input, request.inputs));  // the fields' errors before any file is read
    d = read_dataset_runs(request.inputs, read);
  }
  if (convention) d.convention = *convention;
  write_dataset_output(d, request.output, request.to, "to");
  return d;
}

}  // namespace roadbrdf
