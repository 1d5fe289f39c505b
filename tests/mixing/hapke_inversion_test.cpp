// Inversion of the IMSA white-sky albedo (hapke_imsa.h) and the mixture albedo from end-member
// albedos (mixing.h). References: an independent bisection written here (to 1e-15 in w, on the
// forward map, which mixing_methods_test.cpp checks against an independent midpoint quadrature), and
// the full hemispherical quadrature of the mixture.
#include <gtest/gtest.h>

#include "mixing_test_util.h"
#include "roadbrdf/models/hapke_imsa.h"

namespace {

using namespace mixtest;

double bisection_inverse(double albedo) {
  double lo = 0.0, hi = 1.0;
  while (hi - lo > 1e-15) {
    const double mid = 0.5 * (lo + hi);
    (imsa_white_sky_albedo(mid) < albedo ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(HapkeInversion, MatchesIndependentBisectionTo1e12) {
  const double a_max = imsa_white_sky_albedo(1.0);
  // Albedos over the whole range, including both ends and the steep region near w = 1.
  std::vector<double> albedos = {0.0, 1e-6, 0.01, 0.05, 0.1, 0.3, 0.5, 0.8, 0.95, 1.0, a_max - 1e-6, a_max};
  for (int i = 1; i < 200; ++i) albedos.push_back(a_max * i / 200.0);
  for (double a : albedos) {
    const double w = invert_imsa_white_sky_albedo(a);
    EXPECT_NEAR(w, bisection_inverse(a), 1e-12) << "albedo " << a;
    EXPECT_GE(w, 0.0);
    EXPECT_LE(w, 1.0);
  }
  EXPECT_EQ(invert_imsa_white_sky_albedo(0.0), 0.0);
  EXPECT_EQ(invert_imsa_white_sky_albedo(a_max), 1.0);
  EXPECT_THROW(invert_imsa_white_sky_albedo(a_max * (1.0 + 1e-12)), InputError);
  EXPECT_THROW(invert_imsa_white_sky_albedo(std::nan("")), InputError);
}

TEST(HapkeInversion, MixtureAlbedoFromEndMemberAlbedosEqualsFullQuadrature) {
  const MixInputs in = load_mix_inputs(three_component_formulation("b", "f", "c", "m"),
                                       memory_loader({{"b", glossy_spectral(0.04, 0.06, 40.0)},
                                                      {"f", oren_nayar_spectral(0.30, 0.10, 0.30)},
                                                      {"c", oren_nayar_spectral(0.55, -0.10, 0.60)},
                                                      {"m", oren_nayar_spectral(0.12, 0.02, 0.2)}}));
  for (Method method : {Method::kAreal, Method::kMastic, Method::kHapke}) {
    const MixResult r = mix(in, method, {});
    const std::vector<double> fast = mixture_white_sky_albedo(in, r, test_wavelengths());
    const std::vector<double> full = spectral_white_sky_albedo(*r.model, test_wavelengths());
    ASSERT_EQ(fast.size(), full.size());
    for (std::size_t q = 0; q < full.size(); ++q) EXPECT_NEAR(fast[q], full[q], 1e-13) << name_of(method) << " " << q;
  }
}

}  // namespace
