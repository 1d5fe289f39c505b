// The model variants the property tests run over (defaults, then each enumerated option value one at a
// time), random parameters inside the declared bounds, and the test-name helpers.
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::test {

struct Variant {
  std::string model;
  OptionSet options;
  std::string label;
};

// Every combination of a model's enumerated option values (numeric options keep their default).
inline std::vector<OptionSet> option_combinations(const ModelDescription& d) {
  std::vector<OptionSet> combos = {{}};
  for (const OptionInfo& o : d.options) {
    if (o.values.empty()) continue;
    std::vector<OptionSet> next;
    for (const OptionSet& c : combos) {
      for (const std::string& v : o.values) {
        OptionSet e = c;
        e[o.name] = v;
        next.push_back(e);
      }
    }
    combos = next;
  }
  return combos;
}

// Defaults, then each enumerated option set to each of its non-default values (one at a time).
// Where a value is only valid together with other non-default options (e.g. a distribution that
// needs another masking profile), the first valid combination containing it is used.
inline std::vector<Variant> all_variants() {
  std::vector<Variant> variants;
  for (const std::string& name : model_names()) {
    const ModelDescription d = make_model(name)->description();
    variants.push_back({name, {}, name});
    const std::vector<OptionSet> combos = option_combinations(d);
    for (const OptionInfo& o : d.options) {
      for (const std::string& v : o.values) {
        if (v == o.default_value) continue;
        OptionSet chosen = {{o.name, v}};
        bool valid = true;
        try {
          make_model(name, chosen);
        } catch (const InputError&) {
          valid = false;
          for (const OptionSet& c : combos) {
            if (c.at(o.name) != v) continue;
            try {
              make_model(name, c);
              chosen = c;
              valid = true;
              break;
            } catch (const InputError&) {
            }
          }
        }
        if (!valid) continue;  // a value valid in no combination would be a bug caught below
        std::string label = name;
        for (const auto& [key, value] : chosen) label += "_" + key + "_" + value;
        variants.push_back({name, chosen, label});
      }
    }
  }
  return variants;
}

inline void PrintTo(const Variant& v, std::ostream* os) { *os << v.label; }

inline std::string test_name(const testing::TestParamInfo<Variant>& info) {
  std::string s = info.param.label;
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return s;
}

inline std::vector<double> random_parameters(const ModelDescription& d, Rng& rng, double margin = 0.0) {
  std::vector<double> p;
  for (const ParameterInfo& info : d.parameters) {
    double lo = info.lower;
    double hi = info.upper;
    // Very wide ranges (e.g. Phong exponents) are sampled log-uniformly so that the whole
    // range is exercised, not only its top decade.
    const double width = hi - lo;
    lo += margin * width;
    hi -= margin * width;
    if (lo > 0.0 && hi / lo > 1e3) {
      p.push_back(lo * std::pow(hi / lo, rng.uniform()));
    } else {
      p.push_back(lo + (hi - lo) * rng.uniform());
    }
  }
  return p;
}

}  // namespace roadbrdf::test
