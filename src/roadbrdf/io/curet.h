// Reader of the CUReT BRDF database files (Dana, van Ginneken, Nayar & Koenderink, "Reflectance
// and texture of real-world surfaces", ACM TOG 18(1), 1999), as distributed in two text files:
//   table.txt  one line per geometry: index (1-based), theta_v, phi_v, theta_i, phi_i [radians]
//   abrdf.dat  one line per sample: sample number, then one BRDF value [sr^-1] per geometry of
//              table.txt (grey: the average of the R, G, B channels)
// The geometry count is whatever table.txt holds (205 in the published data); every sample line
// must have exactly that many values. The data are grey (no wavelength): the dataset gets a single
// nominal wavelength (default 550 nm, recorded in the metadata).
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_io.h"

namespace roadbrdf {

struct CuretReadOptions {
  double nominal_wavelength_nm = 550.0;  // the wavelength the single grey channel is stored at
  // Negative values are kept and counted; warnings go here (default: the front end's sink, route_warning).
  std::function<void(const std::string&)> warn;
};

// Sample numbers present in abrdf.dat, in file order. Throws FileError.
std::vector<int> curet_sample_numbers(const std::string& abrdf_path);

// One sample (by its number, first column of abrdf.dat). Throws FileError / InputError.
SpectralDataset read_curet(const std::string& abrdf_path, const std::string& table_path, int sample,
                           const CuretReadOptions& options = {});

}  // namespace roadbrdf
