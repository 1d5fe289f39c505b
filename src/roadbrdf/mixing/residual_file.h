// Residual file of `roadbrdf mix --data MEASURED.csv --residuals RES.csv`: every held-out prediction
// of every compared method next to the measured value, one row per (method, geometry, wavelength).
//
// CSV (comment lines start with '#'; the header row names the columns):
//   method               areal | fitted | mastic | hapke | shadowed
//   fold                 1..K: the cross-validation fold that held this geometry out (the prediction
//                        comes from the fit on the other folds); 0 for methods without fitted
//                        parameters (one prediction for every geometry)
//   theta_i,phi_i,theta_r,phi_r   geometry [deg] (zenith/azimuth convention, core/geometry.h)
//   wavelength           [nm]
//   measured             measured BRDF y [sr^-1]
//   sigma                its standard uncertainty [sr^-1] (column present only when the data have sigma)
//   predicted            held-out predicted BRDF f [sr^-1]
//   residual             f - y [sr^-1]
//   relative_residual    (f - y) / y [1]; "nan" when y = 0
//   normalized_residual  (f - y) / sigma [1] (only with sigma)
// Per method, sqrt(mean residual^2) is the table's held-out RMSE and mean normalized_residual^2 its
// held-out reduced chi^2 (mixing.h, Comparison). Numbers are written with round-trip precision.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/mixing/mixing.h"

namespace roadbrdf::mixing {

// Write atomically (io/csv.h AtomicFile). Every comparison must come from `data`. Throws InputError.
void write_residual_file(const std::string& path, const SpectralDataset& data,
                         const std::vector<Comparison>& comparisons);

}  // namespace roadbrdf::mixing
