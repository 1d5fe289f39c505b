// Spectral resampling of datasets: band averages of the linearly interpolated spectra.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/io/dataset.h"

namespace roadbrdf {

// Output bands: band k covers [lower[k], upper[k]] and is reported at its centre.
struct WavelengthBands {
  std::vector<double> lower, upper;
};
// Consecutive intervals of a list of edges: [e0,e1], [e1,e2], ... (so "400:1000:10" gives the
// 60 bands 400-410, ..., 990-1000 nm reported at 405, ..., 995 nm). Throws InputError.
WavelengthBands bands_from_edges(const std::vector<double>& edges);

// Weights w_k such that sum_k w_k y_k is the mean over [lo, hi] of the piecewise-linear
// interpolant of samples y_k at x_k (the exact integral of that interpolant / (hi - lo)).
// Requires x_0 <= lo < hi <= x_last (no extrapolation); throws InputError otherwise.
std::vector<std::pair<std::size_t, double>> band_average_weights(const std::vector<double>& x, double lo, double hi);

// Resample every spectrum of a dataset to band averages. Uncertainties propagate as
// sigma^2 = sum w_k^2 sigma_k^2 (independent errors). Bands overlapping any of the `drop`
// intervals [nm] are left out (and listed in metadata "dropped_bands"). Throws InputError when
// a band reaches outside the measured range.
SpectralDataset resample_dataset(const SpectralDataset& dataset, const WavelengthBands& bands,
                                 const std::vector<std::pair<double, double>>& drop = {});

}  // namespace roadbrdf
