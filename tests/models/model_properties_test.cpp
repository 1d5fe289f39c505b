// Physical properties every registered model must satisfy, checked over randomised parameters
// inside the declared bounds and for one-option-at-a-time variants of every enumerated option:
//   - non-negativity (for models that declare non_negative),
//   - Helmholtz reciprocity f(w_i, w_r) = f(w_r, w_i) (for models that declare it),
//   - directional albedo <= 1 (for models that declare energy conservation), computed by an
//     independent brute-force quadrature written here, not by the albedo module,
//   - finite values at edge geometries (normal incidence, grazing 89.9 and 90 deg, exact mirror
//     and exact retro directions),
//   - automatic-differentiation gradients equal central finite differences,
//   - azimuthal isotropy exactly where declared (isotropic, isotropic_when_equal).
// New models are covered automatically once registered.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "models/model_variants.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

using test::all_variants;
using test::option_combinations;
using test::random_parameters;
using test::test_name;
using test::Variant;

TEST(ModelVariants, EveryOptionValueIsUsableInSomeCombination) {
  for (const std::string& name : model_names()) {
    const ModelDescription d = make_model(name)->description();
    const std::vector<OptionSet> combos = option_combinations(d);
    for (const OptionInfo& o : d.options) {
      for (const std::string& v : o.values) {
        bool usable = false;
        for (const OptionSet& c : combos) {
          if (c.at(o.name) != v) continue;
          try {
            make_model(name, c);
            usable = true;
            break;
          } catch (const InputError&) {
          }
        }
        EXPECT_TRUE(usable) << name << " option " << o.name << "=" << v << " is valid in no combination";
      }
    }
  }
}

Geometry random_geometry(Rng& rng) {
  // Uniform in solid angle over the hemisphere, plus some grazing and normal cases.
  auto theta = [&] {
    const double x = rng.uniform();
    if (x < 0.05) return 0.0;
    if (x < 0.10) return 89.9 * kDegree;
    return std::acos(rng.uniform());
  };
  return geometry_from_radians(theta(), 2 * kPi * rng.uniform(), theta(), 2 * kPi * rng.uniform());
}

std::vector<Geometry> edge_geometries() {
  std::vector<Geometry> g;
  const double thetas[] = {0.0, 1e-6, 30.0, 60.0, 89.9, 90.0};
  for (double ti : thetas) {
    for (double tr : thetas) {
      for (double dphi : {0.0, 90.0, 180.0}) g.push_back(geometry_from_degrees(ti, 0.0, tr, dphi));
    }
    g.push_back(geometry_from_degrees(ti, 10.0, ti, 190.0));  // exact mirror
    g.push_back(geometry_from_degrees(ti, 10.0, ti, 10.0));   // exact retro
  }
  return g;
}

// Directional albedo  a(theta_i) = int f cos(theta_r) dw_r + R_delta(theta_i), by Gauss-Legendre in
// mu = cos(theta_r) (n nodes) x midpoint rule in phi_r (2n nodes).
double directional_albedo(const Model& model, const std::vector<double>& p, double theta_i, int n) {
  // Gauss-Legendre nodes on [0, 1] by Newton iteration on P_n (independent of the library).
  std::vector<double> x(n), w(n);
  for (int k = 0; k < n; ++k) {
    double z = std::cos(kPi * (k + 0.75) / (n + 0.5));
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p2) / j;
      }
      const double dp = n * (z * p0 - p1) / (z * z - 1.0);
      const double dz = p0 / dp;
      z -= dz;
      if (std::fabs(dz) < 1e-15) {
        x[k] = 0.5 * (z + 1.0);
        w[k] = 1.0 / ((1.0 - z * z) * dp * dp);
        break;
      }
    }
  }
  const int n_phi = 2 * n;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double mu = x[k];
    const double theta_r = std::acos(mu);
    double ring = 0.0;
    for (int j = 0; j < n_phi; ++j) {
      const double phi = 2 * kPi * (j + 0.5) / n_phi;
      ring += model.evaluate(p.data(), geometry_from_radians(theta_i, 0.0, theta_r, phi));
    }
    sum += w[k] * mu * ring * (2 * kPi / n_phi);
  }
  return sum + model.delta_reflectance(p.data(), std::cos(theta_i));
}

class ModelProperties : public testing::TestWithParam<Variant> {
 protected:
  void SetUp() override { model_ = make_model(GetParam().model, GetParam().options); }
  std::unique_ptr<Model> model_;
};

// The claims below hold only where a model declares them, so each runs over exactly the variants
// that declare it (no variant is skipped).
std::vector<Variant> variants_where(bool ModelDescription::*claim) {
  std::vector<Variant> chosen;
  for (const Variant& v : all_variants()) {
    if (make_model(v.model, v.options)->description().*claim) chosen.push_back(v);
  }
  return chosen;
}

// The variants whose model declares that it reads only the direction vectors (Model::reads_angles).
std::vector<Variant> variants_reading_only_vectors() {
  std::vector<Variant> chosen;
  for (const Variant& v : all_variants()) {
    if (!make_model(v.model, v.options)->reads_angles()) chosen.push_back(v);
  }
  return chosen;
}

class NonNegativeModels : public ModelProperties {};
class EnergyConservingModels : public ModelProperties {};
class VectorOnlyModels : public ModelProperties {};

// A model that declares it does not read the angle fields of a geometry (the path tracer then leaves
// them out) gives the same values and gradients, bit for bit, with those fields NaN: through every
// evaluation path (single, with gradient, batch, fixed sets).
TEST_P(VectorOnlyModels, ValuesDoNotDependOnTheAngleFields) {
  const ModelDescription& d = model_->description();
  Rng rng(4242);
  std::vector<Geometry> geometries = edge_geometries();
  for (int k = 0; k < 40; ++k) geometries.push_back(random_geometry(rng));
  std::vector<Geometry> poisoned = geometries;
  for (Geometry& g : poisoned) g.theta_i = g.theta_r = g.phi_i = g.phi_r = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = model_->parameter_count(), n_sets = 3;
  std::vector<double> params;
  for (std::size_t s = 0; s < n_sets; ++s) {
    const std::vector<double> p = s == 0 ? d.default_parameters() : random_parameters(d, rng, 0.05);
    params.insert(params.end(), p.begin(), p.end());
  }
  const auto fixed = model_->fixed_sets(params.data(), n_sets);
  std::vector<double> grad(n), grad_poisoned(n), batch(n_sets), batch_poisoned(n_sets);
  for (std::size_t k = 0; k < geometries.size(); ++k) {
    for (std::size_t s = 0; s < n_sets; ++s) {
      const double* p = params.data() + s * n;
      EXPECT_EQ(model_->evaluate(p, poisoned[k]), model_->evaluate(p, geometries[k])) << d.name << " geometry " << k;
      model_->evaluate_with_gradient(p, geometries[k], grad.data());
      model_->evaluate_with_gradient(p, poisoned[k], grad_poisoned.data());
      for (std::size_t q = 0; q < n; ++q) EXPECT_EQ(grad_poisoned[q], grad[q]) << d.name << " geometry " << k;
    }
    model_->evaluate_batch(&geometries[k], 1, params.data(), n_sets, batch.data());
    model_->evaluate_batch(&poisoned[k], 1, params.data(), n_sets, batch_poisoned.data());
    for (std::size_t s = 0; s < n_sets; ++s) EXPECT_EQ(batch_poisoned[s], batch[s]) << d.name << " geometry " << k;
    fixed->evaluate(geometries[k], batch.data());
    fixed->evaluate(poisoned[k], batch_poisoned.data());
    for (std::size_t s = 0; s < n_sets; ++s) EXPECT_EQ(batch_poisoned[s], batch[s]) << d.name << " geometry " << k;
  }
}

// Oren-Nayar reads theta_i and theta_r, and says so: the claim above is not vacuous.
TEST(ModelAngles, OrenNayarAndItsCompositesReadTheAngles) {
  EXPECT_TRUE(make_model("oren-nayar")->reads_angles());
  EXPECT_TRUE(make_model("oren-nayar+torrance-sparrow")->reads_angles());
  EXPECT_FALSE(make_model("hapke")->reads_angles());
  EXPECT_FALSE(make_model("lambert+torrance-sparrow")->reads_angles());
}

TEST_P(NonNegativeModels, NonNegative) {
  const ModelDescription& d = model_->description();
  Rng rng(12345);
  const std::vector<Geometry> edges = edge_geometries();
  for (int s = 0; s < 200; ++s) {
    const std::vector<double> p = random_parameters(d, rng);
    for (const Geometry& g : edges) {
      ASSERT_GE(model_->evaluate(p.data(), g), 0.0)
          << "theta_i=" << g.theta_i << " theta_r=" << g.theta_r << " cos dphi=" << g.cos_delta_phi;
    }
    for (int k = 0; k < 200; ++k) {
      const Geometry g = random_geometry(rng);
      const double f = model_->evaluate(p.data(), g);
      ASSERT_GE(f, 0.0) << "theta_i=" << g.theta_i << " theta_r=" << g.theta_r << " cos dphi=" << g.cos_delta_phi;
    }
  }
}

TEST_P(ModelProperties, ReciprocalWhereDeclared) {
  const ModelDescription& d = model_->description();
  Rng rng(777);
  double worst = 0.0;
  for (int s = 0; s < 100; ++s) {
    const std::vector<double> p = random_parameters(d, rng);
    for (int k = 0; k < 100; ++k) {
      const Geometry g = random_geometry(rng);
      const double a = model_->evaluate(p.data(), g);
      const double b = model_->evaluate(p.data(), g.swapped());
      const double scale = std::fmax(std::fabs(a), std::fabs(b));
      if (scale > 0.0 && std::isfinite(scale)) worst = std::fmax(worst, std::fabs(a - b) / scale);
    }
  }
  if (d.reciprocal) {
    EXPECT_LT(worst, 1e-9) << d.name << " claims reciprocity";
  } else {
    EXPECT_GT(worst, 1e-6) << d.name << " is declared non-reciprocal but behaved reciprocally";
  }
}

// Turning both directions about the normal by the same angle changes nothing for an isotropic model
// (largest relative change over random geometries and turns at parameter set p).
double largest_change_under_rotation(const Model& model, const std::vector<double>& p, Rng& rng) {
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double ti = std::acos(rng.uniform()), tr = std::acos(rng.uniform());
    const double pi = 2 * kPi * rng.uniform(), pr = 2 * kPi * rng.uniform(), turn = 2 * kPi * rng.uniform();
    const double a = model.evaluate(p.data(), geometry_from_radians(ti, pi, tr, pr));
    const double b = model.evaluate(p.data(), geometry_from_radians(ti, pi + turn, tr, pr + turn));
    const double scale = std::fmax(std::fabs(a), std::fabs(b));
    if (scale > 1e-300 && std::isfinite(scale)) worst = std::fmax(worst, std::fabs(a - b) / scale);
  }
  return worst;
}

TEST_P(ModelProperties, IsotropicExactlyWhereDeclared) {
  const ModelDescription& d = model_->description();
  Rng rng(4242);
  double worst = 0.0, worst_where_equal = 0.0;
  for (int s = 0; s < 50; ++s) {
    std::vector<double> p = random_parameters(d, rng);
    worst = std::fmax(worst, largest_change_under_rotation(*model_, p, rng));
    for (const auto& [first, second] : d.isotropic_when_equal) {
      p[*d.parameter_index(second)] = p[*d.parameter_index(first)];
    }
    if (!d.isotropic_when_equal.empty()) {
      EXPECT_TRUE(is_isotropic_at(d, p.data()));
      worst_where_equal = std::fmax(worst_where_equal, largest_change_under_rotation(*model_, p, rng));
    }
  }
  if (d.isotropic) {
    EXPECT_LT(worst, 1e-9) << d.name << " claims azimuthal isotropy";
  } else {
    EXPECT_GT(worst, 1e-6) << d.name << " is declared anisotropic but behaved isotropically";
    EXPECT_LT(worst_where_equal, 1e-9) << d.name << " claims isotropy where its pairs are equal";
  }
}

TEST(ModelIsotropy, CompositesCombineTheirComponents) {
  const auto m = make_model("lambert+ashikhmin-shirley");
  const ModelDescription& d = m->description();
  EXPECT_FALSE(d.isotropic);
  ASSERT_EQ(d.isotropic_when_equal.size(), 1u);
  EXPECT_EQ(d.isotropic_when_equal[0].first, "ashikhmin-shirley.nu");
  EXPECT_EQ(d.isotropic_when_equal[0].second, "ashikhmin-shirley.nv");
  std::vector<double> p = d.default_parameters();
  EXPECT_TRUE(is_isotropic_at(d, p.data()));  // defaults: nu = nv = 20
  p[*d.parameter_index("ashikhmin-shirley.nv")] = 50.0;
  EXPECT_FALSE(is_isotropic_at(d, p.data()));
  // The pairs of every anisotropic component: isotropic only where all of them are equal.
  const auto both = make_model("ashikhmin-shirley+lafortune", {{"isotropic", "no"}});
  const ModelDescription& b = both->description();
  EXPECT_FALSE(b.isotropic);
  ASSERT_EQ(b.isotropic_when_equal.size(), 2u);
  EXPECT_EQ(b.isotropic_when_equal[1].first, "lafortune.cx1");
  EXPECT_EQ(b.isotropic_when_equal[1].second, "lafortune.cy1");
  EXPECT_TRUE(make_model("lambert+oren-nayar")->description().isotropic);
}

TEST_P(ModelProperties, FiniteAtEdgeGeometries) {
  const ModelDescription& d = model_->description();
  Rng rng(99);
  const std::vector<Geometry> edges = edge_geometries();
  for (int s = 0; s < 50; ++s) {
    std::vector<double> p = s == 0 ? d.default_parameters() : random_parameters(d, rng);
    if (s == 1) {
      for (std::size_t k = 0; k < p.size(); ++k) p[k] = d.parameters[k].lower;
    }
    if (s == 2) {
      for (std::size_t k = 0; k < p.size(); ++k) p[k] = d.parameters[k].upper;
    }
    for (const Geometry& g : edges) {
      const double f = model_->evaluate(p.data(), g);
      ASSERT_TRUE(std::isfinite(f)) << d.name << " at theta_i=" << g.theta_i << " theta_r=" << g.theta_r
                                    << " cos dphi=" << g.cos_delta_phi << " parameter set " << s;
    }
  }
}

TEST_P(EnergyConservingModels, DirectionalAlbedoAtMostOne) {
  const ModelDescription& d = model_->description();
  Rng rng(2024);
  int unresolved = 0;
  int total = 0;
  for (int s = 0; s < 12; ++s) {
    const std::vector<double> p = random_parameters(d, rng);
    for (double theta_deg : {0.0, 30.0, 60.0, 85.0}) {
      const double theta_i = theta_deg * kDegree;
      ++total;
      // Converged value: two quadrature orders must agree to 1e-3; sharp lobes that no order
      // here resolves are counted, not judged.
      double coarse = directional_albedo(*model_, p, theta_i, 48);
      double fine = directional_albedo(*model_, p, theta_i, 96);
      if (std::fabs(fine - coarse) > 1e-3) {
        coarse = fine;
        fine = directional_albedo(*model_, p, theta_i, 192);
      }
      if (std::fabs(fine - coarse) > 1e-3) {
        ++unresolved;
        continue;
      }
      EXPECT_LE(fine, 1.0 + 1e-3) << d.name << " theta_i=" << theta_deg << " deg";
    }
  }
  EXPECT_LE(unresolved, total / 4) << "too many parameter sets too sharp for the reference quadrature";
}

TEST_P(ModelProperties, GradientMatchesFiniteDifferences) {
  const ModelDescription& d = model_->description();
  Rng rng(31337);
  const std::size_t n = model_->parameter_count();
  std::vector<double> grad(n);
  int checked = 0;
  for (int s = 0; s < 20; ++s) {
    const std::vector<double> p = random_parameters(d, rng, 0.05);
    for (int k = 0; k < 20; ++k) {
      const Geometry g = random_geometry(rng);
      const double f = model_->evaluate_with_gradient(p.data(), g, grad.data());
      ASSERT_NEAR(f, model_->evaluate(p.data(), g), 1e-12 * std::fmax(1.0, std::fabs(f)));
      for (std::size_t q = 0; q < n; ++q) {
        const double h = 1e-6 * std::fmax(1.0, std::fabs(p[q]));
        std::vector<double> up = p, down = p;
        up[q] += h;
        down[q] -= h;
        const double fd = (model_->evaluate(up.data(), g) - model_->evaluate(down.data(), g)) / (2 * h);
        if (!std::isfinite(fd)) continue;
        const double tol = 1e-4 * std::fmax(1.0, std::fmax(std::fabs(fd), std::fabs(f)));
        // A kink (max/min/branch) inside [p-h, p+h] makes finite differences meaningless:
        // compare one-sided differences first.
        const double forward = (model_->evaluate(up.data(), g) - f) / h;
        const double backward = (f - model_->evaluate(down.data(), g)) / h;
        if (std::fabs(forward - backward) > tol) continue;
        EXPECT_NEAR(grad[q], fd, tol) << d.name << " parameter " << d.parameters[q].name;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 0);
}

TEST_P(ModelProperties, BatchEqualsSingleEvaluation) {
  const ModelDescription& d = model_->description();
  Rng rng(5);
  const std::size_t n_sets = 3;
  std::vector<double> params;
  for (std::size_t s = 0; s < n_sets; ++s) {
    const auto p = random_parameters(d, rng);
    params.insert(params.end(), p.begin(), p.end());
  }
  std::vector<Geometry> geometries;
  for (int k = 0; k < 50; ++k) geometries.push_back(random_geometry(rng));
  std::vector<double> out(geometries.size() * n_sets);
  model_->evaluate_batch(geometries.data(), geometries.size(), params.data(), n_sets, out.data());
  for (std::size_t k = 0; k < geometries.size(); ++k) {
    for (std::size_t s = 0; s < n_sets; ++s) {
      EXPECT_EQ(out[k * n_sets + s], model_->evaluate(params.data() + s * model_->parameter_count(), geometries[k]));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllModels, ModelProperties, testing::ValuesIn(all_variants()), test_name);
INSTANTIATE_TEST_SUITE_P(Declaring, NonNegativeModels,
                         testing::ValuesIn(variants_where(&ModelDescription::non_negative)), test_name);
INSTANTIATE_TEST_SUITE_P(Declaring, VectorOnlyModels, testing::ValuesIn(variants_reading_only_vectors()), test_name);
INSTANTIATE_TEST_SUITE_P(Declaring, EnergyConservingModels,
                         testing::ValuesIn(variants_where(&ModelDescription::energy_conserving)), test_name);

}  // namespace
}  // namespace roadbrdf
