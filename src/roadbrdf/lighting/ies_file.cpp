// IES LM-63 (.ies), the 1986, 1991 ("IESNA91"), 1995 ("IESNA:LM-63-1995"), 2002 ("IESNA:LM-63-2002")
// and 2019 ("IES:LM-63-2019") formats: an optional format line, keyword lines "[KEYWORD] text"
// ("[MORE]" continues the previous one; the 1986 format has free text instead), the line "TILT=NONE",
// "TILT=INCLUDE" (then the lamp-to-luminaire geometry, the number of tilt angles, the angles and the
// multiplying factors) or "TILT=<file>", and then numbers separated by blanks, commas or line ends:
//   number of lamps, lumens per lamp (-1: absolute photometry), candela multiplier, number of
//   vertical angles, number of horizontal angles, photometric type (1 = C, 2 = B, 3 = A), units
//   (1 = feet, 2 = metres), width, length, height of the luminous opening;
//   ballast factor, ballast-lamp photometric factor (1991 and before; "future use", 1, since 1995),
//   input watts; the vertical angles, the horizontal angles, and the candela values horizontal angle
//   by horizontal angle.
// For type C the vertical angle is gamma and the horizontal angle is the C-plane: LM-63-2002 clause
// 3.0 defines the horizontal angles of type C counter-clockwise seen from above from the 0 deg
// photometric plane, as CIE 121 counts C. The range of the horizontal angles gives the lateral
// symmetry: 0 only (rotational), 0-90 (quadrants), 0-180 (about the C0-C180 plane), 90-270 (about
// the C90-C270 plane), 0-360 (none).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/luminaire_flux.h"
#include "roadbrdf/lighting/luminaire_readers.h"

namespace roadbrdf::lighting::detail {

namespace {

constexpr double kFoot = 0.3048;  // m

// The LM-63 edition of a format line, 1986 when there is none.
int edition_of(std::string_view first_line) {
  if (first_line.rfind("IESNA91", 0) == 0) return 1991;
  if (first_line.rfind("IESNA", 0) != 0 && first_line.rfind("IES:", 0) != 0) return 1986;
  // "IESNA:LM-63-1995", "IESNA:LM-63-2002", "IES:LM-63-2019": the last four digits.
  const std::size_t n = first_line.size();
  if (n >= 4) {
    int year = 0;
    for (std::size_t k = n - 4; k < n; ++k) {
      if (first_line[k] < '0' || first_line[k] > '9') return 2002;
      year = 10 * year + (first_line[k] - '0');
    }
    return year;
  }
  return 2002;
}

class IesReader {
 public:
  IesReader(const LuminaireText& text, Diagnostics& diagnostics) : text_(text), diagnostics_(diagnostics) {}
  Luminaire read();

 private:
  // The header lines up to TILT=; returns the index of the TILT line.
  std::size_t read_header(nlohmann::json& meta);
  std::vector<double> angles(NumberStream& in, std::size_t count, const std::string& what, double lo, double hi);
  PhotometricSymmetry lateral_symmetry(std::vector<double>& horizontal, std::vector<CPlane>& planes, std::size_t line,
                                       std::size_t column);

  const LuminaireText& text_;
  Diagnostics& diagnostics_;
  int edition_ = 1986;
};

std::size_t IesReader::read_header(nlohmann::json& meta) {
  std::size_t k = 0;
  if (text_.line_count() > 0) {
    const std::string_view first = trimmed(text_.line(0));
    edition_ = edition_of(first);
    if (edition_ != 1986) {
      meta["format_line"] = text_field(first);
      k = 1;
    }
  }
  meta["lm63_edition"] = edition_;
  nlohmann::json keywords = nlohmann::json::object();
  nlohmann::json free_text = nlohmann::json::array();
  std::string last_keyword;
  for (; k < text_.line_count(); ++k) {
    const std::string_view line = trimmed(text_.line(k));
    if (line.rfind("TILT", 0) == 0) {
      meta["keywords"] = keywords;
      if (!free_text.empty()) meta["text"] = free_text;
      return k;
    }
    if (line.empty()) continue;
    const std::size_t close = line.find(']');
    if (line.front() == '[' && close != std::string_view::npos) {
      const std::string keyword = text_field(line.substr(1, close - 1));
      const std::string value = text_field(line.substr(close + 1));
      if (keyword == "MORE" && !last_keyword.empty()) {
        keywords[last_keyword] = keywords[last_keyword].get<std::string>() + " " + value;
      } else if (keywords.contains(keyword)) {
        // A repeated keyword adds a line to its text, nothing is overwritten.
        keywords[keyword] = keywords[keyword].get<std::string>() + "\n" + value;
        last_keyword = keyword;
      } else {
        keywords[keyword] = value;
        last_keyword = keyword;
      }
    } else {
      free_text.push_back(text_field(line));
    }
  }
  text_.fail(text_.line_count() == 0 ? 0 : text_.line_count() - 1, 0, "truncated: the file ends before its TILT= line");
}

std::vector<double> IesReader::angles(NumberStream& in, std::size_t count, const std::string& what, double lo,
                                      double hi) {
  std::vector<double> out;
  for (std::size_t k = 0; k < count; ++k) {
    const std::string name = what + " " + std::to_string(k + 1) + " of " + std::to_string(count);
    const double a = in.next(name);
    if (a < lo || a > hi) {
      text_.fail(
          in.line(), in.column(),
          name + " is " + std::to_string(a) + ", outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "] deg");
    }
    if (!out.empty() && a <= out.back()) text_.fail(in.line(), in.column(), name + ": the angles must increase");
    out.push_back(a);
  }
  return out;
}

PhotometricSymmetry IesReader::lateral_symmetry(std::vector<double>& horizontal, std::vector<CPlane>& planes,
                                                std::size_t line, std::size_t column) {
  const double first = horizontal.front();
  const double last = horizontal.back();
  if (horizontal.size() == 1 && first == 0.0) return PhotometricSymmetry::rotational;
  if (first == 0.0 && last == 90.0) return PhotometricSymmetry::quadrants;
  if (first == 0.0 && last == 180.0) return PhotometricSymmetry::c0_c180;
  if (first == 90.0 && last == 270.0) return PhotometricSymmetry::c90_c270;
  if (first == 0.0 && last == 360.0) {
    // The plane at 360 deg is the plane at 0 deg again.
    double largest = 0.0, difference = 0.0;
    for (std::size_t j = 0; j < planes.front().values.size(); ++j) {
      largest = std::max(largest, planes.front().values[j]);
      difference = std::max(difference, std::abs(planes.back().values[j] - planes.front().values[j]));
    }
    if (difference > 0.0) {
      diagnostics_.warn("c360_differs",
                        "the intensities at horizontal angle 360 deg differ from those at 0 deg by up "
                        "to " +
                            std::to_string(difference) + " (the largest at 0 deg is " + std::to_string(largest) +
                            "); those at 0 deg are used");
    }
    planes.pop_back();
    horizontal.pop_back();
    return PhotometricSymmetry::none;
  }
  if (first == 0.0 && last > 180.0) {
    diagnostics_.note("open_horizontal_range", "the horizontal angles end at " + std::to_string(last) +
                                                   " deg, not 360: between them and 360 deg the intensities are "
                                                   "interpolated towards those at 0 deg");
    return PhotometricSymmetry::none;
  }
  text_.fail(line, column,
             "horizontal angles from " + std::to_string(first) + " to " + std::to_string(last) +
                 " deg: LM-63 gives type C files 0 (rotational symmetry), 0-90, 0-180, 90-270 or 0-360 deg");
}

Luminaire IesReader::read() {
  Luminaire lum;
  lum.format = "ies";
  nlohmann::json& meta = lum.metadata;
  const std::size_t tilt_line = read_header(meta);
  const std::string_view tilt = trimmed(text_.line(tilt_line));
  if (tilt.rfind("TILT=", 0) != 0) text_.fail(tilt_line, 1, "expected TILT=NONE, TILT=INCLUDE or TILT=<file>");
  const std::string tilt_value = text_field(tilt.substr(5));
  NumberStream in(text_, tilt_line + 1, true);
  if (tilt_value == "INCLUDE") {
    const long geometry = in.next_integer("the lamp-to-luminaire geometry of the tilt data", 1, 3);
    const long count = in.next_integer("the number of tilt angles", 0, 100000);
    std::vector<double> tilt_angles = angles(in, static_cast<std::size_t>(count), "tilt angle", 0.0, 180.0);
    std::vector<double> factors;
    for (long k = 0; k < count; ++k) {
      const double f = in.next("tilt multiplying factor " + std::to_string(k + 1) + " of " + std::to_string(count));
      if (f < 0.0) text_.fail(in.line(), in.column(), "a tilt multiplying factor must not be negative");
      factors.push_back(f);
    }
    meta["tilt"] = {{"lamp_to_luminaire_geometry", geometry}, {"angles_deg", tilt_angles}, {"factors", factors}};
    diagnostics_.note("tilt_table",
                      "the file's TILT=INCLUDE table (lamp output against the luminaire's tilt) is "
                      "kept in the metadata; the intensities are those of the luminaire as measured");
  } else if (tilt_value != "NONE") {
    text_.fail(tilt_line, 6,
               "TILT=" + tilt_value +
                   " names a separate tilt file, which is not read (TILT=NONE and "
                   "TILT=INCLUDE are)");
  }
  const long lamps = in.next_integer("the number of lamps", 1, 100000);
  const double lumens = in.next("the lumens per lamp");
  if (lumens != -1.0 && !(lumens > 0.0)) {
    text_.fail(in.line(), in.column(), "the lumens per lamp must be positive, or -1 for absolute photometry");
  }
  const double multiplier = in.next("the candela multiplier");
  if (!(multiplier > 0.0)) text_.fail(in.line(), in.column(), "the candela multiplier must be positive");
  const auto n_v = static_cast<std::size_t>(in.next_integer("the number of vertical angles", 1, 100000));
  const auto n_h = static_cast<std::size_t>(in.next_integer("the number of horizontal angles", 1, 100000));
  const long type = in.next_integer("the photometric type", 1, 3);
  if (type != 1) {
    text_.fail(in.line(), in.column(),
               std::string("photometric type ") + (type == 2 ? "B" : "A") + " is not supported: only type C (1) is");
  }
  const long units = in.next_integer("the units type", 1, 2);
  const double width = in.next("the width of the luminous opening");
  const double length = in.next("the length of the luminous opening");
  const double height = in.next("the height of the luminous opening");
  const double ballast = in.next("the ballast factor");
  if (!(ballast > 0.0)) text_.fail(in.line(), in.column(), "the ballast factor must be positive");
  const double lamp_factor = in.next(edition_ < 1995 ? "the ballast-lamp photometric factor" : "the future-use field");
  if (!(lamp_factor > 0.0)) text_.fail(in.line(), in.column(), "the ballast-lamp photometric factor must be positive");
  lum.power_w = in.next("the input watts");
  const std::vector<double> vertical = angles(in, n_v, "vertical angle", 0.0, 180.0);
  std::vector<double> horizontal = angles(in, n_h, "horizontal angle", 0.0, 360.0);
  const std::size_t horizontal_line = in.line();
  const std::size_t horizontal_column = in.column();
  std::vector<CPlane> planes;
  for (std::size_t i = 0; i < n_h; ++i) {
    CPlane plane{horizontal[i], {}};
    plane.values.reserve(n_v);
    for (std::size_t j = 0; j < n_v; ++j) {
      const std::string what = "candela value " + std::to_string(j + 1) + " of horizontal angle " +
                               std::to_string(i + 1) + " of " + std::to_string(n_h);
      const double value = in.next(what);
      if (value < 0.0) text_.fail(in.line(), in.column(), what + " is negative");
      plane.values.push_back(value);
    }
    planes.push_back(std::move(plane));
  }
  if (!in.at_end()) {
    in.next("a value after the candela values");
    text_.fail(in.line(), in.column(),
               "more values than the header's counts give (" + std::to_string(n_h) + " horizontal angles of " +
                   std::to_string(n_v) + " candela values)");
  }
  lum.symmetry = lateral_symmetry(horizontal, planes, horizontal_line, horizontal_column);

  // candela as rated = value x multiplier x ballast factor (x the ballast-lamp photometric factor
  // before 1995; since then the field is reserved and must be 1).
  double scale = multiplier * ballast;
  if (edition_ < 1995) {
    scale *= lamp_factor;
  } else if (lamp_factor != 1.0) {
    diagnostics_.warn("future_use_field", "the field after the ballast factor is " + std::to_string(lamp_factor) +
                                              " where LM-63 since 1995 reserves it as 1; it is not applied");
  }
  lum.absolute_photometry = lumens == -1.0;
  lum.lamp_flux_lm = lum.absolute_photometry
                         ? 0.0
                         : static_cast<double>(lamps) * lumens * ballast * (edition_ < 1995 ? lamp_factor : 1.0);
  lum.distribution = make_distribution(expand_symmetry(std::move(planes), lum.symmetry), vertical, scale);
  // The file states no luminaire flux: the luminaire's is its intensities' integral.
  lum.flux_lm = luminous_flux(lum.distribution).total_lm();

  const double unit = units == 1 ? kFoot : 1.0;
  LuminousArea& area = lum.luminous_area;
  area.circular = width < 0.0 && length < 0.0;  // LM-63-2002 Table 1: negative sizes give round shapes
  // LM-63: the length along the 0-180 deg photometric axis, the width across it.
  area.along_c0_m = std::abs(length) * unit;
  area.along_c90_m = std::abs(width) * unit;
  area.heights_m = {std::abs(height) * unit, std::abs(height) * unit, std::abs(height) * unit, std::abs(height) * unit};
  meta["number_of_lamps"] = lamps;
  meta["lumens_per_lamp"] = lumens;
  meta["candela_multiplier"] = multiplier;
  meta["ballast_factor"] = ballast;
  meta[edition_ < 1995 ? "ballast_lamp_photometric_factor" : "future_use"] = lamp_factor;
  meta["units"] = units == 1 ? "feet" : "metres";
  meta["luminous_opening"] = {{"width", width}, {"length", length}, {"height", height}};
  const nlohmann::json& keywords = meta["keywords"];
  const auto keyword = [&keywords](const char* key) {
    return keywords.contains(key) ? keywords[key].get<std::string>() : std::string();
  };
  lum.name = keyword("LUMINAIRE");
  if (lum.name.empty()) lum.name = keyword("LUMCAT");
  lum.manufacturer = keyword("MANUFAC");
  return lum;
}

}  // namespace

Luminaire parse_ies(const LuminaireText& text, Diagnostics& diagnostics) { return IesReader(text, diagnostics).read(); }

}  // namespace roadbrdf::lighting::detail
