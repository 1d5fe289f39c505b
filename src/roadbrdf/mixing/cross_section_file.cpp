// Calibrated intimate mixing: the calibration file and the request of the front ends (calibration.h).
#include <fmt/core.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/formulation/formulation.h"
#include "roadbrdf/mixing/calibration.h"

namespace roadbrdf::mixing {

namespace {

using ordered = nlohmann::ordered_json;

ordered number_or_null(double x) { return std::isfinite(x) ? ordered(x) : ordered(nullptr); }

constexpr const char* kFormat = "roadbrdf-cross-sections";

// A documentation value: a number or null.
void check_number_or_null(const JsonNode& node) {
  if (!node.is_null()) node.number();
}

}  // namespace

void write_cross_section_file(const std::string& path, const CrossSectionFile& content) {
  const CrossSectionCalibration& c = content.calibration;
  ordered j;
  j["format"] = kFormat;
  j["version"] = 1;
  j["roadbrdf_version"] = version();
  j["method"] = "hapke";
  j["reference"] = c.reference;
  j["units"] = {{"cross_section_factor", "1: multiplies M/(rho D) of the end-member (reference = 1)"},
                {"rms", "1: reflectance factor R = pi f, root mean square over geometries and wavelengths"}};
  ordered members = ordered::array();
  for (std::size_t i = 0; i < c.end_members.size(); ++i) {
    members.push_back({{"name", c.end_members[i]},
                       {"fit", i < c.end_member_fits.size() ? c.end_member_fits[i] : std::string()},
                       {"cross_section_factor", c.factors[i]},
                       {"standard_error", number_or_null(c.standard_errors[i])}});
  }
  j["end_members"] = members;
  ordered mixtures = ordered::array();
  for (std::size_t m = 0; m < c.mixtures.size(); ++m) {
    mixtures.push_back({{"name", c.mixtures[m]},
                        {"formulation", m < content.formulations.size() ? content.formulations[m] : std::string()},
                        {"data", m < content.data.size() ? content.data[m] : std::string()},
                        {"rms_uncalibrated", number_or_null(c.rms_uncalibrated[m])},
                        {"rms_calibrated", number_or_null(c.rms_calibrated[m])}});
  }
  j["mixtures"] = mixtures;
  j["rms_uncalibrated"] = number_or_null(c.rms_uncalibrated_all);
  j["rms_calibrated"] = number_or_null(c.rms_calibrated_all);
  j["residuals"] = c.residual_count;
  j["iterations"] = c.iterations;
  j["notes"] = c.notes;
  AtomicFile out(path);
  write_json(out.stream(), j, 1);
  out.stream() << '\n';
  out.commit();
}

std::map<std::string, double> read_cross_section_factors(const std::string& path) {
  const Json doc = parse_json_file(path);
  const JsonNode root(doc, path);
  if (!root.is_object()) root.fail("must be a JSON object (a calibration file written by `roadbrdf mix-calibrate`)");
  root.check_keys({"format", "version", "roadbrdf_version", "method", "reference", "units", "end_members", "mixtures",
                   "rms_uncalibrated", "rms_calibrated", "residuals", "iterations", "notes"});
  if (root.at("format").string() != kFormat) root.at("format").fail(std::string("must be \"") + kFormat + "\"");
  root.at("version").integer(1, 1);
  if (const auto m = root.find("method"); m && m->string() != "hapke") m->fail("must be \"hapke\"");
  const JsonNode members = root.at("end_members");
  if (members.size() == 0) members.fail("must list at least one end-member");
  std::map<std::string, double> factors;
  for (const JsonNode& e : members.elements()) {
    e.check_keys({"name", "fit", "cross_section_factor", "standard_error"});
    const std::string name = e.at("name").string();
    if (name.empty()) e.at("name").fail("must not be empty");
    if (factors.count(name)) e.at("name").fail("'" + name + "' is listed twice");
    const JsonNode k = e.at("cross_section_factor");
    const double value = k.number();
    if (!(value > 0.0)) k.fail("must be > 0");
    if (const auto se = e.find("standard_error")) check_number_or_null(*se);
    if (const auto fit = e.find("fit")) fit->string();
    factors[name] = value;
  }
  if (const auto ref = root.find("reference")) {
    if (!factors.count(ref->string())) ref->fail("'" + ref->string() + "' is not one of end_members");
  }
  if (const auto mixtures = root.find("mixtures")) {
    for (const JsonNode& m : mixtures->elements()) {
      m.check_keys({"name", "formulation", "data", "rms_uncalibrated", "rms_calibrated"});
      for (const char* key : {"rms_uncalibrated", "rms_calibrated"}) {
        if (const auto x = m.find(key)) check_number_or_null(*x);
      }
    }
  }
  for (const char* key : {"rms_uncalibrated", "rms_calibrated"}) {
    if (const auto x = root.find(key)) check_number_or_null(*x);
  }
  if (const auto notes = root.find("notes")) notes->strings();
  return factors;
}

namespace {

// The measured mixtures' files, which the dataset-reading fields' FILE: prefixes may name.
std::vector<std::string> data_files(const CrossSectionRequest& request) {
  std::vector<std::string> files;
  for (std::size_t m = 0; m < request.mixture_count(); ++m) files.push_back(request.data_file(m));
  return files;
}

}  // namespace

RequestFields<CrossSectionRequest> CrossSectionRequest::fields() {
  using R = CrossSectionRequest;
  static const std::vector<RequestField<R>> table = [] {
    std::vector<RequestField<R>> rows = {
        {"mixtures", "MIXTURES", "",
         "Pairs FORMULATION.json DATA.csv: each measured mixture's formulation and measured BRDF", &R::mixtures,
         FileRole::input, true},
    };
    for (const RequestField<R>& row : dataset_read_fields<R>()) rows.push_back(row);
    rows.push_back({"reference", "--reference", "",
                    "End-member whose factor is fixed at 1 (default: the first end-member of the first mixture)",
                    &R::reference});
    rows.push_back({"output", "-o,--output", "",
                    "Output calibration file (JSON, see src/roadbrdf/mixing/calibration.h)", &R::output,
                    FileRole::output});
    return rows;
  }();
  return table;
}

void CrossSectionRequest::validate() const {
  if (mixtures.empty()) throw FieldError("mixtures", "give at least one measured mixture (formulation and data)");
  if (mixtures.size() % 2 != 0) {
    throw FieldError("mixtures",
                     fmt::format("give pairs of a formulation and its measured data ({} {} given: the last one "
                                 "has no partner)",
                                 mixtures.size(), mixtures.size() == 1 ? "file" : "files"));
  }
  for (std::size_t k = 0; k < mixtures.size(); ++k) {
    if (mixtures[k].empty()) throw FieldError("mixtures", fmt::format("file {} is empty", k + 1));
  }
  for (std::size_t m = 0; m < mixture_count(); ++m) options_for(data_file(m), data_files(*this));
}

CrossSectionRun run_cross_section_calibration(const CrossSectionRequest& request) {
  request.validate();
  std::vector<FileArgument> read;
  for (std::size_t m = 0; m < request.mixture_count(); ++m) {
    read.push_back({"formulation " + request.formulation_file(m), request.formulation_file(m)});
    read.push_back({"data " + request.data_file(m), request.data_file(m)});
  }
  const std::vector<FileArgument> outputs = {{"`output`", request.output}};
  check_distinct_files(read, outputs);
  // The fit files the formulations name are inputs too.
  std::vector<Formulation> formulations;
  formulations.reserve(request.mixture_count());
  for (std::size_t m = 0; m < request.mixture_count(); ++m) {
    formulations.push_back(read_formulation(request.formulation_file(m)));
    const std::vector<FileArgument> fits = formulation_input_files(formulations.back());
    read.insert(read.end(), fits.begin(), fits.end());
  }
  check_distinct_files(read, outputs);
  std::vector<MixInputs> inputs;
  std::vector<SpectralDataset> data;
  inputs.reserve(request.mixture_count());
  data.reserve(request.mixture_count());
  for (std::size_t m = 0; m < request.mixture_count(); ++m) {
    inputs.push_back(load_mix_inputs(formulations[m]));
    data.push_back(read_dataset(request.data_file(m), request.options_for(request.data_file(m), data_files(request))));
  }
  std::vector<CalibrationMixture> mixtures;
  std::set<std::string> names;
  for (std::size_t m = 0; m < inputs.size(); ++m) {
    std::string name = inputs[m].formulation.name;
    if (!names.insert(name).second) name = fmt::format("{} ({})", name, request.formulation_file(m));
    mixtures.push_back({name, &inputs[m], &data[m]});
  }
  CrossSectionRun run;
  run.content.calibration = calibrate_cross_sections(mixtures, request.reference);
  for (std::size_t m = 0; m < request.mixture_count(); ++m) {
    run.content.formulations.push_back(request.formulation_file(m));
    run.content.data.push_back(request.data_file(m));
  }
  if (!request.output.empty()) write_cross_section_file(request.output, run.content);
  return run;
}

std::string CrossSectionRun::table() const {
  const CrossSectionCalibration& c = content.calibration;
  std::string out = fmt::format("{:<20} {:>14} {:>14}\n", "mixture", "RMS(k=1)", "RMS(calibrated)");
  for (std::size_t m = 0; m < c.mixtures.size(); ++m) {
    out += fmt::format("{:<20} {:>14.4f} {:>14.4f}\n", c.mixtures[m], c.rms_uncalibrated[m], c.rms_calibrated[m]);
  }
  out += fmt::format("{:<20} {:>14.4f} {:>14.4f}   (reflectance factor, {} values)\n", "all", c.rms_uncalibrated_all,
                     c.rms_calibrated_all, c.residual_count);
  out += fmt::format("{:<20} {:>14} {:>14}\n", "end-member", "factor k", "SE(k)");
  for (std::size_t i = 0; i < c.end_members.size(); ++i) {
    out += fmt::format(
        "{:<20} {:>14.5g} {:>14}\n", c.end_members[i], c.factors[i],
        c.end_members[i] == c.reference ? std::string("(reference)") : fmt::format("{:.3g}", c.standard_errors[i]));
  }
  for (const std::string& note : c.notes) out += "note: " + note + "\n";
  return out;
}

}  // namespace roadbrdf::mixing
