// EULUMDAT (.ldt): one field per line (the format as published by Stockmar, "EULUMDAT: ein
// Datenformat fuer Lichtstaerkeverteilungen", Licht 1990, and kept by LiTG/DIAL):
//   1 company, 2 type indicator Ityp (0-3), 3 symmetry indicator Isym (0-4), 4 number of C-planes Mc,
//   5 their spacing Dc (0: not equidistant), 6 number of gamma angles Ng, 7 their spacing Dg,
//   8 report number, 9 luminaire name, 10 luminaire number, 11 file name, 12 date/user,
//   13-15 luminaire length (diameter), width (0: circular), height [mm], 16-17 luminous area length
//   (diameter) and width [mm], 18-21 luminous area heights at C0, C90, C180, C270 [mm],
//   22 downward flux fraction DFF [%], 23 light output ratio LORL [%], 24 conversion factor for the
//   intensities, 25 tilt during measurement [deg], 26 number n of lamp sets, then per set: number of
//   lamps (negative: absolute photometry), type, total flux [lm], colour temperature, colour
//   rendering, wattage with ballast [W]; then 10 direct ratios, Mc C angles, Ng gamma angles and the
//   intensities [cd/klm of the lamps' flux], plane by plane, for the planes the symmetry leaves:
//   Isym 0: all Mc planes; 1: one plane; 2: C0..C180 (Mc/2 + 1 planes); 3: C270..C360/C0..C90
//   (Mc/2 + 1 planes, from the plane 3 Mc/4); 4: C0..C90 (Mc/4 + 1 planes).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/luminaire_readers.h"

namespace roadbrdf::lighting::detail {

namespace {

constexpr std::size_t kHeaderLines = 26;  // fields 1-26, before the lamp sets
constexpr std::size_t kLinesPerLampSet = 6;
constexpr std::size_t kDirectRatios = 10;

PhotometricSymmetry symmetry_of(long isym) {
  switch (isym) {
    case 1:
      return PhotometricSymmetry::rotational;
    case 2:
      return PhotometricSymmetry::c0_c180;
    case 3:
      return PhotometricSymmetry::c90_c270;
    case 4:
      return PhotometricSymmetry::quadrants;
    default:
      return PhotometricSymmetry::none;
  }
}

class EulumdatReader {
 public:
  EulumdatReader(const LuminaireText& text, Diagnostics& diagnostics) : text_(text), diagnostics_(diagnostics) {}

  Luminaire read();

 private:
  std::string field(std::size_t k) const {
    if (k >= text_.line_count()) {
      text_.fail(text_.line_count() == 0 ? 0 : text_.line_count() - 1, 0,
                 "truncated: the file ends before field " + std::to_string(k + 1) + " of the EULUMDAT header");
    }
    return text_field(text_.line(k));
  }
  double number(std::size_t k, const std::string& what) { return number_on_line(text_, k, what, decimal_comma_); }
  long integer(std::size_t k, const std::string& what, long lo, long hi) {
    const double value = number(k, what);
    if (value != std::floor(value) || value < static_cast<double>(lo) || value > static_cast<double>(hi)) {
      text_.fail(k, 1, what + " must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
    }
    return static_cast<long>(value);
  }
  // The angles of a list, strictly increasing within [lo, hi].
  std::vector<double> angles(NumberStream& in, std::size_t count, const std::string& what, double lo, double hi);

  const LuminaireText& text_;
  Diagnostics& diagnostics_;
  bool decimal_comma_ = false;
};

std::vector<double> EulumdatReader::angles(NumberStream& in, std::size_t count, const std::string& what, double lo,
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

Luminaire EulumdatReader::read() {
  Luminaire lum;
  lum.format = "eulumdat";
  nlohmann::json& meta = lum.metadata;
  lum.manufacturer = field(0);
  meta["company"] = lum.manufacturer;
  meta["type_indicator"] = integer(1, "type indicator Ityp", 0, 3);
  const long isym = integer(2, "symmetry indicator Isym", 0, 4);
  meta["symmetry_indicator"] = isym;
  lum.symmetry = symmetry_of(isym);
  const long mc = integer(3, "number of C-planes Mc", 1, 3600);
  const double dc = number(4, "C-plane spacing Dc");
  const long ng = integer(5, "number of gamma angles Ng", 1, 3600);
  const double dg = number(6, "gamma spacing Dg");
  meta["c_spacing_deg"] = dc;
  meta["gamma_spacing_deg"] = dg;
  meta["report_number"] = field(7);
  lum.name = field(8);
  meta["luminaire_number"] = field(9);
  if (lum.name.empty()) lum.name = field(9);
  meta["file_name"] = field(10);
  meta["date_user"] = field(11);
  meta["luminaire_mm"] = {{"length", number(12, "luminaire length")},
                          {"width", number(13, "luminaire width")},
                          {"height", number(14, "luminaire height")}};
  const double area_length = number(15, "luminous area length");
  const double area_width = number(16, "luminous area width");
  LuminousArea& area = lum.luminous_area;
  // The EULUMDAT length runs along the C90-C270 axis: the side face seen from C0 is length x
  // height C0 (as Relux reads the files: tests/lighting/luminaire_real_data_test.cpp).
  area.circular = area_width == 0.0;
  area.along_c90_m = area_length / 1000.0;
  area.along_c0_m = area.circular ? area.along_c90_m : area_width / 1000.0;
  const char* const height_names[] = {"C0", "C90", "C180", "C270"};
  for (std::size_t k = 0; k < 4; ++k) {
    area.heights_m[k] = number(17 + k, std::string("luminous area height ") + height_names[k]) / 1000.0;
  }
  if (area_length < 0.0 || area_width < 0.0 ||
      std::min({area.heights_m[0], area.heights_m[1], area.heights_m[2], area.heights_m[3]}) < 0.0) {
    text_.fail(15, 1, "the luminous area's dimensions (fields 16-21) must not be negative");
  }
  meta["luminous_area_mm"] = {{"length", area_length},
                              {"width", area_width},
                              {"height_c0", area.heights_m[0] * 1000.0},
                              {"height_c90", area.heights_m[1] * 1000.0},
                              {"height_c180", area.heights_m[2] * 1000.0},
                              {"height_c270", area.heights_m[3] * 1000.0}};
  meta["downward_flux_fraction_percent"] = number(21, "downward flux fraction DFF");
  const double lorl = number(22, "light output ratio LORL");
  meta["light_output_ratio_percent"] = lorl;
  const double conversion = number(23, "conversion factor for luminous intensities");
  if (!(conversion > 0.0)) text_.fail(23, 1, "the conversion factor for luminous intensities must be positive");
  meta["intensity_conversion_factor"] = conversion;
  meta["measurement_tilt_deg"] = number(24, "tilt during measurement");
  const long sets = integer(25, "number of lamp sets", 1, 20);
  nlohmann::json lamp_sets = nlohmann::json::array();
  for (long s = 0; s < sets; ++s) {
    const std::size_t at = kHeaderLines + static_cast<std::size_t>(s) * kLinesPerLampSet;
    const std::string set = "lamp set " + std::to_string(s + 1);
    lamp_sets.push_back({{"number_of_lamps", integer(at, set + ": number of lamps", -100000, 100000)},
                         {"type", field(at + 1)},
                         {"flux_lm", number(at + 2, set + ": total luminous flux")},
                         {"colour_temperature", field(at + 3)},
                         {"colour_rendering", field(at + 4)},
                         {"power_w", number(at + 5, set + ": wattage")}});
  }
  meta["lamp_sets"] = lamp_sets;
  if (sets > 1) {
    diagnostics_.note("lamp_sets", "the file gives " + std::to_string(sets) +
                                       " lamp sets: the first is used, the others are kept in the metadata");
  }
  const std::size_t first_set = kHeaderLines;
  const double lamp_flux = lamp_sets[0]["flux_lm"].get<double>();
  if (!(lamp_flux > 0.0)) text_.fail(first_set + 2, 1, "lamp set 1: the total luminous flux must be positive");
  lum.absolute_photometry = lamp_sets[0]["number_of_lamps"].get<long>() < 0;
  lum.lamp_flux_lm = lum.absolute_photometry ? 0.0 : lamp_flux;
  lum.flux_lm = lum.absolute_photometry ? lamp_flux : lamp_flux * lorl / 100.0;
  lum.power_w = lamp_sets[0]["power_w"].get<double>();
  const std::size_t ratios_at = kHeaderLines + static_cast<std::size_t>(sets) * kLinesPerLampSet;
  nlohmann::json ratios = nlohmann::json::array();
  for (std::size_t k = 0; k < kDirectRatios; ++k) {
    ratios.push_back(number(ratios_at + k, "direct ratio " + std::to_string(k + 1) + " of 10"));
  }
  meta["direct_ratios"] = ratios;

  NumberStream in(text_, ratios_at + kDirectRatios, false);
  const auto n_c = static_cast<std::size_t>(mc);
  const auto n_g = static_cast<std::size_t>(ng);
  const std::vector<double> c_angles = angles(in, n_c, "C angle", 0.0, 360.0 - 1e-9);
  const std::vector<double> gamma = angles(in, n_g, "gamma angle", 0.0, 180.0);
  const auto check_step = [&](const std::vector<double>& list, double step, const char* what) {
    if (step <= 0.0) return;
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (std::abs(list[k] - list[0] - static_cast<double>(k) * step) > 1e-3) {
        diagnostics_.warn("angle_spacing", std::string("the ") + what + " angles are not spaced by the header's " +
                                               std::to_string(step) + " deg; the listed angles are used");
        return;
      }
    }
  };
  check_step(c_angles, dc, "C");
  check_step(gamma, dg, "gamma");

  // The planes the symmetry leaves, as indices into the C angles, and where each must lie.
  std::vector<std::size_t> stored;
  const auto need = [&](std::size_t index, double c) {
    if (std::abs(c_angles[index] - c) > 1e-6) {
      text_.fail(ratios_at + kDirectRatios + index, 0,
                 "symmetry indicator " + std::to_string(isym) + " needs C angle " + std::to_string(index + 1) + " at " +
                     std::to_string(c) + " deg, the file has " + std::to_string(c_angles[index]));
    }
  };
  const auto need_divisible = [&](long by) {
    if (mc % by != 0) {
      text_.fail(3, 1,
                 "symmetry indicator " + std::to_string(isym) + " needs a number of C-planes divisible by " +
                     std::to_string(by) + ", the file has " + std::to_string(mc));
    }
  };
  switch (isym) {
    case 0:
      for (std::size_t k = 0; k < n_c; ++k) stored.push_back(k);
      break;
    case 1:
      stored.push_back(0);
      break;
    case 2:
      need_divisible(2);
      for (std::size_t k = 0; k <= n_c / 2; ++k) stored.push_back(k);
      need(0, 0.0);
      need(n_c / 2, 180.0);
      break;
    case 3:
      need_divisible(4);
      for (std::size_t k = 0; k <= n_c / 2; ++k) stored.push_back((3 * n_c / 4 + k) % n_c);
      need(3 * n_c / 4, 270.0);
      need(n_c / 4, 90.0);
      break;
    default:
      need_divisible(4);
      for (std::size_t k = 0; k <= n_c / 4; ++k) stored.push_back(k);
      need(0, 0.0);
      need(n_c / 4, 90.0);
      break;
  }
  std::vector<CPlane> planes;
  for (std::size_t p = 0; p < stored.size(); ++p) {
    CPlane plane{isym == 1 ? 0.0 : c_angles[stored[p]], {}};
    plane.values.reserve(n_g);
    for (std::size_t j = 0; j < n_g; ++j) {
      const std::string what = "intensity " + std::to_string(j + 1) + " of C-plane " + std::to_string(p + 1) + " of " +
                               std::to_string(stored.size());
      const double value = in.next(what);
      if (value < 0.0) text_.fail(in.line(), in.column(), what + " is negative");
      plane.values.push_back(value);
    }
    planes.push_back(std::move(plane));
  }
  if (!in.at_end()) {
    in.next("a value after the intensities");
    text_.fail(in.line(), in.column(),
               "more values than the header's counts give (" + std::to_string(stored.size()) + " C-planes of " +
                   std::to_string(ng) + " intensities for symmetry indicator " + std::to_string(isym) + ")");
  }
  if (decimal_comma_ || in.read_decimal_comma()) {
    diagnostics_.note("decimal_comma", "numbers with a decimal comma were read as decimal numbers");
  }
  // cd = (cd/klm) x conversion factor x flux of the lamps (or of the luminaire, absolute) / 1000 lm.
  lum.distribution =
      make_distribution(expand_symmetry(std::move(planes), lum.symmetry), gamma, conversion * lamp_flux / 1000.0);
  return lum;
}

}  // namespace

Luminaire parse_eulumdat(const LuminaireText& text, Diagnostics& diagnostics) {
  return EulumdatReader(text, diagnostics).read();
}

}  // namespace roadbrdf::lighting::detail
