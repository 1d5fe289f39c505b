// A luminaire's photometry: its luminous intensity distribution in the CIE (C, gamma) system
// (CIE 121-1996; EN 13032-1), read from EULUMDAT (.ldt) or IES LM-63 (.ies) files (luminaire_file.h).
//
// Angles: gamma is measured from the luminaire's downward vertical axis (0 = nadir, 90 = horizontal,
// 180 = zenith); C is the azimuth of the half-plane around that axis, increasing counter-clockwise
// seen from above, 0 <= C < 360. For a road luminaire C0 points along the road axis and C90 across the
// carriageway (the lighting module turns it into place: installation.h).
//
// The distribution is stored expanded to the whole sphere of C-planes (the file's symmetry undone),
// in candela for the luminaire as rated (`flux_lm`); intensity() interpolates it.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace roadbrdf::lighting {

struct IntensityDistribution {
  // C-planes [deg], increasing, in [0, 360): the distribution is periodic in C (C = 360 is C = 0).
  std::vector<double> c_deg;
  // gamma angles [deg], increasing, within [0, 180]; outside [gamma.front(), gamma.back()] the
  // intensity is 0 (a file that stops at 90 deg emits nothing upward).
  std::vector<double> gamma_deg;
  // Luminous intensity [cd], row-major [c][gamma]: candela[i * gamma_deg.size() + j].
  std::vector<double> candela;

  double at(std::size_t c_index, std::size_t gamma_index) const {
    return candela[c_index * gamma_deg.size() + gamma_index];
  }
  // Luminous intensity [cd] towards (C, gamma) [deg]: bilinear in (C, gamma) between the tabulated
  // planes and angles, periodic in C (any real C is reduced modulo 360), 0 outside the gamma range.
  // A single C-plane (rotational symmetry) is used for every C.
  double intensity(double c_deg, double gamma_deg) const;
  // Throws std::logic_error when the sizes or orders above do not hold (the readers check their input
  // and report it as a FileError first).
  void check_consistent() const;
};

struct Luminaire {
  std::string file;                    // where it was read from ("" for one built in memory)
  std::string format;                  // "eulumdat" or "ies"
  std::string name;                    // luminaire name / catalogue number as the file gives it
  std::string manufacturer;            // as the file gives it ("" if absent)
  IntensityDistribution distribution;  // [cd] for `flux_lm`
  double flux_lm = 0.0;                // luminous flux of the luminaire as rated [lm] (header flux x LOR...)
  double lamp_flux_lm = 0.0;           // flux of its lamps (lamp set 1) [lm]; 0 when the file gives absolute photometry
  double power_w = 0.0;                // system power [W] as the file gives it (0 = unknown)
  nlohmann::json metadata;             // everything else the file says (symmetry, lamp sets, luminous area...)
};

}  // namespace roadbrdf::lighting
