// CIE photometric tables: the 1931 2-degree luminous efficiency V(lambda) and the relative spectral
// power of CIE standard illuminants A and D65 (data/third-party/photometry/, 340-830 nm, 10 nm, see
// data/ATTRIBUTION.md), a reader for a user's lamp spectrum, and photometric weights for a
// wavelength grid.
//
// Interpolation. The bundled tables are on a uniform 10 nm grid; between grid points they are
// interpolated with Sprague's fifth-order polynomial (spectra/interpolation.h; CIE 167:2005
// recommends it for 10 nm colorimetric data). It reproduces V(555 nm) = 1.0002 from the 10 nm table
// (linear interpolation would give 0.9950; the 1 nm CIE table has 1.0000). Lamp files are
// interpolated the same way when uniformly spaced with >= 6 points, else linearly. Every quantity
// here is non-negative: Sprague overshoot below zero in the near-zero tails of V (|value| < 1e-6)
// is 0.
//
// Range. V(lambda) is 0 outside 340-830 nm (its tabulated values are below 1e-6 at both ends).
// An illuminant has no value outside its tabulated range: value() throws there.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/spectra/spectrum.h"

namespace roadbrdf::photometry {

// CIE 1931 2-degree V(lambda) (photopic luminous efficiency, peak 1 at 555 nm), 0 outside 340-830 nm.
const spectra::Spectrum& v_lambda();
// Relative spectral power of CIE illuminant A (tungsten, 2856 K) and D65 (daylight), 100 at 560 nm,
// tabulated 340-830 nm.
const spectra::Spectrum& illuminant_a();
const spectra::Spectrum& illuminant_d65();

// A lamp spectrum file (spectra/spectrum_file.h) with two columns, wavelength [nm] and relative
// spectral power (any unit: only ratios matter), >= 0, at least 2 rows. Interpolated linearly
// (Sprague if uniformly spaced with >= 6 points). The lamp spectrum counts as 0 outside its range,
// so the file must cover at least 99% of the integral of V(lambda); otherwise FileError. Other
// errors: FileError with line and column.
spectra::Spectrum read_lamp_spectrum(const std::string& path);

// "A", "D65" (case-insensitive) or the path of a lamp spectrum file.
spectra::Spectrum illuminant_from_name(const std::string& name_or_file);

// Photometric (luminous) weights of a wavelength grid under an illuminant S:
//   w_k = V(l_k) S(l_k) dl_k / sum_j V(l_j) S(l_j) dl_j,
// dl_k the trapezoid width ((l_{k+1} - l_{k-1})/2, half intervals at the ends), so that
// sum_k w_k f(l_k) is the trapezoid approximation of  int f V S dl / int V S dl  over the grid.
// Grid nodes where V = 0 (outside 340-830 nm) get weight 0 whatever S is; nodes where V > 0 but the
// illuminant is not tabulated count as S = 0. The grid must be strictly increasing with >= 2 points.
// Throws InputError if the grid covers less than `min_coverage` of int V S dl (see luminous_coverage),
// e.g. a grid that stops at 500 nm.
std::vector<double> photometric_weights(const std::vector<double>& wavelengths, const spectra::Spectrum& illuminant,
                                        double min_coverage = 0.99);

// Fraction of int V(l) S(l) dl (over the whole range where both are defined) that lies in
// [lo, hi] nm; 1 nm trapezoid of the interpolated tables.
double luminous_coverage(double lo_nm, double hi_nm, const spectra::Spectrum& illuminant);

// The 1 nm integration grid used for photometric weighting of a spectral model whose wavelengths
// span [lo, hi]: every integer nm in [max(lo, 340), min(hi, 830)] (plus the ends if not integers).
std::vector<double> photometric_grid(double lo_nm, double hi_nm);

}  // namespace roadbrdf::photometry
