#include "roadbrdf/mixing/residual_file.h"

#include <fmt/core.h>

#include <cmath>
#include <limits>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::mixing {

namespace {

// Degrees rounded to 1e-9 so that 30 deg does not print as 29.999999999999996.
std::string angle_text(double radians) { return fmt::format("{}", std::round(rad_to_deg(radians) * 1e9) / 1e9 + 0.0); }

std::string number_text(double x) { return std::isfinite(x) ? fmt::format("{}", x) : std::string("nan"); }

}  // namespace

void write_residual_file(const std::string& path, const SpectralDataset& data,
                         const std::vector<Comparison>& comparisons) {
  const std::size_t N = data.geometry_count(), M = data.wavelength_count();
  const bool sigma = data.has_sigma();
  for (const Comparison& c : comparisons) {
    if (c.predicted.size() != N * M || c.fold_of_geometry.size() != N) {
      throw InputError("residual file: the comparison of method '" + name_of(c.method) +
                       "' does not match the measured data");
    }
  }
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "# roadbrdf mix: held-out residuals per method, geometry and wavelength "
         "(src/roadbrdf/mixing/residual_file.h)\n"
      << "# units: angles deg, wavelength nm, measured/sigma/predicted/residual sr^-1, relative_residual and "
         "normalized_residual 1\n"
      << "# residual = predicted - measured; relative_residual = residual / measured; normalized_residual = "
         "residual / sigma\n"
      << "method,fold,theta_i,phi_i,theta_r,phi_r,wavelength,measured," << (sigma ? "sigma," : "")
      << "predicted,residual,relative_residual" << (sigma ? ",normalized_residual" : "") << '\n';
  for (const Comparison& c : comparisons) {
    const std::string method = name_of(c.method);
    for (std::size_t n = 0; n < N; ++n) {
      const Geometry& g = data.geometries[n];
      const std::string prefix = fmt::format("{},{},{},{},{},{},", method, c.fold_of_geometry[n], angle_text(g.theta_i),
                                             angle_text(g.phi_i), angle_text(g.theta_r), angle_text(g.phi_r));
      for (std::size_t m = 0; m < M; ++m) {
        const std::size_t i = n * M + m;
        const double y = data.brdf[i];
        const double f = c.predicted[i];
        const double residual = f - y;
        out << prefix << number_text(data.wavelengths[m]) << ',' << number_text(y) << ',';
        if (sigma) out << number_text(data.sigma[i]) << ',';
        out << number_text(f) << ',' << number_text(residual) << ','
            << number_text(y != 0.0 ? residual / y : std::numeric_limits<double>::quiet_NaN());
        if (sigma) out << ',' << number_text(residual / data.sigma[i]);
        out << '\n';
      }
    }
  }
  file.commit();
}

}  // namespace roadbrdf::mixing
