// MixtureModel as a Model: gradients against central differences, parameter layout, reciprocity,
// and the MIX.json round trip (write_mix_file -> read_mix_file gives the same BRDF).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "mixing_test_util.h"
#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/mixing/mix_file.h"
#include "roadbrdf/models/mixture_model.h"

namespace {

using namespace mixtest;

std::shared_ptr<MixtureModel> mixture(MixtureKind kind) {
  std::vector<std::shared_ptr<const Model>> models = {make_model("oren-nayar"), make_model("lambert"),
                                                      make_model("oren-nayar")};
  return std::make_shared<MixtureModel>(kind, models, std::vector<std::string>{"a", "b", "c"},
                                        std::vector<bool>{false, false, true});
}

std::vector<double> parameters(const MixtureModel& m) {
  std::vector<double> p(m.parameter_count());
  p[0] = 0.2, p[1] = 0.3, p[2] = 0.5;
  std::size_t q = 3;
  if (m.kind() == MixtureKind::kHapke) {
    p[3] = 0.1, p[4] = 0.6, p[5] = 0.8;
    q = 6;
  }
  if (m.kind() == MixtureKind::kShadowed) p[q++] = 0.4;
  // a: oren-nayar (albedo, sigma); b: lambert (albedo); c: oren-nayar (albedo, sigma)
  const double rest[] = {0.3, 0.25, 0.5, 0.6, 0.5};
  for (double x : rest) p[q++] = x;
  EXPECT_EQ(q, m.parameter_count());
  return p;
}

TEST(MixtureModel, ParameterNamesAndLayout) {
  const auto m = mixture(MixtureKind::kHapke);
  const auto& d = m->description();
  EXPECT_EQ(d.parameters[0].name, "weight.a");
  EXPECT_EQ(d.parameters[3].name, "ssa.a");
  EXPECT_EQ(d.parameters[6].name, "a.albedo");
  EXPECT_EQ(d.parameters[8].name, "b.albedo");
  EXPECT_EQ(m->component_offset(2), 9u);
  const auto s = mixture(MixtureKind::kShadowed);
  EXPECT_EQ(s->description().parameters[3].name, "shadowing");
  EXPECT_FALSE(s->description().parameters[3].spectral);
}

TEST(MixtureModel, GradientMatchesCentralDifferences) {
  for (MixtureKind kind : {MixtureKind::kLinear, MixtureKind::kHapke, MixtureKind::kShadowed}) {
    const auto m = mixture(kind);
    const std::vector<double> p = parameters(*m);
    for (const Geometry& g : {geometry_from_degrees(30, 0, 50, 120), geometry_from_degrees(60, 0, 20, 10)}) {
      std::vector<double> gradient(p.size());
      const double value = m->evaluate_with_gradient(p.data(), g, gradient.data());
      EXPECT_NEAR(value, m->evaluate(p.data(), g), 1e-14);
      for (std::size_t q = 0; q < p.size(); ++q) {
        const double h = 1e-6;
        std::vector<double> up = p, down = p;
        up[q] += h;
        down[q] -= h;
        const double numeric = (m->evaluate(up.data(), g) - m->evaluate(down.data(), g)) / (2 * h);
        EXPECT_NEAR(gradient[q], numeric, 1e-6 * std::max(1.0, std::fabs(numeric)))
            << name_of(kind) << " " << m->description().parameters[q].name;
      }
    }
  }
}

// A one-member mixture with weight 1 is its member: the albedo integrator must treat an anisotropic
// Ashikhmin-Shirley lobe inside a mixture as anisotropic (it used to integrate it as isotropic, 3 % off).
TEST(MixtureModel, SingleAnisotropicMemberKeepsItsAlbedo) {
  std::shared_ptr<const Model> as = make_model("ashikhmin-shirley");
  const std::shared_ptr<const Model> reference = as;
  const MixtureModel m(MixtureKind::kLinear, std::vector<std::shared_ptr<const Model>>{std::move(as)},
                       std::vector<std::string>{"a"}, std::vector<bool>{false});
  EXPECT_FALSE(m.description().isotropic);
  const std::vector<double> own = {0.3, 0.05, 10.0, 200.0};  // rd, rs, nu, nv
  std::vector<double> mixed = {1.0};                         // weight of "a", then its parameters
  mixed.insert(mixed.end(), own.begin(), own.end());
  ASSERT_EQ(mixed.size(), m.parameter_count());
  EXPECT_FALSE(roadbrdf::albedo::is_isotropic(m, mixed.data(), 1));
  for (double theta_s : {0.0, 0.5, 1.0}) {
    for (double phi_s : {0.0, 0.7}) {
      const double a = roadbrdf::albedo::black_sky(*reference, own.data(), 1, theta_s, phi_s).value[0];
      const double b = roadbrdf::albedo::black_sky(m, mixed.data(), 1, theta_s, phi_s).value[0];
      EXPECT_NEAR(b, a, 2e-5) << theta_s << ' ' << phi_s;
    }
  }
}

TEST(MixtureModel, ReciprocalAndBatchConsistent) {
  for (MixtureKind kind : {MixtureKind::kLinear, MixtureKind::kHapke, MixtureKind::kShadowed}) {
    const auto m = mixture(kind);
    const std::vector<double> p = parameters(*m);
    const std::vector<Geometry> gs = test_geometries();
    std::vector<double> batch(gs.size());
    m->evaluate_batch(gs.data(), gs.size(), p.data(), 1, batch.data());
    for (std::size_t n = 0; n < gs.size(); ++n) {
      EXPECT_NEAR(batch[n], m->evaluate(p.data(), gs[n]), 1e-15);
      EXPECT_NEAR(m->evaluate(p.data(), gs[n]), m->evaluate(p.data(), gs[n].swapped()), 1e-12) << name_of(kind);
    }
  }
}

TEST(MixFile, RoundTripOfEveryPredictionMethod) {
  const MixInputs in = load_mix_inputs(three_component_formulation("b", "f", "c", "m"),
                                       memory_loader({{"b", lambert_spectral(0.05, 0.01)},
                                                      {"f", oren_nayar_spectral(0.3, 0.1, 0.3)},
                                                      {"c", oren_nayar_spectral(0.5, -0.1, 0.5)},
                                                      {"m", oren_nayar_spectral(0.12, 0.02, 0.2)}}));
  MixFileContent content;
  content.inputs = &in;
  for (Method method : {Method::kAreal, Method::kMastic, Method::kHapke})
    content.results.push_back(mix(in, method, {}));
  const std::string path =
      (std::filesystem::temp_directory_path() / ("roadbrdf_mix_roundtrip_" + std::to_string(::getpid()) + ".json"))
          .string();
  write_mix_file(path, content);
  EXPECT_TRUE(is_mix_file(path));
  for (const MixResult& r : content.results) {
    const SpectralModel back = read_spectral_model_file(path, name_of(r.method));
    for (const Geometry& g : test_geometries()) {
      for (double w : {400.0, 555.0, 700.0}) EXPECT_NEAR(value_at(back, g, w), value_at(*r.model, g, w), 1e-12);
    }
  }
  EXPECT_THROW(read_mix_file(path, "nonexistent"), FileError);
  std::filesystem::remove(path);
}

}  // namespace
