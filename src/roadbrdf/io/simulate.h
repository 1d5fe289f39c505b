// Virtual gonioreflectometer: sample a model (or a fit) on an instrument's geometry grid at given
// wavelengths and add a realistic, reproducible measurement noise.
//
// Noise model (standard deviation, per value):
//   sigma(g, lambda) = sqrt((relative * f)^2 + absolute^2) * shape(lambda)
//   shape(lambda) = 1 + (edge_factor - 1) * (exp(-(lambda - lambda_min)/edge_width)
//                                             + exp(-(lambda_max - lambda)/edge_width))
//                     + (water_factor - 1) * (exp(-((lambda - 1400)/50)^2) + exp(-((lambda - 1900)/60)^2))
// with lambda_min/max the detector range (default 350-2500 nm): larger at the detector's spectral
// edges (weak lamp and detector response) and in the atmospheric water-absorption bands.
// Values: f + sigma * z, z standard normal from the library's random family seeded with `seed`
// (core/random.h: xoshiro256**, Box-Muller deviates), the same with every standard library.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "roadbrdf/io/calibration.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf {

struct NoiseModel {
  double relative = 0.0;     // dimensionless
  double absolute = 0.0;     // sr^-1
  double edge_factor = 1.0;  // noise multiplier at the detector edges
  double edge_width_nm = 60.0;
  double water_factor = 1.0;  // noise multiplier at the centre of the 1400 and 1900 nm water bands
  double detector_min_nm = 350.0;
  double detector_max_nm = 2500.0;
  bool is_zero() const { return relative == 0.0 && absolute == 0.0; }
  double shape(double wavelength_nm) const;
};

// "relative=0.01,absolute=1e-4,edge=4,water=3" (any subset; also "none"). Throws FieldError("noise"
// or "noise.NAME").
NoiseModel parse_noise_model(const std::string& spec);

struct SimulationInput {
  const SpectralModel* model = nullptr;
  std::vector<Geometry> geometries;
  AngleConvention convention = AngleConvention::kZenithAzimuth;
  std::vector<double> wavelengths;  // nm, strictly increasing
  // Parameters given as spectra (wavelength -> value, linearly interpolated, no extrapolation),
  // overriding the model's value at every wavelength (e.g. a spectral albedo).
  std::map<std::string, spectra::Spectrum> spectral_parameters;
  NoiseModel noise;
  std::uint64_t seed = 1;
  bool write_sigma = true;  // store the noise standard deviation as sigma
  // Round values to this many significant digits, as instruments write them (0 = full precision);
  // sigma is then rounded to 2 significant digits.
  int significant_digits = 0;
};

// Throws InputError (unknown parameter, value outside its bounds at some wavelength, model not
// tabulated at a wavelength).
SpectralDataset simulate_dataset(const SimulationInput& input);

}  // namespace roadbrdf
