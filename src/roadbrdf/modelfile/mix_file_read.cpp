#include "roadbrdf/modelfile/mix_file_read.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/modelfile/fit_file_read.h"
#include "roadbrdf/models/mixture_model.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {

using mixing::MixtureKind;
using mixing::MixtureModel;

bool is_mix_document(const Json& j) {
  return j.is_object() && j.contains("format") && j.at("format") == "roadbrdf-mix";
}

bool is_mix_file(const std::string& path) {
  try {
    return is_mix_document(parse_json_text(read_text_file(path, fit_file_limits()), path));
  } catch (const InputError&) {
    return false;  // not JSON at all: read_spectral_model_file reports it as a fit file
  }
}

namespace {

// Runs `make` and reports an InputError (unknown model, option, mixture kind) at `node`.
template <class Make>
auto located(const JsonNode& node, Make make) -> decltype(make()) {
  try {
    return make();
  } catch (const FileError&) {
    throw;
  } catch (const InputError& e) {
    node.fail(e.what());
  }
}

}  // namespace

SpectralModel read_mix_file(const std::string& path, const std::string& method) {
  return read_mix_file_entry(path, method).model;
}

MixFileEntry read_mix_file_entry(const std::string& path, const std::string& method) {
  return mix_file_entry(parse_json_file(path), input_display_name(path), method);
}

MixFileEntry mix_file_entry(const Json& document, const std::string& name, const std::string& method) {
  const JsonNode root(document, name);
  if (!root.is_object() || root.string_or("format", "") != "roadbrdf-mix") {
    throw FileError(root.file(), 0, 0, "not a roadbrdf mix file (format key)");
  }
  const JsonNode methods = root.at("methods");
  if (methods.size() == 0) methods.fail("no methods in this mix file");
  std::string wanted = method;
  if (wanted.empty()) {
    const auto best = root.find("best");
    wanted = best && best->is_string() ? best->string() : methods[0].at("method").string();
  }
  const JsonNode end_members = root.at("end_members");
  for (const JsonNode& m : methods.elements()) {
    if (m.at("method").string() != wanted) continue;
    const JsonNode model_node = m.at("model");
    const std::string model_name = model_node.string();
    const std::string prefix = "mixture-";
    if (model_name.rfind(prefix, 0) != 0) model_node.fail("unknown model '" + model_name + "' (expected mixture-...)");
    const MixtureKind kind =
        located(model_node, [&] { return parse_name<MixtureKind>(model_name.substr(prefix.size()), "mixture kind"); });
    std::vector<std::shared_ptr<const Model>> models;
    const JsonNode names_node = m.at("end_members");
    const std::vector<std::string> names = names_node.strings();
    for (std::size_t k = 0; k < names.size(); ++k) {
      bool found = false;
      for (const JsonNode& e : end_members.elements()) {
        if (e.at("name").string() != names[k]) continue;
        OptionSet options;
        if (const auto o = e.find("options")) options = o->string_map();
        const JsonNode member_model = e.at("model");
        models.push_back(located(
            member_model, [&] { return std::shared_ptr<const Model>(make_model(member_model.string(), options)); }));
        found = true;
        break;
      }
      if (!found) names_node[k].fail("end-member '" + names[k] + "' is not described in end_members");
    }
    std::vector<bool> coarse;
    if (const auto c = m.find("coarse")) {
      for (const JsonNode& flag : c->elements()) coarse.push_back(flag.boolean());
    }
    auto mixture = located(m, [&] { return std::make_shared<const MixtureModel>(kind, models, names, coarse); });
    const JsonNode wavelength_node = m.at("wavelengths");
    const auto wavelengths = wavelength_node.numbers();
    for (std::size_t w = 1; w < wavelengths.size(); ++w) {
      if (!(wavelengths[w] > wavelengths[w - 1])) wavelength_node[w].fail("wavelengths must be strictly increasing");
    }
    const std::size_t rows = wavelengths.empty() ? 1 : wavelengths.size();
    const auto table = read_parameter_table(m.at("parameters"), mixture->description(), rows, wavelengths);
    if (wavelengths.empty()) return {SpectralModel(mixture, table), wanted};
    SpectralModel model(mixture, wavelengths, table);
    model.set_parameter_covariance(read_parameter_covariance(m, mixture->description(), wavelengths.size()));
    return {std::move(model), wanted};
  }
  methods.fail("no method '" + wanted + "' in this mix file");
}

}  // namespace roadbrdf
