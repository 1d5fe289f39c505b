// The metadata claim ModelDescription::mirror_lobe = false ("no lobe about the mirror direction that
// the (mu, dphi) rule's first nodes could miss at grazing incidence"), which lets black_sky() skip its
// grazing cross-check with the mirror-polar rule (hemisphere.h), checked where it matters: for every
// registered model and option that declares it, at every corner of its parameter box (its physical
// range) and at its defaults, and at sun zeniths from 70 to 89.9 deg, the (mu, dphi) rule alone and the
// mirror-polar rule (an independent parameterisation of the hemisphere, centred on the mirror
// direction) agree within their error estimates and the tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf::albedo {
namespace {

// Every model, and every value of each of its options with the others at their defaults (the
// combinations the registry refuses, e.g. a distribution without a masking function for the default
// profile, left out), by name and options.
struct Variant {
  std::string name;
  OptionSet options;
};

std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (const std::string& name : model_names()) {
    out.push_back({name, {}});
    const ModelDescription d = make_model(name)->description();
    for (const OptionInfo& o : d.options) {
      for (const std::string& v : o.values) {
        if (v != o.default_value) out.push_back({name, {{o.name, v}}});
      }
    }
  }
  return out;
}

// The corners of the parameter box (every parameter at either end of its physical range, where values
// given with -p or fitted with --bounds may lie) and the defaults.
std::vector<double> parameter_sets(const ModelDescription& d) {
  const std::size_t P = d.parameters.size();
  std::vector<double> sets = d.default_parameters();
  for (std::size_t corner = 0; corner < (std::size_t{1} << P); ++corner) {
    for (std::size_t k = 0; k < P; ++k) {
      const auto [lower, upper] = d.physical_range(k);
      sets.push_back(((corner >> k) & 1U) != 0 ? upper : lower);
    }
  }
  return sets;
}

TEST(MirrorLobe, WithoutALobeTheFirstRuleAloneAgreesWithTheMirrorPolarRuleAtGrazingSun) {
  int checked = 0;
  for (const Variant& v : variants()) {
    std::shared_ptr<const Model> model;
    try {
      model = make_model(v.name, v.options);
    } catch (const InputError&) {
      continue;
    }
    const ModelDescription& d = model->description();
    if (d.mirror_lobe) continue;
    const std::vector<double> sets = parameter_sets(d);
    const std::size_t n_sets = sets.size() / d.parameters.size();
    QuadratureSettings settings;
    settings.tolerance = 1e-5;
    settings.grazing_check = false;
    for (double deg : {70.0, 80.0, 85.0, 89.0, 89.9}) {
      const SpectralIntegral a = black_sky(*model, sets.data(), n_sets, deg * kDegree, 0.0, settings);
      const SpectralIntegral b = black_sky_mirror_polar(*model, sets.data(), n_sets, deg * kDegree, 0.0, settings);
      ASSERT_TRUE(a.converged) << v.name << " " << deg;
      for (std::size_t s = 0; s < n_sets; ++s) {
        EXPECT_LE(std::fabs(a.value[s] - b.value[s]), a.error[s] + b.error[s] + settings.tolerance)
            << v.name << " set " << s << " at " << deg << " deg: " << a.value[s] << " vs " << b.value[s];
      }
    }
    ++checked;
  }
  EXPECT_GE(checked, 3);  // lambert, oren-nayar, ross-li at least
}

}  // namespace
}  // namespace roadbrdf::albedo
