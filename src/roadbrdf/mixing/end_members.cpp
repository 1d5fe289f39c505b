// The end-members of a formulation: its distinct fit files, loaded once (mixing.h load_mix_inputs).
#include <filesystem>

#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/modelfile/fit_file_read.h"

namespace roadbrdf::mixing {

namespace {

std::string stem_of_fit(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  for (const char* suffix : {".fit.json", ".json"}) {
    const std::string s(suffix);
    if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) {
      return name.substr(0, name.size() - s.size());
    }
  }
  return name;
}

}  // namespace

FitLoader fit_loader(const std::map<std::string, std::string>& texts) {
  return [texts](const std::string& path, const std::string& model) {
    const auto given = texts.find(path);
    return given == texts.end() ? read_fit_file(path, model) : parse_fit_file(given->second, path, model);
  };
}

MixInputs load_mix_inputs(const Formulation& formulation, const FitLoader& loader_in) {
  const FitLoader loader = loader_in ? loader_in : FitLoader([](const std::string& path, const std::string& model) {
    return read_fit_file(path, model);
  });
  MixInputs inputs;
  inputs.formulation = formulation;
  const std::string where = formulation.path.empty() ? std::string("<formulation>") : formulation.path;
  auto find_or_add = [&](const std::string& path, const std::string& fit_model, const std::string& key) {
    for (std::size_t e = 0; e < inputs.end_members.size(); ++e) {
      if (inputs.end_members[e].fit_path == path && inputs.end_members[e].fit_model == fit_model) return e;
    }
    EndMember m;
    m.fit_path = path;
    m.fit_model = fit_model;
    m.name = stem_of_fit(path);
    if (!fit_model.empty()) m.name += "[" + fit_model + "]";
    // Unique names.
    std::string base = m.name;
    for (int count = 2;; ++count) {
      bool clash = false;
      for (const auto& other : inputs.end_members) clash = clash || other.name == m.name;
      if (!clash) break;
      m.name = base + "#" + std::to_string(count);
    }
    try {
      m.model = std::make_shared<const SpectralModel>(loader(path, fit_model));
    } catch (const InputError& e) {
      throw FileError(where, 0, 0, key + ": cannot use fit file '" + path + "': " + e.what());
    }
    inputs.end_members.push_back(std::move(m));
    return inputs.end_members.size() - 1;
  };
  for (std::size_t i = 0; i < formulation.components.size(); ++i) {
    const Component& c = formulation.components[i];
    const std::string path = c.fit_path.empty() ? c.fit : c.fit_path;
    const std::size_t e =
        find_or_add(path, c.fit_model, "components[" + std::to_string(i) + "] (\"" + c.name + "\").fit");
    inputs.end_members[e].components.push_back(i);
  }
  if (formulation.mastic) {
    const std::string path =
        formulation.mastic->fit_path.empty() ? formulation.mastic->fit : formulation.mastic->fit_path;
    const std::size_t e = find_or_add(path, formulation.mastic->fit_model, "mastic.fit");
    inputs.end_members[e].is_mastic = true;
  }
  return inputs;
}

}  // namespace roadbrdf::mixing
