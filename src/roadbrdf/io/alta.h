// Reader of the ALTA text data format (Belcour et al., ALTA library, https://alta.gforge.inria.fr):
//   #DIM n m                 n input coordinates, m output values per line (m = 1 supported)
//   #VS 0                    no vertical segments (confidence intervals); others are refused
//   #PARAM_IN <name>         input parametrisation, supported:
//       ISOTROPIC_TL_TV_PROJ_DPHI  theta_l, then the viewing direction projected azimuthally:
//                                  (x, y) = theta_v (cos phi_v, sin phi_v), light at azimuth 0
//                                  (ALTA params.cpp, to_cartesian); radians
//       SPHERICAL_TL_PL_TV_PV      theta_l, phi_l, theta_v, phi_v [radians]
//   #PARAM_OUT <name>        INV_STERADIAN (BRDF) or INV_STERADIAN_COSINE_FACTOR (BRDF x cos theta_v,
//                            the cosine of the *outgoing* (view) direction, ALTA params.h)
//   then one line per measurement: n inputs and m outputs, separated by spaces.
// Light -> w_i (incident, theta_i = theta_l), view -> w_r. INV_STERADIAN_COSINE_FACTOR values are
// divided by cos theta_v to give BRDF [sr^-1]; at grazing view (cos theta_v < 1e-6) that is
// impossible: such rows are an error unless `exclude_grazing` is set, in which case they are left
// out, counted, warned about and recorded in metadata "alta_grazing_rows_excluded".
#pragma once

#include <functional>
#include <span>
#include <string>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/io/dataset.h"

namespace roadbrdf {

// The output units of #PARAM_OUT (above), as ALTA names them.
enum class AltaOutput { kInvSteradian, kInvSteradianCosine };
inline constexpr EnumName<AltaOutput> kAltaOutputNames[] = {
    {AltaOutput::kInvSteradian, "INV_STERADIAN", "BRDF"},
    {AltaOutput::kInvSteradianCosine, "INV_STERADIAN_COSINE_FACTOR", "BRDF x cos(theta_v)"},
};
constexpr std::span<const EnumName<AltaOutput>> enum_names(AltaOutput) { return kAltaOutputNames; }

struct AltaReadOptions {
  // ALTA files carry no wavelength: the single channel is stored at this wavelength [nm]. Required.
  double wavelength_nm = 0.0;
  // Output unit (a name of kAltaOutputNames) when the file has no #PARAM_OUT line ("" = error).
  std::string assumed_output;
  bool exclude_grazing = false;
  bool average_duplicates = false;
  std::function<void(const std::string&)> warn;
};

SpectralDataset read_alta(const std::string& path, const AltaReadOptions& options);

// Writes a single-wavelength dataset as ALTA text data: "#DIM 4 1", "#VS 0", #PARAM_IN
// SPHERICAL_TL_PL_TV_PV (radians), #PARAM_OUT INV_STERADIAN, a "#WAVELENGTH_NM" comment, one line per
// geometry with round-trip precision (read_alta reads back the same values). A missing value has no
// ALTA spelling: InputError, as for more than one wavelength. Written atomically ("-" = standard output).
void write_alta(const SpectralDataset& dataset, const std::string& path);

}  // namespace roadbrdf
