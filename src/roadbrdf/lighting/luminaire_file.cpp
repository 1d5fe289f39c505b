#include "roadbrdf/lighting/luminaire_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/lighting/luminaire_readers.h"
#include "roadbrdf/lighting/luminaire_text.h"

namespace roadbrdf::lighting {

namespace detail {

namespace {

double reduced_angle(double c) {
  double r = std::fmod(c, 360.0);
  if (r < 0.0) r += 360.0;
  // An image that lands a rounding error below 360 deg is the plane at 0 deg.
  if (r > 360.0 - 1e-9) r = 0.0;
  return r;
}

}  // namespace

std::vector<CPlane> expand_symmetry(std::vector<CPlane> given, PhotometricSymmetry symmetry) {
  // The given planes first, then their images: after a stable sort by angle, the first plane of a
  // run of equal angles is a given one when there is one.
  std::vector<CPlane> planes;
  planes.reserve(4 * given.size());
  for (const CPlane& p : given) planes.push_back({reduced_angle(p.c_deg), p.values});
  for (const CPlane& p : given) {
    switch (symmetry) {
      case PhotometricSymmetry::none:
      case PhotometricSymmetry::rotational:
        break;
      case PhotometricSymmetry::c0_c180:
        planes.push_back({reduced_angle(360.0 - p.c_deg), p.values});
        break;
      case PhotometricSymmetry::c90_c270:
        planes.push_back({reduced_angle(180.0 - p.c_deg), p.values});
        break;
      case PhotometricSymmetry::quadrants:
        planes.push_back({reduced_angle(180.0 - p.c_deg), p.values});
        planes.push_back({reduced_angle(180.0 + p.c_deg), p.values});
        planes.push_back({reduced_angle(360.0 - p.c_deg), p.values});
        break;
    }
  }
  std::stable_sort(planes.begin(), planes.end(), [](const CPlane& a, const CPlane& b) { return a.c_deg < b.c_deg; });
  std::vector<CPlane> out;
  out.reserve(planes.size());
  for (CPlane& p : planes) {
    if (out.empty() || p.c_deg - out.back().c_deg > 1e-9) out.push_back(std::move(p));
  }
  return out;
}

IntensityDistribution make_distribution(const std::vector<CPlane>& planes, const std::vector<double>& gamma_deg,
                                        double scale) {
  IntensityDistribution d;
  d.gamma_deg = gamma_deg;
  d.c_deg.reserve(planes.size());
  d.candela.reserve(planes.size() * gamma_deg.size());
  for (const CPlane& p : planes) {
    d.c_deg.push_back(p.c_deg);
    for (const double v : p.values) d.candela.push_back(v * scale);
  }
  d.check_consistent();
  return d;
}

}  // namespace detail

namespace {

// An IES LM-63 file starts with its format line ("IESNA:LM-63-2002", "IESNA91", "IES:LM-63-2019"),
// or, in the 1986 format, with keyword lines and then "TILT=".
bool looks_like_ies(const detail::LuminaireText& text) {
  for (std::size_t k = 0; k < text.line_count(); ++k) {
    const std::string_view line = detail::trimmed(text.line(k));
    if (line.empty()) continue;
    if (line.rfind("IESNA", 0) == 0 || line.rfind("IES:", 0) == 0 || line.rfind("TILT=", 0) == 0) return true;
    return line.front() == '[';
  }
  return false;
}

std::string extension_of(const std::string& path) {
  const auto dot = path.rfind('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

Luminaire parse_luminaire(std::string_view content, const std::string& name, Diagnostics& diagnostics) {
  // A UTF-8 byte order mark is no part of the first line.
  if (content.rfind("\xEF\xBB\xBF", 0) == 0) content.remove_prefix(3);
  const detail::LuminaireText text(content, name);
  const bool ies = looks_like_ies(text) || (extension_of(name) == "ies" && text.line_count() == 0);
  Luminaire luminaire = ies ? detail::parse_ies(text, diagnostics) : detail::parse_eulumdat(text, diagnostics);
  luminaire.file = name;
  return luminaire;
}

Luminaire read_luminaire(const std::string& path, Diagnostics& diagnostics) {
  const std::string content = read_text_file(path);
  return parse_luminaire(content, input_display_name(path), diagnostics);
}

}  // namespace roadbrdf::lighting
