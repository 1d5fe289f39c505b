#include "roadbrdf/io/resample.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"

namespace roadbrdf {

WavelengthBands bands_from_edges(const std::vector<double>& edges) {
  if (edges.size() < 2) throw InputError("band averaging needs at least two band edges (START:STOP:STEP)");
  WavelengthBands b;
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    if (!(edges[k + 1] > edges[k])) throw InputError("band edges must be strictly increasing");
    b.lower.push_back(edges[k]);
    b.upper.push_back(edges[k + 1]);
  }
  return b;
}

std::vector<std::pair<std::size_t, double>> band_average_weights(const std::vector<double>& x, double lo, double hi) {
  if (x.empty()) throw InputError("no samples to average");
  if (!(hi > lo)) throw InputError(fmt::format("empty band [{}, {}] nm", lo, hi));
  const double tol = 1e-9 * std::max(1.0, std::fabs(x.back()));
  if (lo < x.front() - tol || hi > x.back() + tol) {
    throw InputError(fmt::format("band [{}, {}] nm reaches outside the measured range [{}, {}] nm (no extrapolation)",
                                 lo, hi, x.front(), x.back()));
  }
  lo = std::max(lo, x.front());
  hi = std::min(hi, x.back());
  std::vector<double> w(x.size(), 0.0);
  if (x.size() == 1) return {{0, 1.0}};
  // Integrate the linear interpolant over each overlap [a, b] of [lo, hi] with a segment [x_k, x_k+1]:
  // int y = (b - a) * (y(a) + y(b)) / 2 with y(t) = y_k (1 - u) + y_k+1 u, u = (t - x_k)/(x_k+1 - x_k).
  for (std::size_t k = 0; k + 1 < x.size(); ++k) {
    const double a = std::max(lo, x[k]), b = std::min(hi, x[k + 1]);
    if (b <= a) continue;
    const double h = x[k + 1] - x[k];
    const double ua = (a - x[k]) / h, ub = (b - x[k]) / h;
    const double len = b - a;
    w[k] += len * ((1 - ua) + (1 - ub)) / 2;
    w[k + 1] += len * (ua + ub) / 2;
  }
  std::vector<std::pair<std::size_t, double>> out;
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (w[k] != 0.0) out.emplace_back(k, w[k] / (hi - lo));
  }
  return out;
}

SpectralDataset resample_dataset(const SpectralDataset& d, const WavelengthBands& bands,
                                 const std::vector<std::pair<double, double>>& drop) {
  SpectralDataset out;
  out.geometries = d.geometries;
  out.convention = d.convention;
  out.metadata = d.metadata;
  std::vector<std::vector<std::pair<std::size_t, double>>> weights;
  std::string dropped;
  for (std::size_t b = 0; b < bands.lower.size(); ++b) {
    bool skip = false;
    for (const auto& [lo, hi] : drop) {
      if (bands.lower[b] < hi && bands.upper[b] > lo) skip = true;
    }
    if (skip) {
      dropped += fmt::format("{}{}-{}", dropped.empty() ? "" : " ", bands.lower[b], bands.upper[b]);
      continue;
    }
    weights.push_back(band_average_weights(d.wavelengths, bands.lower[b], bands.upper[b]));
    out.wavelengths.push_back(0.5 * (bands.lower[b] + bands.upper[b]));
  }
  if (out.wavelengths.empty()) throw InputError("every band was dropped: nothing left to resample");
  const std::size_t n = d.geometries.size(), m = d.wavelengths.size(), mb = out.wavelengths.size();
  out.brdf.assign(n * mb, 0.0);
  if (d.has_sigma()) out.sigma.assign(n * mb, 0.0);
  for (std::size_t g = 0; g < n; ++g) {
    for (std::size_t b = 0; b < mb; ++b) {
      double sum = 0.0, var = 0.0;
      for (const auto& [k, w] : weights[b]) {
        sum += w * d.brdf[g * m + k];
        if (d.has_sigma()) var += w * w * d.sigma[g * m + k] * d.sigma[g * m + k];
      }
      out.brdf[g * mb + b] = sum;
      if (d.has_sigma()) out.sigma[g * mb + b] = std::sqrt(var);
    }
  }
  out.metadata["resampling"] =
      fmt::format("band averages of the linearly interpolated spectrum over {} bands", out.wavelengths.size());
  out.metadata["band_edges_nm"] =
      fmt::format("{}:{} (band k reported at its centre)", bands.lower.front(), bands.upper.back());
  if (!dropped.empty()) out.metadata["dropped_bands"] = dropped;
  return out;
}

}  // namespace roadbrdf
