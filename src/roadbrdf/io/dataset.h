// In-memory spectral BRDF dataset: N geometries x M wavelengths.
// Readers and writers for the file formats live next to this header (measurement I/O).
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/io/geometry_file.h"

namespace roadbrdf {

struct SpectralDataset {
  std::vector<Geometry> geometries;                              // N measurement geometries
  std::vector<double> wavelengths;                               // M wavelengths [nm], strictly increasing
  std::vector<double> brdf;                                      // N x M, row-major (geometry-major) [sr^-1]
  std::vector<double> sigma;                                     // empty, or N x M standard uncertainties [sr^-1]
  AngleConvention convention = AngleConvention::kZenithAzimuth;  // of the source file
  std::map<std::string, std::string> metadata;                   // "sample", "instrument", "units", free keys
  std::vector<std::string> comments;                             // free comment lines of the source file, in order

  std::size_t geometry_count() const { return geometries.size(); }
  std::size_t wavelength_count() const { return wavelengths.size(); }
  bool has_sigma() const { return !sigma.empty(); }
  double value(std::size_t geometry, std::size_t wavelength) const {
    return brdf[geometry * wavelengths.size() + wavelength];
  }
  double& value(std::size_t geometry, std::size_t wavelength) {
    return brdf[geometry * wavelengths.size() + wavelength];
  }
};

}  // namespace roadbrdf
