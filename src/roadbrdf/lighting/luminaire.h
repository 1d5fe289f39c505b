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

#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/enum_names.h"

namespace roadbrdf::lighting {

// The symmetry a file declares (EULUMDAT ISYM; IES LM-63 by its range of horizontal angles). The
// distribution is stored expanded; the symmetry says which planes were measured.
enum class PhotometricSymmetry { none, rotational, c0_c180, c90_c270, quadrants };
inline constexpr EnumName<PhotometricSymmetry> kPhotometricSymmetryNames[] = {
    {PhotometricSymmetry::none, "none", "every C-plane given"},
    {PhotometricSymmetry::rotational, "rotational", "one C-plane: the same in every azimuth"},
    {PhotometricSymmetry::c0_c180, "c0-c180", "mirror image about the C0-C180 plane"},
    {PhotometricSymmetry::c90_c270, "c90-c270", "mirror image about the C90-C270 plane"},
    {PhotometricSymmetry::quadrants, "quadrants", "mirror image about both planes"},
};
constexpr std::span<const EnumName<PhotometricSymmetry>> enum_names(PhotometricSymmetry) {
  return kPhotometricSymmetryNames;
}

// The luminous area of a luminaire (EULUMDAT fields 16-21; IES LM-63 luminous opening): a
// rectangle of sides `along_c0_m` (along the C0-C180 axis) and `along_c90_m` (along the C90-C270
// axis), or a disc of diameter `along_c0_m` (circular), with side faces of height heights_m =
// {C0, C90, C180, C270}: the face seen from that C-plane. All zero when the file gives none.
struct LuminousArea {
  double along_c0_m = 0.0;
  double along_c90_m = 0.0;
  bool circular = false;
  std::array<double, 4> heights_m{};

  // Area of the luminous area projected on a plane normal to (C, gamma) [m^2]: the bottom face
  // A cos(gamma) (for gamma < 90 deg) plus the side faces seen from that azimuth, sin(gamma) times
  //   a90 h_C0 max(cos C, 0) + a0 h_C90 max(sin C, 0) + a90 h_C180 max(-cos C, 0) + a0 h_C270 max(-sin C, 0)
  // for a rectangle (the face seen from C0 spans the C90-C270 side a90), and D h(C) for a disc (a
  // cylinder's side, h = h_C0 cos^2 C + h_C90 sin^2 C in the quadrant of C). The area behind
  // luminance = I / A_p (CIE 117, CIE 190 for UGR tables).
  double projected_m2(double c_deg, double gamma_deg) const;
};

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
  PhotometricSymmetry symmetry = PhotometricSymmetry::none;  // as the file declares it
  bool absolute_photometry = false;  // intensities for the luminaire itself (no lamp flux to scale them by)
  LuminousArea luminous_area;        // for luminances (projected_m2)
};

}  // namespace roadbrdf::lighting
