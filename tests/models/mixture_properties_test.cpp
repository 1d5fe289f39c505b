// The property claims of the mixture models (MixtureModel, every kind) as the registered models make
// them: the value at grazing directions (89.999 and 90 deg and their mixes) is the limit or a declared
// 0 (grazing_check.h, the check every registered model passes), and each declared nested model
// (reduces_to) is the mixture at the declared values.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "models/grazing_check.h"
#include "models/model_variants.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/models/mixture_model.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

using mixing::MixtureKind;
using mixing::MixtureModel;

struct EndMembers {
  std::vector<std::string> models;
  std::vector<OptionSet> options;
  std::vector<bool> coarse;
};

// End-member sets: smooth at the horizon (two Lambertians: no declared zero anywhere, so every value
// must be the limit), divergent closed forms (Oren-Nayar, Hapke with and without roughness, a
// composite with a specular lobe) next to finite ones.
std::vector<EndMembers> end_member_sets() {
  return {
      {{"lambert", "lambert"}, {{}, {}}, {false, true}},
      {{"oren-nayar", "lambert", "oren-nayar"}, {{}, {}, {}}, {false, false, true}},
      {{"hapke", "lambert"}, {{}, {}}, {false, true}},
      {{"oren-nayar+torrance-sparrow", "hapke"}, {{}, {{"roughness", "hapke1984"}}}, {true, false}},
  };
}

std::shared_ptr<MixtureModel> mixture(MixtureKind kind, const EndMembers& e) {
  std::vector<std::shared_ptr<const Model>> models;
  std::vector<std::string> names;
  for (std::size_t k = 0; k < e.models.size(); ++k) {
    models.push_back(make_model(e.models[k], e.options[k]));
    names.push_back("m" + std::to_string(k));
  }
  return std::make_shared<MixtureModel>(kind, models, names, e.coarse);
}

const MixtureKind kKinds[] = {MixtureKind::kLinear, MixtureKind::kHapke, MixtureKind::kShadowed};

TEST(MixtureProperties, ValueAtNinetyDegreesIsTheLimitOrADeclaredZero) {
  for (MixtureKind kind : kKinds) {
    for (const EndMembers& e : end_member_sets()) {
      const auto m = mixture(kind, e);
      SCOPED_TRACE(m->description().name + " of " + e.models[0] + ", " + e.models[1]);
      // The lower bounds' set has every weight 0, which the hapke kind refuses: one weight 1 there.
      const int zeros = test::expect_grazing_limits_or_declared_zeros(*m, [&](std::vector<double>& p) {
        if (p[m->weight_index(0)] == 0.0) p[m->weight_index(0)] = 1.0;
      });
      if (m->description().grazing_zero.empty()) {
        EXPECT_EQ(zeros, 0);
      } else {
        EXPECT_GT(zeros, 0) << m->description().grazing_zero;  // the claim is used
      }
    }
  }
}

// The hapke kind's multiple-scattering correction at theta_i = theta_r = 90 deg, where its closed form
// is 0/0: with H1(x) = 1 + 2x (1 - gamma) + O(x^2), the bracket [w H(mu0) H(mu) - sum_k c_k w_k
// H_k(mu0) H_k(mu)] is 2 (mu0 + mu) [w (1 - gamma) - sum_k c_k w_k (1 - gamma_k)] + O(mu^2), so the
// limit of bracket / (4 pi (mu0 + mu)) is [w (1 - gamma) - sum_k c_k w_k (1 - gamma_k)] / (2 pi).
TEST(MixtureProperties, HapkeMixtureOfLambertiansAtBothHorizonsIsTheClosedFormLimit) {
  const auto m = mixture(MixtureKind::kHapke, end_member_sets()[0]);
  // weights c = 0.25, 0.75 (normalised from 1, 3), ssa 0.3, 0.9, albedos 0.2, 0.6.
  const double p[] = {1.0, 3.0, 0.3, 0.9, 0.2, 0.6};
  const double c0 = 0.25, c1 = 0.75, w0 = 0.3, w1 = 0.9, w = c0 * w0 + c1 * w1;
  const double linear = (c0 * 0.2 + c1 * 0.6) / kPi;
  const double correction =
      (w * (1.0 - std::sqrt(1.0 - w)) - c0 * w0 * (1.0 - std::sqrt(1.0 - w0)) - c1 * w1 * (1.0 - std::sqrt(1.0 - w1))) /
      (2.0 * kPi);
  for (double dphi : {0.0, 90.0, 180.0}) {
    EXPECT_NEAR(m->evaluate(p, test::grazing_test_geometry(90.0, 90.0, dphi)), linear + correction, 1e-15) << dphi;
  }
  // Just inside the horizon the closed form (evaluated here without the cancellation-free rewrite,
  // where it is still accurate) approaches the same value.
  const double mu = std::cos(89.99 * kDegree);
  auto h1 = [](double x, double ssa) { return (1.0 + 2.0 * x) / (1.0 + 2.0 * x * std::sqrt(1.0 - ssa)); };
  const double bracket =
      w * h1(mu, w) * h1(mu, w) - c0 * w0 * h1(mu, w0) * h1(mu, w0) - c1 * w1 * h1(mu, w1) * h1(mu, w1);
  const double inside = linear + bracket / (4.0 * kPi * 2.0 * mu);
  EXPECT_NEAR(m->evaluate(p, test::grazing_test_geometry(89.99, 89.99, 0.0)), inside, 1e-12);
  EXPECT_NEAR(inside, linear + correction, 1e-3 * std::fabs(correction));
}

TEST(MixtureProperties, EachDeclaredNestedModelIsTheMixtureAtTheDeclaredValues) {
  Rng rng(4040);
  for (MixtureKind kind : kKinds) {
    for (const EndMembers& e : end_member_sets()) {
      const auto m = mixture(kind, e);
      const ModelDescription& d = m->description();
      const std::size_t K = e.models.size();
      ASSERT_EQ(d.reduces_to.size(), K) << d.name;
      for (std::size_t k = 0; k < K; ++k) {
        const Model& member = m->component(k);
        EXPECT_EQ(d.reduces_to[k].first, member.description().name);
        EXPECT_NE(d.reduces_to[k].second.find("weight.m" + std::to_string(k) + " = 1"), std::string::npos);
        for (int s = 0; s < 5; ++s) {
          std::vector<double> p = test::random_parameters(d, rng, 0.02);
          for (std::size_t j = 0; j < K; ++j) p[m->weight_index(j)] = j == k ? 1.0 : 0.0;
          // The shadowed kind: s = 0 as declared, or any s when the end-member is coarse.
          if (kind == MixtureKind::kShadowed && !e.coarse[k]) p[m->shadowing_index()] = 0.0;
          for (double ti : {0.0, 35.0, 70.0, 89.999}) {
            for (double tr : {10.0, 50.0, 85.0}) {
              for (double dphi : {0.0, 120.0, 180.0}) {
                const Geometry g = test::grazing_test_geometry(ti, tr, dphi);
                const double expected = member.evaluate(p.data() + m->component_offset(k), g);
                EXPECT_NEAR(m->evaluate(p.data(), g), expected, 1e-13 * std::fabs(expected) + 1e-300)
                    << d.name << " reduced to " << d.reduces_to[k].first << " at " << ti << ", " << tr << ", " << dphi;
              }
            }
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace roadbrdf
