// The parameter layout of every model: the description (the names files, fits and scripts use) and
// the indices the model's code reads them at (its enum Parameter, Lafortune's lobe stride) must
// agree for every option variant, and no variant may describe more parameters than the model's
// kMaxParameters (the size of the automatic-differentiation arrays of ModelAdapter, model.h).
#include <gtest/gtest.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/models/ashikhmin_shirley.h"
#include "roadbrdf/models/burley.h"
#include "roadbrdf/models/hapke.h"
#include "roadbrdf/models/kelemen_szirmay_kalos.h"
#include "roadbrdf/models/lafortune.h"
#include "roadbrdf/models/lambert.h"
#include "roadbrdf/models/model.h"
#include "roadbrdf/models/oren_nayar.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/retro_phong.h"
#include "roadbrdf/models/ross_li.h"
#include "roadbrdf/models/rpv.h"
#include "roadbrdf/models/simonot.h"
#include "roadbrdf/models/torrance_sparrow.h"

namespace roadbrdf {
namespace {

// A model whose description has one parameter more than its kMaxParameters.
struct TooManyParameters {
  static constexpr const char* kName = "too-many";
  static constexpr int kMaxParameters = 1;
  static std::vector<OptionInfo> options() { return {}; }
  static ModelDescription describe(const OptionSet&) {
    ModelDescription d;
    d.parameters = {{"a", "1", "first", 0.5, 0.0, 1.0, true, true}, {"b", "1", "second", 0.5, 0.0, 1.0, true, false}};
    return d;
  }
  explicit TooManyParameters(const OptionSet&) {}
  template <typename T>
  T operator()(const T* p, const Geometry&) const {
    return p[0] + p[1];
  }
};

TEST(ModelParameterLayout, MoreParametersThanTheBoundIsRefused) {
  try {
    ModelAdapter<TooManyParameters> adapter(OptionSet{});
    ADD_FAILURE() << "a description of 2 parameters was accepted with kMaxParameters = 1";
  } catch (const std::logic_error& e) {
    EXPECT_EQ(std::string(e.what()), "model 'too-many' describes 2 parameters, more than its kMaxParameters = 1");
  }
}

// Every combination of a model's option values: enumerated values, and for a numeric option (a
// lobe count) the integers 0..16, of which the model accepts some.
std::vector<OptionSet> all_option_sets(const std::string& model) {
  const ModelDescription d = make_model(model)->description();
  std::vector<OptionSet> combos = {{}};
  for (const OptionInfo& o : d.options) {
    std::vector<std::string> values = o.values;
    if (values.empty()) {
      for (int k = 0; k <= 16; ++k) values.push_back(std::to_string(k));
    }
    std::vector<OptionSet> next;
    for (const OptionSet& c : combos) {
      for (const std::string& v : values) {
        OptionSet e = c;
        e[o.name] = v;
        next.push_back(e);
      }
    }
    combos = std::move(next);
  }
  return combos;
}

// The descriptions of every valid option combination (an invalid one is an InputError, never
// the logic_error of a parameter count above kMaxParameters).
std::vector<ModelDescription> all_descriptions(const std::string& model) {
  std::vector<ModelDescription> out;
  for (const OptionSet& options : all_option_sets(model)) {
    try {
      out.push_back(make_model(model, options)->description());
    } catch (const InputError&) {
    }
  }
  return out;
}

TEST(ModelParameterLayout, EveryVariantOfEveryModelIsWithinItsBound) {
  std::size_t variants = 0;
  for (const std::string& name : model_names()) {
    std::vector<ModelDescription> descriptions;
    EXPECT_NO_THROW(descriptions = all_descriptions(name)) << name;
    EXPECT_FALSE(descriptions.empty()) << name;
    variants += descriptions.size();
  }
  EXPECT_GT(variants, model_names().size());
}

int position(const ModelDescription& d, const std::string& parameter) {
  for (std::size_t k = 0; k < d.parameters.size(); ++k) {
    if (d.parameters[k].name == parameter) return static_cast<int>(k);
  }
  return -1;
}

// Each (enumerator, name): wherever the description of a variant has the parameter, it is at the
// enumerator's index; and some variant has it.
template <class M>
void expect_layout(const std::vector<std::pair<typename M::Parameter, std::string>>& named) {
  const std::vector<ModelDescription> descriptions = all_descriptions(M::kName);
  ASSERT_FALSE(descriptions.empty()) << M::kName;
  for (const auto& [index, name] : named) {
    int found = 0;
    for (const ModelDescription& d : descriptions) {
      const int at = position(d, name);
      if (at < 0) continue;
      ++found;
      EXPECT_EQ(at, static_cast<int>(index)) << M::kName << " '" << name << "' in: " << d.summary;
    }
    EXPECT_GT(found, 0) << M::kName << ": no variant has a parameter '" << name << "'";
  }
}

TEST(ModelParameterLayout, EnumeratorsAreThePositionsOfTheDescribedParameters) {
  expect_layout<Lambert>({{Lambert::kAlbedo, "albedo"}});
  expect_layout<OrenNayar>({{OrenNayar::kAlbedo, "albedo"}, {OrenNayar::kSigma, "sigma"}});
  expect_layout<AshikhminShirley>({{AshikhminShirley::kRd, "rd"},
                                   {AshikhminShirley::kRs, "rs"},
                                   {AshikhminShirley::kNu, "nu"},
                                   {AshikhminShirley::kNv, "nv"}});
  expect_layout<Simonot>({{Simonot::kAlbedo, "albedo"}, {Simonot::kIor, "ior"}});
  expect_layout<RetroPhong>({{RetroPhong::kKd, "kd"},
                             {RetroPhong::kN, "n"},
                             {RetroPhong::kK1, "k1"},
                             {RetroPhong::kK2, "k2"},
                             {RetroPhong::kK3, "k3"},
                             {RetroPhong::kK4, "k4"}});
  expect_layout<TorranceSparrow>({{TorranceSparrow::kKs, "ks"},
                                  {TorranceSparrow::kRoughness, "roughness"},
                                  {TorranceSparrow::kIor, "ior"},
                                  {TorranceSparrow::kExtinction, "k"}});
  expect_layout<KelemenSzirmayKalos>({{KelemenSzirmayKalos::kAlbedo, "albedo"},
                                      {KelemenSzirmayKalos::kRoughness, "roughness"},
                                      {KelemenSzirmayKalos::kIor, "ior"}});
  expect_layout<Burley>({{Burley::kAlbedo, "albedo"},
                         {Burley::kRoughness, "roughness"},
                         {Burley::kSpecular, "specular"},
                         {Burley::kIor, "ior"},
                         {Burley::kGamma, "gtr_gamma"}});
  expect_layout<Hapke>({{Hapke::kW, "w"},
                        {Hapke::kB0, "b0"},
                        {Hapke::kH, "h"},
                        {Hapke::kXi, "xi"},
                        {Hapke::kLegendreB, "legendre_b"},
                        {Hapke::kLegendreC, "legendre_c"},
                        {Hapke::kHg2B, "hg2_b"},
                        {Hapke::kHg2C, "hg2_c"}});
  expect_layout<RossLi>({{RossLi::kIso, "f_iso"}, {RossLi::kVol, "f_vol"}, {RossLi::kGeo, "f_geo"}});
  expect_layout<RahmanPintyVerstraete>({{RahmanPintyVerstraete::kRho0, "rho0"},
                                        {RahmanPintyVerstraete::kK, "k"},
                                        {RahmanPintyVerstraete::kTheta, "Theta"}});
}

// Lafortune reads lobe k (0-based) at 1 + k * stride: rho, cx, (cy when anisotropic), cz, n.
TEST(ModelParameterLayout, LafortuneLobesAreAtTheirStride) {
  int checked = 0;
  for (const ModelDescription& d : all_descriptions(Lafortune::kName)) {
    const bool isotropic = d.option_values.at("isotropic") == "yes";
    const int lobes = std::stoi(d.option_values.at("lobes"));
    const int stride = isotropic ? 4 : 5;
    ASSERT_EQ(d.parameters.size(), static_cast<std::size_t>(1 + lobes * stride)) << d.summary;
    EXPECT_EQ(d.parameters[0].name, "kd");
    for (int k = 0; k < lobes; ++k) {
      const std::string s = std::to_string(k + 1);
      std::vector<std::string> names = {"rho" + s, "cx" + s, "cz" + s, "n" + s};
      if (!isotropic) names.insert(names.begin() + 2, "cy" + s);
      for (int j = 0; j < stride; ++j) EXPECT_EQ(d.parameters[1 + k * stride + j].name, names[j]) << d.summary;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 2 * Lafortune::kMaxLobes);  // lobes 1..4, isotropic or not
}

}  // namespace
}  // namespace roadbrdf
