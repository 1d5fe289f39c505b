// compute_albedo's weighting stages (report_stages.h): the solar-weighted broadband values (report
// eq. 2.20) and the luminous (V(lambda)-weighted) ones.
#include <fmt/core.h>

#include "roadbrdf/albedo/report_stages.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/spectra/cie.h"
#include "roadbrdf/spectra/interpolation.h"
#include "roadbrdf/spectra/spectrum.h"

namespace roadbrdf::albedo::detail {

namespace {

// The three SPECTRL2 weights at one sun zenith: direct horizontal (on black-sky), diffuse (on
// white-sky) and global (on black-sky alone and on white-sky alone).
struct Spectrl2Weights {
  spectra::Spectrum direct_horizontal, diffuse, global;
};
Spectrl2Weights spectrl2_weights(const Spectrl2Output& o) {
  std::vector<double> direct_horizontal;
  for (double v : o.direct_normal) direct_horizontal.push_back(v * o.cos_zenith);
  Spectrl2Weights w;
  w.direct_horizontal = spectra::Spectrum("spectrl2-direct-horizontal", o.wavelengths, std::move(direct_horizontal));
  w.diffuse = spectra::Spectrum("spectrl2-diffuse", o.wavelengths, o.diffuse);
  w.global = spectra::Spectrum("spectrl2-global", o.wavelengths, o.global);
  return w;
}

// A model without wavelengths: its single set is its broadband value.
Broadband unweighted(const Hemispherical& albedos, const Sky& sky) {
  Broadband b;
  b.weighting = "none (non-spectral model)";
  b.white = albedos.white.value[0];
  b.white_error = albedos.white.error[0];
  for (std::size_t z = 0; z < albedos.black.size(); ++z) {
    b.black.push_back(albedos.black[z][0]);
    b.black_error.push_back(albedos.black_error[z][0]);
    if (!sky.blue.empty()) {
      b.blue.push_back(sky.blue[z][0]);
      b.blue_error.push_back(sky.blue_error[z][0]);
    }
  }
  return b;
}

// Whether the luminous values can be formed from these wavelengths: at least two, covering 99% of
// the luminous integral (photometry::photometric_weights). Otherwise a note says why not.
bool luminous_possible(const std::vector<double>& wavelengths, const spectra::Spectrum& illuminant,
                       std::vector<std::string>& notes) {
  if (wavelengths.size() < 2) {
    notes.push_back(
        fmt::format("single-band fit ({:g} nm): the luminous (V(lambda)-weighted) values need a spectrum "
                    "and are omitted",
                    wavelengths.front()));
    return false;
  }
  const double coverage = photometry::luminous_coverage(wavelengths.front(), wavelengths.back(), illuminant);
  if (coverage < 0.99) {
    notes.push_back(
        fmt::format("the fit's wavelengths ({:g}-{:g} nm) hold {:.1f}% of the luminous integral under {} "
                    "(99% needed): the luminous values are omitted",
                    wavelengths.front(), wavelengths.back(), 100.0 * coverage, illuminant.name()));
    return false;
  }
  return true;
}

}  // namespace

Broadband broadband_albedos(const ParameterSets& sets, const AlbedoRequest& a, const Hemispherical& albedos,
                            const Sky& sky, std::vector<std::string>& notes) {
  const std::vector<double>& wavelengths = sets.wavelengths;
  if (!a.spectrum.empty() && (!sets.spectral || wavelengths.size() < 2)) {
    // Nothing to weigh, but a spectrum that was asked for is still read and checked, never ignored.
    (void)solar_spectrum_from_name(a.spectrum);
    notes.push_back(fmt::format("spectrum {}: a {} has nothing to weigh, the weighting has no effect", a.spectrum,
                                sets.spectral ? "single-band fit" : "non-spectral model"));
  }
  if (!sets.spectral) return unweighted(albedos, sky);
  Broadband b;
  if (wavelengths.size() < 2) {
    // A single band has no spectrum to weigh: its values are reported per wavelength only.
    b.formed = false;
    notes.push_back(
        fmt::format("single-band fit ({:g} nm): the broadband (solar-weighted) values need at least two "
                    "wavelengths and are omitted",
                    wavelengths.front()));
    return b;
  }
  // One fixed weight for everything, or SPECTRL2's spectra at each sun zenith.
  std::optional<spectra::Spectrum> fixed;
  if (!a.spectrum.empty()) fixed = solar_spectrum_from_name(a.spectrum);
  if (!fixed && !sky.atmosphere) fixed = astm_g173("global");
  b.weighting = fixed ? fixed->name() : "spectrl2 (direct horizontal on black-sky, diffuse on white-sky)";
  const Hemispherical& h = albedos;
  for (std::size_t z = 0; z < h.black.size(); ++z) {
    const Spectrl2Weights w = fixed ? Spectrl2Weights{} : spectrl2_weights(sky.spectra[z]);
    const spectra::Spectrum& e = fixed ? *fixed : w.global;
    b.black_means.push_back(spectral_weighted_mean(wavelengths, h.black[z], h.black_error[z], e));
    b.black.push_back(b.black_means.back().value);
    b.black_error.push_back(b.black_means.back().error);
    b.outside = b.black_means.back().fraction_outside;
    if (z == 0) {
      b.white_mean = spectral_weighted_mean(wavelengths, h.white.value, h.white.error, e);
      b.white = b.white_mean.value;
      b.white_error = b.white_mean.error;
    }
    if (!sky.blue.empty()) {
      b.blue_means.push_back(fixed ? spectral_weighted_mean(wavelengths, sky.blue[z], sky.blue_error[z], e)
                                   : spectral_weighted_mean2(wavelengths, h.black[z], h.black_error[z],
                                                             w.direct_horizontal, h.white.value, h.white.error,
                                                             w.diffuse));
      b.blue.push_back(b.blue_means.back().value);
      b.blue_error.push_back(b.blue_means.back().error);
    }
  }
  // A named string, not a literal pushed in place: g++ 12 at -O2 with precompiled headers takes the
  // literal's inlined move for an out-of-bounds copy (-Warray-bounds, a known false positive).
  static const std::string kWhiteSkyNote =
      "broadband white-sky is weighted by SPECTRL2's global spectrum at the first sun zenith";
  if (!fixed) notes.push_back(kWhiteSkyNote);
  return b;
}

nlohmann::json luminous_albedos(const ParameterSets& sets, const AlbedoRequest& a, const Hemispherical& albedos,
                                std::vector<std::string>& notes) {
  if (a.illuminant.empty()) return nullptr;
  const spectra::Spectrum illuminant = photometry::illuminant_from_name(a.illuminant);
  std::vector<double> black;
  double white = albedos.white.value[0];
  if (!sets.spectral) {
    for (const auto& bs : albedos.black) black.push_back(bs[0]);
  } else {
    if (!luminous_possible(sets.wavelengths, illuminant, notes)) return nullptr;
    // Luminous reflectance: sum_k w_k a(l_k) on the photometric grid, the weights normalised.
    const std::vector<double> grid = photometry::photometric_grid(sets.wavelengths.front(), sets.wavelengths.back());
    const std::vector<double> w = photometry::photometric_weights(grid, illuminant);
    auto weigh = [&](const std::vector<double>& v) {
      double sum = 0.0;
      for (std::size_t k = 0; k < grid.size(); ++k) {
        sum +=
            w[k] * spectra::interpolate_linear(sets.wavelengths, v, grid[k], spectra::Extrapolation::kRefuse, "albedo");
      }
      return sum;
    };
    for (const auto& bs : albedos.black) black.push_back(weigh(bs));
    white = weigh(albedos.white.value);
  }
  return {{"illuminant", illuminant.name()}, {"black_sky", black}, {"white_sky", white}};
}

}  // namespace roadbrdf::albedo::detail
