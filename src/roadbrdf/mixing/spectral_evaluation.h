// Evaluation of a spectral model (a fit or a mixture) at many geometries and wavelengths, and its
// white-sky albedo by the fixed quadrature of hapke_imsa.h. Below mixing.h and albedo_cache.h, which
// both use it.
#pragma once

#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf::mixing {

// Values of a spectral model at the given geometries and wavelengths: N x M, geometry-major.
std::vector<double> evaluate_spectral(const SpectralModel& model, const std::vector<Geometry>& geometries,
                                      const std::vector<double>& wavelengths);

// White-sky albedo (hapke_imsa.h quadrature) of a spectral model at each wavelength (or once when
// `wavelengths` is empty and the model is not spectral).
std::vector<double> spectral_white_sky_albedo(const SpectralModel& model, const std::vector<double>& wavelengths);

}  // namespace roadbrdf::mixing
