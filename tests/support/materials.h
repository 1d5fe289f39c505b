// Test support: material specifications for virtual surfaces (surface/height_field.h).
#pragma once

#include <map>
#include <string>
#include <utility>

#include "roadbrdf/surface/height_field.h"

namespace roadbrdf::test {

// A model material named after the model, with the given parameters and options.
inline surface::MaterialSpec model_material(const std::string& model, std::map<std::string, double> params,
                                            std::map<std::string, std::string> options = {}) {
  surface::MaterialSpec m;
  m.name = model;
  m.model = model;
  m.parameters = std::move(params);
  m.options = std::move(options);
  return m;
}

// A Lambertian material of the given albedo.
inline surface::MaterialSpec lambert(double albedo, const std::string& name = "lambert") {
  surface::MaterialSpec m = model_material("lambert", {{"albedo", albedo}});
  m.name = name;
  return m;
}

}  // namespace roadbrdf::test
