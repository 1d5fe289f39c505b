#include "roadbrdf/modelfile/model_source.h"

#include <memory>
#include <utility>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/modelfile/fit_file_read.h"
#include "roadbrdf/modelfile/mix_file_read.h"
#include "roadbrdf/modelfile/model_by_name.h"
#include "roadbrdf/modelfile/model_source_fields.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {

namespace {

bool is_model_name(const std::string& name) {
  if (name.find('+') != std::string::npos && name.find_first_of("./") == std::string::npos) return true;  // composite
  for (const std::string& m : model_names()) {
    if (m == name) return true;
  }
  for (const ModelAlias& a : model_aliases()) {
    if (a.name == name) return true;
  }
  return false;
}

// Every '+'-separated part of `name` is a single model or an alias: an error of make_model is then
// about the options.
bool every_part_is_a_model(const std::string& name) {
  std::size_t start = 0;
  while (true) {
    const std::size_t end = name.find('+', start);
    const std::string part = name.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (part.empty() || part.find('+') != std::string::npos || !is_model_name(part)) return false;
    if (end == std::string::npos) return true;
    start = end + 1;
  }
}

}  // namespace

RequestFields<ModelSourceFields> ModelSourceFields::fields() {
  using R = ModelSourceFields;
  static const RequestField<R> rows[] = {
      {"model", "MODEL", "", "Model name (e.g. oren-nayar or lambert+torrance-sparrow, with -p), FIT.json or MIX.json",
       &R::model, FileRole::input, true},
      {"parameters", "-p,--parameter", "", "Model parameter NAME=VALUE (repeatable); defaults otherwise",
       &R::parameters},
      {"options", "--option", "", "Model option NAME=VALUE (repeatable), e.g. distribution=ggx", &R::options},
      {"fit", "--fit", "",
       "Which fit of FIT.json (its model name, e.g. lambert+torrance-sparrow) or which method of a MIX.json "
       "(default: the best-ranked)",
       &R::fit},
  };
  return rows;
}

std::string source_kind(const std::string& source) {
  if (source.size() > 5 && source.compare(source.size() - 5, 5, ".json") == 0) return "fit";
  if (is_model_name(source)) return "model";
  return "data";
}

std::map<std::string, std::string> assignments(const std::vector<std::string>& items, const std::string& field) {
  std::map<std::string, std::string> out;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size()) {
      throw FieldError(field, "expected NAME=VALUE, got '" + item + "'");
    }
    if (!out.emplace(item.substr(0, eq), item.substr(eq + 1)).second) {
      throw FieldError(field, "'" + item.substr(0, eq) + "' is given twice");
    }
  }
  return out;
}

SpectralModel spectral_model_with(const std::string& name, const std::map<std::string, double>& parameters,
                                  const OptionSet& options) {
  std::unique_ptr<Model> model;
  try {
    model = make_model(name, options);
  } catch (const FieldError&) {
    throw;
  } catch (const InputError& e) {
    throw FieldError(every_part_is_a_model(name) ? "options" : "model", e.what());
  }
  std::vector<double> p;
  try {
    p = parameters_from_assignments(model->description(), parameters);
  } catch (const FieldError&) {
    throw;
  } catch (const InputError& e) {
    throw FieldError("parameters", e.what());
  }
  return SpectralModel(std::shared_ptr<const Model>(std::move(model)), std::move(p));
}

SpectralModel spectral_model_from_assignments(const std::string& name, const std::vector<std::string>& parameters,
                                              const std::vector<std::string>& options) {
  const std::map<std::string, std::string> option_map = assignments(options, "options");
  std::map<std::string, double> values;
  for (const auto& [key, text] : assignments(parameters, "parameters")) {
    double v = 0.0;
    if (!parse_finite_double(text, v)) throw FieldError("parameters", "'" + text + "' is not a finite number");
    values[key] = v;
  }
  return spectral_model_with(name, values, OptionSet(option_map.begin(), option_map.end()));
}

ResolvedModel read_model_file(const std::string& path, const std::string& selection) {
  // One parse (a fit file of a few models at 2151 wavelengths is 8 MB of JSON), then its "format".
  const std::string name = input_display_name(path);
  const Json document = parse_json_text(read_text_file(path, fit_file_limits()), name);
  if (is_mix_document(document)) {
    MixFileEntry mix = mix_file_entry(document, name, selection);
    return {std::move(mix.model), "mix", std::move(mix.entry)};
  }
  FitFileEntry fit = fit_file_entry(document, name, selection);  // reports a file that is neither as a fit file
  return {std::move(fit.model), "fit", std::move(fit.entry)};
}

SpectralModel read_spectral_model_file(const std::string& path, const std::string& selection) {
  return read_model_file(path, selection).model;
}

ResolvedModel resolve_model(const std::string& source, const std::vector<std::string>& parameters,
                            const std::vector<std::string>& options, const std::string& fit) {
  if (source_kind(source) == "fit") {
    if (!parameters.empty()) throw FieldError("parameters", "apply to a model, not to a fit file ('" + source + "')");
    if (!options.empty()) throw FieldError("options", "apply to a model, not to a fit file ('" + source + "')");
    return read_model_file(source, fit);
  }
  if (!fit.empty()) throw FieldError("fit", "selects a fit of a fit file; '" + source + "' is a model name");
  SpectralModel model = spectral_model_from_assignments(source, parameters, options);
  std::string name = model.model().name();
  return {std::move(model), "model", std::move(name)};
}

SpectralModel spectral_model_of(const std::string& source, const std::vector<std::string>& parameters,
                                const std::vector<std::string>& options, const std::string& fit) {
  return resolve_model(source, parameters, options, fit).model;
}

}  // namespace roadbrdf
