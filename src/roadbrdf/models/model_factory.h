// How the registry makes a model: each model's source file (models/<name>.cpp) defines its factory,
// so that the model's code, and its ceres::Jet instantiations for the fitter, compile in that file
// alone (in parallel with the others, and again only when that model changes). The registry
// (registry.cpp) lists the factories and does the look-up, aliases and composites.
//
// A new model is its header (the struct, model.h), its source file
//   #include "roadbrdf/models/my_model.h"
//   #include "roadbrdf/models/model_factory.h"
//   namespace roadbrdf {
//   ModelFactory my_model_factory() { return factory_of<MyModel>(); }
//   }
// its line in the list below and in registry.cpp's table, and its tests.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/models/model.h"

namespace roadbrdf {

struct ModelFactory {
  std::string_view name;
  // The model under `name` (its own or one of its aliases).
  std::unique_ptr<Model> (*make)(const OptionSet& options, const std::string& name);
  // The other names it is known by (ModelAlias), each with options it fixes.
  std::vector<ModelAlias> (*aliases)();
};

template <class M>
concept HasAliases = requires {
  M::aliases();
};

template <class M>
ModelFactory factory_of() {
  ModelFactory factory;
  factory.name = M::kName;
  factory.make = [](const OptionSet& options, const std::string& name) -> std::unique_ptr<Model> {
    return std::make_unique<ModelAdapter<M>>(options, name);
  };
  if constexpr (HasAliases<M>) {
    factory.aliases = [] { return M::aliases(); };
  } else {
    factory.aliases = [] { return std::vector<ModelAlias>{}; };
  }
  return factory;
}

// The factories, one per model source file (in display order in registry.cpp).
ModelFactory lambert_factory();
ModelFactory oren_nayar_factory();
ModelFactory ashikhmin_shirley_factory();
ModelFactory simonot_factory();
ModelFactory lafortune_factory();
ModelFactory retro_phong_factory();
ModelFactory torrance_sparrow_factory();
ModelFactory kelemen_szirmay_kalos_factory();
ModelFactory burley_factory();
ModelFactory hapke_factory();
ModelFactory ross_li_factory();
ModelFactory rpv_factory();
// [model-factories]

}  // namespace roadbrdf
