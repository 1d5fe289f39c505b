// The r-table request's field table (core/request_fields.h) and its task: the source resolved (a
// model by the one resolver of model arguments, or an r-table file), the report of rtable_request.cpp,
// the comparison and the output file.
#include <string>
#include <utility>

#include "roadbrdf/core/error.h"
#include "roadbrdf/modelfile/fit_file_read.h"
#include "roadbrdf/modelfile/model_source.h"
#include "roadbrdf/photometry/rtable_request.h"

namespace roadbrdf::photometry {

namespace {

using R = RTableRequest;

// The report's comparison with `compare` and its output file, the steps after the table.
void compare_and_write(RTableReport& report, const RTableRequest& request) {
  if (!request.compare.empty()) {
    report.compare_with(read_rtable(request.compare, std::nullopt, request.alpha, kRScale).table, request.compare);
  }
  if (!request.output.empty()) {
    const RTableFormat format = request.output_format();
    write_rtable_file(request.output, report.table, format);
    report.output = {{"file", request.output}, {"format", name_of(format)}};
  }
}

}  // namespace

std::span<const RequestField<RTableRequest>> RTableRequest::fields() {
  // Help texts that list an enumeration's names are made once from its table (core/enum_names.h).
  static const std::string import_format_help =
      "Format of the imported file when its extension does not tell: " + names_text<RTableFormat>();
  static const std::string format_help = "Table format: " + described_names_text<RTableFormat>() +
                                         " (default: from the output's extension, else csv); " + "all store 1e4 r";
  static const std::string q0_region_help =
      "Q0 averaging region: " + described_names_text<Q0Region>() + " (default standard)";
  static const std::string class_system_help =
      "Class reported as 'class': " + names_text<ClassSystem>() + " (default R)";
  static const std::vector<RequestField<R>> rows = [] {
    std::vector<RequestField<R>> all = model_source_fields<R>();
    // The model is one of two sources here: `import_file` is the other, so it is not required.
    for (RequestField<R>& row : all) {
      if (row.name == "model") row.required = false;
    }
    const RequestField<R> own[] = {
        {"import_file", "--import", "",
         "Read an r-table file instead of computing one (.csv, .rtb, .dat Radiance; 0 = missing cell)", &R::import_file,
         FileRole::input},
        {"import_format", "--import-format", "", import_format_help, &R::import_format},
        {"scale", "--scale", "", "Imported file values are r times this (default 1e4; e.g. 1 for plain r)", &R::scale},
        {"alpha", "--alpha", "deg", "Observation angle above the road plane (default 1)", &R::alpha},
        {"illuminant", "--illuminant", "",
         "Photometric weighting V(lambda) x S(lambda) of a spectral model: A (default), D65, or a lamp spectrum CSV "
         "(wavelength_nm, relative power)",
         &R::illuminant, FileRole::input},
        {"wavelength", "--wavelength", "nm", "Use the spectral model at one wavelength instead", &R::wavelength},
        {"band", "--band", "nm", "Use the unweighted mean over a band A:B instead", &R::band},
        {"format", "--format", "", format_help, &R::format},
        {"output", "-o,--output", "", "Write the table here (atomically); default: standard output", &R::output,
         FileRole::output},
        {"compare", "--compare", "",
         "Compare with another r-table file (reference): max/mean relative difference, Q0 and S1 differences",
         &R::compare, FileRole::input},
        {"q0_region", "--q0-region", "", q0_region_help, &R::q0_region},
        {"class_system", "--class-system", "", class_system_help, &R::class_system},
    };
    all.insert(all.end(), std::begin(own), std::end(own));
    return all;
  }();
  return rows;
}

RTableFormat RTableRequest::output_format() const {
  if (!format.empty()) return rtable_format_from_name(format, "format");
  return rtable_format_from_path(output).value_or(RTableFormat::csv);
}

RTableReport rtable(const RTableRequest& request) {
  const bool from_import = !request.import_file.empty();
  if (from_import == !request.model.empty()) {
    throw InputError(
        "give either a `model` (a model name, FIT.json or MIX.json) or an `import_file`, not both and not neither");
  }
  check_request_files(request);
  request.output_format();  // a bad name is refused before any work
  RTableReport report;
  if (from_import) {
    const std::pair<const char*, bool> model_fields[] = {{"parameters", !request.parameters.empty()},
                                                         {"options", !request.options.empty()},
                                                         {"fit", !request.fit.empty()}};
    for (const auto& [field, given] : model_fields) {
      if (given) throw FieldError(field, "does not apply to a finished r-table read from `import_file`");
    }
    request.validate_for_import();
    std::optional<RTableFormat> format;
    if (!request.import_format.empty()) format = rtable_format_from_name(request.import_format, "import_format");
    RTableFile file = read_rtable(request.import_file, format, request.alpha, request.scale);
    nlohmann::json source = {
        {"import", request.import_file}, {"format", name_of(file.format)}, {"scale", request.scale}};
    report = rtable_report(std::move(file), request);
    report.source = std::move(source);
  } else {
    if (!request.import_format.empty()) throw FieldError("import_format", "applies to `import_file` only");
    if (request.scale != kRScale) throw FieldError("scale", "applies to `import_file` only");
    request.validate();
    const ResolvedModel resolved = request.resolve();
    report = rtable_report(resolved.model, request);
    const std::string name = resolved.model.model().name();
    report.source = {{"model", name}};
    if (is_fit_file_argument(request.model)) {
      report.table.name = request.model + " (" + name + ")";
      report.source["fit_file"] = request.model;
    }
  }
  compare_and_write(report, request);
  return report;
}

RTableReport rtable(const SpectralModel& model, const RTableRequest& request) {
  const std::pair<const char*, bool> source_fields[] = {{"model", !request.model.empty()},
                                                        {"parameters", !request.parameters.empty()},
                                                        {"options", !request.options.empty()},
                                                        {"fit", !request.fit.empty()},
                                                        {"import_file", !request.import_file.empty()},
                                                        {"import_format", !request.import_format.empty()},
                                                        {"scale", request.scale != kRScale}};
  for (const auto& [field, given] : source_fields) {
    if (given) throw FieldError(field, "does not apply to a model given as an object (a Model or SpectralModel)");
  }
  check_request_files(request);
  request.output_format();
  RTableReport report = rtable_report(model, request);
  report.source = {{"model", model.model().name()}};
  compare_and_write(report, request);
  return report;
}

}  // namespace roadbrdf::photometry
