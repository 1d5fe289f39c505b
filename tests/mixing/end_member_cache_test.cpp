// End-members prepared once for many mixtures (mixing/end_member_cache.h): the albedo of a linear
// method from its end-members' integrals, the r-table from their cached values, and the linearity
// metadata of the method table.
#include "roadbrdf/mixing/end_member_cache.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mixing_test_util.h"

namespace {

using namespace mixtest;
using roadbrdf::albedo::AlbedoRequest;
using roadbrdf::photometry::RTableRequest;

MixInputs glossy_inputs() {
  return load_mix_inputs(three_component_formulation("binder", "fines", "coarse", "mastic"),
                         memory_loader({{"binder", glossy_spectral(0.02, 0.05, 40.0)},
                                        {"fines", oren_nayar_spectral(0.25, 0.1, 0.4)},
                                        {"coarse", oren_nayar_spectral(0.35, -0.1, 0.2)},
                                        {"mastic", oren_nayar_spectral(0.12, 0.05, 0.3)}}));
}

AlbedoRequest request() {
  AlbedoRequest a;
  a.sun_zenith_deg = {30.0, 60.0};
  a.diffuse_fraction = "0.15";
  return a;
}

RTableRequest band_request() {
  RTableRequest r;
  r.band = std::make_pair(450.0, 650.0);  // the test models' 400-700 nm hold too little of V(lambda) x A
  return r;
}

// Lambertian end-members: the black- and white-sky albedo of rho/pi is rho, so the mixture's is the
// weighted sum of the rho_k at every wavelength (closed form).
TEST(LinearMixtureAlbedo, LambertianEndMembersGiveTheWeightedAlbedos) {
  const MixInputs in = load_mix_inputs(three_component_formulation("binder", "fines", "coarse", "mastic"),
                                       memory_loader({{"binder", lambert_spectral(0.05, 0.01)},
                                                      {"fines", lambert_spectral(0.3, 0.1)},
                                                      {"coarse", lambert_spectral(0.4, -0.05)},
                                                      {"mastic", lambert_spectral(0.15, 0.02)}}));
  EndMemberCache cache;
  for (Method m : {Method::kAreal, Method::kMastic}) {
    const MixResult r = mix(in, m, {});
    const nlohmann::json a = mixture_albedo(r, request(), cache);
    const std::vector<double> wavelengths = a["wavelengths"];
    ASSERT_EQ(wavelengths.size(), test_wavelengths().size());
    for (std::size_t q = 0; q < wavelengths.size(); ++q) {
      const double x = (wavelengths[q] - 400.0) / 300.0;
      double expected = 0.0;
      for (std::size_t k = 0; k < r.end_members.size(); ++k) {
        const std::map<std::string, std::pair<double, double>> rho = {
            {"binder", {0.05, 0.01}}, {"fines", {0.3, 0.1}}, {"coarse", {0.4, -0.05}}, {"mastic", {0.15, 0.02}}};
        const auto [r0, r1] = rho.at(r.end_members[k]);
        expected += r.weights[k] * (r0 + r1 * x);
      }
      EXPECT_NEAR(a["white_sky"][q].get<double>(), expected, 1e-9) << name_of(m) << " " << wavelengths[q];
      EXPECT_NEAR(a["black_sky"][1][q].get<double>(), expected, 1e-9) << name_of(m) << " " << wavelengths[q];
    }
  }
}

// Against the mixture's own adaptive quadrature (what `roadbrdf albedo MIX.json` computes): both are
// the exact integral to within their error estimates, so they differ by at most the sum of the two.
TEST(LinearMixtureAlbedo, AgreesWithTheMixtureQuadratureWithinBothErrorEstimates) {
  const MixInputs in = glossy_inputs();
  EndMemberCache cache;
  for (Method m : {Method::kAreal, Method::kMastic}) {
    const MixResult r = mix(in, m, {});
    const nlohmann::json fast = mixture_albedo(r, request(), cache);
    const nlohmann::json direct = albedo::compute_albedo(*r.model, request());
    for (const char* key : {"black_sky", "blue_sky"}) {
      const std::string error = std::string(key) + "_error";
      for (std::size_t z = 0; z < 2; ++z) {
        for (std::size_t q = 0; q < test_wavelengths().size(); ++q) {
          const double bound = fast[error][z][q].get<double>() + direct[error][z][q].get<double>();
          EXPECT_LE(std::fabs(fast[key][z][q].get<double>() - direct[key][z][q].get<double>()), bound)
              << name_of(m) << " " << key;
          EXPECT_GT(fast[key][z][q].get<double>(), 0.01);
        }
        const double bound = fast["broadband"][error][z].get<double>() + direct["broadband"][error][z].get<double>();
        EXPECT_LE(std::fabs(fast["broadband"][key][z].get<double>() - direct["broadband"][key][z].get<double>()),
                  bound);
      }
    }
    for (std::size_t q = 0; q < test_wavelengths().size(); ++q) {
      const double bound = fast["white_sky_error"][q].get<double>() + direct["white_sky_error"][q].get<double>();
      EXPECT_LE(std::fabs(fast["white_sky"][q].get<double>() - direct["white_sky"][q].get<double>()), bound);
      EXPECT_LE(fast["white_sky_error"][q].get<double>(), 1e-5);  // sum a_k e_k with sum a_k = 1
    }
  }
  // The end-member integrals are computed once: a second mixture of the same end-members adds none.
  const std::size_t computed = cache.integrals_computed();
  MixSettings other;
  other.binder_coverage = 0.3;
  (void)mixture_albedo(mix(in, Method::kAreal, other), request(), cache);
  EXPECT_EQ(cache.integrals_computed(), computed);
}

TEST(LinearMixtureAlbedo, NonlinearMethodsIntegrateTheMixtureItself) {
  const MixInputs in = glossy_inputs();
  EndMemberCache cache;
  const MixResult r = mix(in, Method::kHapke, {});
  EXPECT_EQ(mixture_albedo(r, request(), cache), albedo::compute_albedo(*r.model, request()));
  EXPECT_EQ(cache.integrals_computed(), 0u);
}

// The r-table from the cached end-member values is the mixture's own, bit for bit, for every kind.
TEST(MixtureRTable, SameNumbersAsTheMixtureBitForBit) {
  const MixInputs in = glossy_inputs();
  EndMemberCache cache;
  for (Method m : {Method::kAreal, Method::kMastic, Method::kHapke}) {
    const MixResult r = mix(in, m, {});
    const photometry::RTableReport fast = mixture_rtable(r, band_request(), cache);
    const photometry::RTableReport direct = photometry::rtable_report(*r.model, band_request());
    ASSERT_EQ(fast.table.scaled.size(), direct.table.scaled.size());
    for (std::size_t c = 0; c < fast.table.scaled.size(); ++c) {
      ASSERT_TRUE(fast.table.scaled[c] == direct.table.scaled[c] ||
                  (std::isnan(fast.table.scaled[c]) && std::isnan(direct.table.scaled[c])))
          << name_of(m) << " cell " << c;
    }
    EXPECT_EQ(fast.summary.q0, direct.summary.q0);
    EXPECT_EQ(fast.summary.s1, direct.summary.s1);
    EXPECT_EQ(fast.chosen.name, direct.chosen.name);
    EXPECT_EQ(fast.to_json(), direct.to_json());
  }
  const std::size_t computed = cache.values_computed();
  MixSettings other;
  other.mastic_area_fraction = 0.5;
  (void)mixture_rtable(mix(in, Method::kMastic, other), band_request(), cache);
  EXPECT_EQ(cache.values_computed(), computed);
}

// The linearity declared in the method table agrees with the mixture each method builds.
TEST(MethodLinearity, DeclaredLinearMethodsBuildLinearMixtures) {
  const MixInputs in = glossy_inputs();
  const MixResult truth = mix(in, Method::kAreal, {});
  const SpectralDataset data = make_dataset([&](const Geometry& g, double w) { return value_at(*truth.model, g, w); });
  for (Method m : values_of<Method>()) {
    const MixResult r = mix(in, m, {}, method_needs_data(m) ? &data : nullptr);
    EXPECT_EQ(method_is_linear(m), r.mixture->kind() == MixtureKind::kLinear) << name_of(m);
  }
  EXPECT_TRUE(method_is_linear(Method::kAreal));
  EXPECT_FALSE(method_is_linear(Method::kHapke));
  EXPECT_FALSE(method_is_linear(Method::kShadowed));
}

}  // namespace
