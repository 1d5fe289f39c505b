// The two readers behind read_luminaire (luminaire_file.h), and what they share: undoing a file's
// symmetry into the full circle of C-planes.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/lighting/luminaire.h"
#include "roadbrdf/lighting/luminaire_text.h"

namespace roadbrdf::lighting::detail {

// EULUMDAT (eulumdat.cpp).
Luminaire parse_eulumdat(const LuminaireText& text, Diagnostics& diagnostics);
// IES LM-63 (ies_file.cpp).
Luminaire parse_ies(const LuminaireText& text, Diagnostics& diagnostics);

// One measured C-plane: its angle [deg] and intensities at the file's gamma angles.
struct CPlane {
  double c_deg;
  std::vector<double> values;
};

// The C-planes of `symmetry` (none: as given; rotational: the one plane) expanded over the circle:
// each given plane also stands at its mirror images (C0-C180 plane: 360 - C; C90-C270 plane:
// 180 - C; quadrants: both and 180 + C), every angle reduced to [0, 360). A plane that falls on a
// given one (C0 and C180 are their own images) is not added twice. Returns planes sorted by angle.
std::vector<CPlane> expand_symmetry(std::vector<CPlane> given, PhotometricSymmetry symmetry);

// The distribution of sorted, expanded planes over `gamma_deg`, each value times `scale` [cd].
IntensityDistribution make_distribution(const std::vector<CPlane>& planes, const std::vector<double>& gamma_deg,
                                        double scale);

}  // namespace roadbrdf::lighting::detail
