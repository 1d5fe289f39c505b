#include "roadbrdf/io/simulate_request.h"

#include <algorithm>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/io/simulate.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace roadbrdf {

RequestFields<SimulateRequest> SimulateRequest::fields() {
  using R = SimulateRequest;
  static const std::string format_help = "Output format: " + names_text<DatasetFormat>() + " (default wide)";
  static const std::vector<RequestField<R>> rows = [] {
    std::vector<RequestField<R>> all = model_source_fields<R>();
    const RequestField<R> own[] = {
        {"grid", "--grid", "", "Geometry grid CSV: theta_i,phi_i,theta_r,phi_r or gamma,alpha,beta,delta [deg]",
         &R::grid, FileRole::input, true},
        {"wavelengths", "--wavelengths", "nm",
         "Wavelengths: START:STOP:STEP (both ends included), a list or a mix, increasing (default: the fit's "
         "wavelengths)",
         &R::wavelengths},
        {"spectral", "--spectral", "",
         "Parameter given as a spectrum NAME=FILE (wavelength [nm], value; linear interpolation, no "
         "extrapolation), e.g. albedo=bitumen-albedo.csv; repeatable",
         &R::spectral},
        {"noise", "--noise", "",
         "Noise model: none, or relative=R,absolute=A[sr^-1],edge=E,edge-width=W[nm],water=F,detector-min=NM,"
         "detector-max=NM (sigma = sqrt((R f)^2 + A^2) x spectral shape)",
         &R::noise},
        {"seed", "--seed", "", "Seed of the noise (same seed, same data)", &R::seed},
        {"digits", "--digits", "",
         "Round values to N significant digits as an instrument file would (0 = full precision; sigma to 2)",
         &R::digits},
        {"sigma", "--no-sigma", "", "Do not write the noise standard deviation as sigma_<nm> columns", &R::sigma},
        {"metadata", "--metadata", "", "Extra metadata KEY=VALUE written as '# key: value' (repeatable)", &R::metadata},
        {"format", "--format", "", format_help, &R::format},
        {"output", "-o,--output", "", "Output dataset CSV (default: standard output)", &R::output, FileRole::output},
    };
    all.insert(all.end(), std::begin(own), std::end(own));
    return all;
  }();
  return rows;
}

namespace {

// NAME=VALUE items of `field`, split at the first '='; a name given twice is an error.
std::map<std::string, std::string> named_items(const std::vector<std::string>& items, const std::string& field) {
  std::map<std::string, std::string> out;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw FieldError(field, "expects NAME=VALUE, got '" + item + "'");
    if (!out.emplace(item.substr(0, eq), item.substr(eq + 1)).second) {
      throw FieldError(field + "." + item.substr(0, eq), "is given twice");
    }
  }
  return out;
}

}  // namespace

SpectralDataset simulate(const SimulateRequest& request) {
  if (request.model.empty()) throw FieldError("model", "give a model name or a FIT.json");
  if (request.grid.empty()) throw FieldError("grid", "give a geometry grid CSV");
  const std::map<std::string, std::string> spectra_files = named_items(request.spectral, "spectral");
  const std::map<std::string, std::string> metadata = named_items(request.metadata, "metadata");
  std::vector<FileArgument> spectrum_inputs;
  for (const auto& [name, file] : spectra_files) spectrum_inputs.push_back({"`spectral`", file});
  check_request_files(request, spectrum_inputs);
  if (request.digits < 0 || request.digits > 17) throw FieldError("digits", "must be in [0, 17]");
  // A bad format name is refused before any work.
  static_cast<void>(parse_name<DatasetFormat>(request.format, "format"));
  const NoiseModel noise = parse_noise_model(request.noise);
  const SpectralModel model = request.resolve().model;
  const GeometryTable grid = read_geometry_file(request.grid);
  SimulationInput in;
  in.model = &model;
  in.geometries = grid.geometries;
  in.convention = grid.convention;
  if (!request.wavelengths.empty()) {
    check_range_values(request.wavelengths, "wavelengths", wavelength_rules());
    in.wavelengths = request.wavelengths;
  } else if (model.is_spectral()) {
    in.wavelengths = model.wavelengths();
  } else {
    throw FieldError("wavelengths", "give START:STOP:STEP [nm] (the model is not spectral)");
  }
  for (const auto& item : spectra_files) {
    const std::string prefix = item.first + "=";
    const bool also_fixed = std::any_of(request.parameters.begin(), request.parameters.end(),
                                        [&prefix](const std::string& p) { return p.rfind(prefix, 0) == 0; });
    if (also_fixed) throw FieldError("spectral." + item.first, "is given both as a spectrum and in `parameters`");
    in.spectral_parameters[item.first] = spectra::read_spectrum(item.second);
  }
  in.noise = noise;
  in.seed = request.seed;
  in.write_sigma = request.sigma;
  in.significant_digits = request.digits;
  SpectralDataset d = simulate_dataset(in);
  d.metadata["grid"] = request.grid;
  for (const auto& [key, value] : metadata) d.metadata[key] = value;
  write_dataset_output(d, request.output, request.format);
  return d;
}

}  // namespace roadbrdf
