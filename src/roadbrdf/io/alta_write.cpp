// Writer of ALTA text data (alta.h).
#include <fmt/core.h>

#include <cmath>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/io/alta.h"

namespace roadbrdf {

void write_alta(const SpectralDataset& dataset, const std::string& path) {
  if (dataset.wavelength_count() != 1) {
    throw InputError(fmt::format("ALTA text data hold one value per line here: {} wavelengths need one file each",
                                 dataset.wavelength_count()));
  }
  for (std::size_t n = 0; n < dataset.geometry_count(); ++n) {
    if (std::isnan(dataset.value(n, 0))) {
      throw InputError(fmt::format("geometry {} has no value, which ALTA text data cannot say", n));
    }
  }
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "#DIM 4 1\n#VS 0\n#PARAM_IN SPHERICAL_TL_PL_TV_PV\n#PARAM_OUT INV_STERADIAN\n";
  out << fmt::format("#WAVELENGTH_NM {}\n", dataset.wavelengths[0]);
  for (std::size_t n = 0; n < dataset.geometry_count(); ++n) {
    const Geometry& g = dataset.geometries[n];
    out << fmt::format("{} {} {} {} {}\n", g.theta_i, g.phi_i, g.theta_r, g.phi_r, dataset.value(n, 0));
  }
  file.commit();
}

}  // namespace roadbrdf
