#include "roadbrdf/surface/height_field.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/json_input.h"

namespace roadbrdf::surface {

namespace fs = std::filesystem;
using nlohmann::json;

double HeightField::height_at(double x, double y) const {
  const double fx = x / cell_size_mm, fy = y / cell_size_mm;
  const double fi = std::floor(fx), fj = std::floor(fy);
  const long i = static_cast<long>(fi), j = static_cast<long>(fj);
  const double u = fx - fi, v = fy - fj;
  const double z00 = height(i, j), z10 = height(i + 1, j), z01 = height(i, j + 1), z11 = height(i + 1, j + 1);
  if (u >= v) return z00 + (z10 - z00) * u + (z11 - z10) * v;
  return z00 + (z11 - z01) * u + (z01 - z00) * v;
}

void validate(const HeightField& f) {
  if (!(f.cell_size_mm > 0.0) || !std::isfinite(f.cell_size_mm)) throw InputError("surface: cell size must be > 0");
  if (f.nx < 2 || f.ny < 2) throw InputError("surface: needs at least 2 x 2 cells");
  const std::size_t n = static_cast<std::size_t>(f.nx) * f.ny;
  if (f.heights.size() != n) throw InputError("surface: heights_mm must hold nx*ny values");
  if (f.material.size() != n) throw InputError("surface: material must hold nx*ny values");
  if (f.materials.empty()) throw InputError("surface: no materials");
  for (double z : f.heights) {
    if (!std::isfinite(z)) throw InputError("surface: a height is not finite");
  }
  for (auto m : f.material) {
    if (m >= f.materials.size()) {
      throw InputError("surface: material index " + std::to_string(m) + " but only " +
                       std::to_string(f.materials.size()) + " materials");
    }
  }
}

HeightField make_flat(const MaterialSpec& material, int n, double cell_size_mm) {
  HeightField f;
  f.name = "flat " + material.name;
  f.description = "flat sample z = 0 of one material";
  f.cell_size_mm = cell_size_mm;
  f.nx = f.ny = n;
  f.heights.assign(static_cast<std::size_t>(n) * n, 0.0);
  f.material.assign(static_cast<std::size_t>(n) * n, 0);
  f.materials = {material};
  return f;
}

namespace {

// MPD of one periodic profile of n equally spaced values (ISO 13473-1 style, see header).
double profile_mpd(const std::vector<double>& z) {
  const std::size_t n = z.size();
  // Remove the least-squares linear trend.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double x = static_cast<double>(k);
    sx += x;
    sy += z[k];
    sxx += x * x;
    sxy += x * z[k];
  }
  const double dn = static_cast<double>(n);
  const double den = dn * sxx - sx * sx;
  const double slope = den != 0.0 ? (dn * sxy - sx * sy) / den : 0.0;
  const double intercept = (sy - slope * sx) / dn;
  double mean = 0.0, peak1 = -1e300, peak2 = -1e300;
  for (std::size_t k = 0; k < n; ++k) {
    const double r = z[k] - (intercept + slope * static_cast<double>(k));
    mean += r / dn;
    if (k < n / 2) {
      peak1 = std::max(peak1, r);
    } else {
      peak2 = std::max(peak2, r);
    }
  }
  return 0.5 * (peak1 + peak2) - mean;
}

}  // namespace

TextureStatistics texture_statistics(const HeightField& f) {
  validate(f);
  TextureStatistics s;
  const std::size_t n = f.heights.size();
  double sum = 0.0, sum2 = 0.0;
  s.max_height_mm = -1e300;
  s.min_height_mm = 1e300;
  for (double z : f.heights) {
    sum += z;
    s.max_height_mm = std::max(s.max_height_mm, z);
    s.min_height_mm = std::min(s.min_height_mm, z);
  }
  s.mean_height_mm = sum / static_cast<double>(n);
  for (double z : f.heights) sum2 += (z - s.mean_height_mm) * (z - s.mean_height_mm);
  s.rms_height_mm = std::sqrt(sum2 / static_cast<double>(n));

  double mpd = 0.0;
  std::vector<double> profile(f.nx);
  for (int j = 0; j < f.ny; ++j) {
    for (int i = 0; i < f.nx; ++i) profile[i] = f.height(i, j);
    mpd += profile_mpd(profile);
  }
  profile.assign(f.ny, 0.0);
  for (int i = 0; i < f.nx; ++i) {
    for (int j = 0; j < f.ny; ++j) profile[j] = f.height(i, j);
    mpd += profile_mpd(profile);
  }
  s.mpd_mm = mpd / static_cast<double>(f.nx + f.ny);
  s.etd_mm = 0.2 + 0.8 * s.mpd_mm;

  const std::size_t m = f.materials.size();
  s.exposed_area_fraction.assign(m, 0.0);
  s.exposed_true_area_fraction.assign(m, 0.0);
  const double h = f.cell_size_mm;
  double true_total = 0.0;
  for (int j = 0; j < f.ny; ++j) {
    for (int i = 0; i < f.nx; ++i) {
      const double z00 = f.height(i, j), z10 = f.height(i + 1, j), z01 = f.height(i, j + 1),
                   z11 = f.height(i + 1, j + 1);
      // Areas of the two triangles (projected area h^2/2 each) divided by h^2: sqrt(1+|grad|^2)/2.
      const double a1 =
          0.5 * std::sqrt(1.0 + ((z10 - z00) / h) * ((z10 - z00) / h) + ((z11 - z10) / h) * ((z11 - z10) / h));
      const double a2 =
          0.5 * std::sqrt(1.0 + ((z11 - z01) / h) * ((z11 - z01) / h) + ((z01 - z00) / h) * ((z01 - z00) / h));
      const auto mat = f.material_at(i, j);
      s.exposed_area_fraction[mat] += 1.0;
      s.exposed_true_area_fraction[mat] += a1 + a2;
      true_total += a1 + a2;
    }
  }
  for (std::size_t k = 0; k < m; ++k) {
    s.exposed_area_fraction[k] /= static_cast<double>(n);
    s.exposed_true_area_fraction[k] /= true_total;
  }
  s.surface_area_ratio = true_total / static_cast<double>(n);
  return s;
}

// ---- file I/O ---------------------------------------------------------------------------------

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw FileError(path, 0, 0, what); }

std::string relative_to(const std::string& target, const std::string& file) {
  if (target.empty()) return target;
  fs::path folder = fs::path(file).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  const fs::path rel = fs::relative(fs::absolute(target, ec), fs::absolute(folder, ec), ec);
  if (ec || rel.empty()) return fs::absolute(target).string();
  return rel.generic_string();
}

std::string resolve_from(const std::string& target, const std::string& file) {
  if (target.empty() || fs::path(target).is_absolute()) return target;
  const fs::path folder = fs::path(file).parent_path();
  return (folder / target).lexically_normal().string();
}

}  // namespace

HeightField read_surface(const std::string& path) {
  const Json document = parse_json_file(path);
  const JsonNode root(document, input_display_name(path));
  if (!root.is_object()) root.fail("a surface file is a JSON object");
  if (root.string_or("format", "") != "roadbrdf-surface") root.fail("\"format\" must be \"roadbrdf-surface\"");
  if (root.at("version").integer(1, 1) != 1) root.fail("unsupported \"version\" (expected 1)");
  HeightField f;
  f.name = root.string_or("name", "");
  f.description = root.string_or("description", "");
  f.cell_size_mm = root.at("cell_size_mm").number();
  constexpr long long kMaxCells = std::numeric_limits<int>::max();
  f.nx = static_cast<int>(root.at("nx").integer(2, kMaxCells));
  f.ny = static_cast<int>(root.at("ny").integer(2, kMaxCells));
  if (!root.boolean_or("periodic", true)) root.at("periodic").fail("only periodic surfaces are supported");
  f.heights = root.at("heights_mm").numbers();
  const JsonNode mats = root.at("materials");
  const JsonNode material = root.at("material");
  const long long last_material = static_cast<long long>(std::min<std::size_t>(mats.size(), 65536)) - 1;
  if (last_material < 0) mats.fail("no materials");
  f.material.reserve(material.size());
  for (const long long m : material.integers(0, last_material)) f.material.push_back(static_cast<std::uint16_t>(m));
  for (std::size_t k = 0; k < mats.size(); ++k) {
    const JsonNode m = mats[k];
    MaterialSpec spec;
    spec.name = m.at("name").string();
    spec.fit = m.string_or("fit", "");
    spec.fit_model = m.string_or("fit_model", "");
    spec.model = m.string_or("model", "");
    if (const auto p = m.find("parameters")) spec.parameters = p->number_map();
    if (const auto o = m.find("options")) spec.options = o->string_map();
    if (spec.fit.empty() == spec.model.empty()) m.fail("give exactly one of \"fit\" and \"model\"");
    spec.fit_path = resolve_from(spec.fit, path);
    f.materials.push_back(std::move(spec));
  }
  try {
    validate(f);
  } catch (const InputError& e) {
    fail(root.file(), e.what());
  }
  return f;
}

json MaterialSpec::to_json() const {
  if (!model.empty()) return {{"name", name}, {"model", model}, {"parameters", parameters}, {"options", options}};
  return {{"name", name}, {"fit", fit_path.empty() ? fit : fit_path}, {"fit_model", fit_model}};
}

json TextureStatistics::to_json() const {
  return {{"mpd_mm", mpd_mm},
          {"etd_mm", etd_mm},
          {"rms_height_mm", rms_height_mm},
          {"mean_height_mm", mean_height_mm},
          {"min_height_mm", min_height_mm},
          {"max_height_mm", max_height_mm},
          {"surface_area_ratio", surface_area_ratio},
          {"exposed_area_fraction", exposed_area_fraction},
          {"exposed_true_area_fraction", exposed_true_area_fraction}};
}

void write_surface(const HeightField& f, const std::string& path, const TextureStatistics* statistics) {
  validate(f);
  json j;
  j["format"] = "roadbrdf-surface";
  j["version"] = 1;
  j["name"] = f.name;
  j["description"] = f.description;
  j["cell_size_mm"] = f.cell_size_mm;
  j["nx"] = f.nx;
  j["ny"] = f.ny;
  j["periodic"] = true;
  json mats = json::array();
  for (const auto& m : f.materials) {
    json e = m.to_json();
    if (e.contains("fit")) e["fit"] = relative_to(e["fit"].get<std::string>(), path);
    mats.push_back(e);
  }
  j["materials"] = mats;
  if (statistics) {
    json s = statistics->to_json();
    for (const char* key : {"mean_height_mm", "min_height_mm", "max_height_mm"}) s.erase(key);
    s["note"] =
        "informative: MPD over every row and column, baseline = sample period (ISO 13473-1 uses 100 mm); "
        "ETD = 0.2 + 0.8 MPD [mm]; area fractions: projected (horizontal) and true facet area";
    j["statistics"] = s;
  }
  // Heights rounded to 0.1 um keep the file compact (the round trip is then exact).
  std::vector<double> rounded(f.heights.size());
  for (std::size_t k = 0; k < rounded.size(); ++k) rounded[k] = std::round(f.heights[k] * 1e4) / 1e4;
  j["heights_mm"] = rounded;
  j["material"] = f.material;
  AtomicFile out(path);
  write_json(out.stream(), j);
  out.stream() << '\n';
  out.commit();
}

// ---- PNG preview ------------------------------------------------------------------------------

namespace {

std::uint32_t crc32(const unsigned char* data, std::size_t n, std::uint32_t crc = 0xffffffffu) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t k = 0; k < 256; ++k) {
      std::uint32_t c = k;
      for (int b = 0; b < 8; ++b) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[k] = c;
    }
    return t;
  }();
  for (std::size_t k = 0; k < n; ++k) crc = table[(crc ^ data[k]) & 0xff] ^ (crc >> 8);
  return crc;
}

void put32(std::string& s, std::uint32_t v) {
  s.push_back(static_cast<char>(v >> 24));
  s.push_back(static_cast<char>(v >> 16));
  s.push_back(static_cast<char>(v >> 8));
  s.push_back(static_cast<char>(v));
}

void chunk(std::string& png, const char* type, const std::string& data) {
  put32(png, static_cast<std::uint32_t>(data.size()));
  std::string body(type, 4);
  body += data;
  png += body;
  put32(png, crc32(reinterpret_cast<const unsigned char*>(body.data()), body.size()) ^ 0xffffffffu);
}

}  // namespace

void write_preview_png(const HeightField& f, const std::string& path) {
  validate(f);
  const TextureStatistics s = texture_statistics(f);
  const double lo = s.min_height_mm, span = std::max(1e-12, s.max_height_mm - s.min_height_mm);
  static const double hues[][3] = {{0.55, 0.55, 0.55}, {0.95, 0.55, 0.25}, {0.35, 0.65, 0.95}, {0.45, 0.85, 0.40},
                                   {0.90, 0.80, 0.30}, {0.80, 0.40, 0.85}, {0.95, 0.35, 0.40}};
  // Raw scanlines (filter byte 0), top row = largest y.
  std::string raw;
  raw.reserve(static_cast<std::size_t>(f.ny) * (3 * f.nx + 1));
  for (int j = f.ny - 1; j >= 0; --j) {
    raw.push_back('\0');
    for (int i = 0; i < f.nx; ++i) {
      const double z = 0.25 * (f.height(i, j) + f.height(i + 1, j) + f.height(i, j + 1) + f.height(i + 1, j + 1));
      const double b = 0.25 + 0.75 * (z - lo) / span;
      const double* c = hues[f.material_at(i, j) % 7];
      for (int k = 0; k < 3; ++k)
        raw.push_back(static_cast<char>(std::lround(std::clamp(255.0 * b * c[k], 0.0, 255.0))));
    }
  }
  // zlib stream with stored (uncompressed) deflate blocks of at most 65535 bytes.
  std::string z;
  z.push_back(static_cast<char>(0x78));
  z.push_back(static_cast<char>(0x01));
  std::size_t pos = 0;
  do {
    const std::size_t len = std::min<std::size_t>(65535, raw.size() - pos);
    const bool last = pos + len == raw.size();
    z.push_back(static_cast<char>(last ? 1 : 0));
    z.push_back(static_cast<char>(len & 0xff));
    z.push_back(static_cast<char>(len >> 8));
    z.push_back(static_cast<char>(~len & 0xff));
    z.push_back(static_cast<char>((~len >> 8) & 0xff));
    z.append(raw, pos, len);
    pos += len;
  } while (pos < raw.size());
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) {
    a = (a + c) % 65521u;
    b = (b + a) % 65521u;
  }
  put32(z, (b << 16) | a);

  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put32(ihdr, static_cast<std::uint32_t>(f.nx));
  put32(ihdr, static_cast<std::uint32_t>(f.ny));
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit RGB, deflate, no filter, no interlace
  chunk(png, "IHDR", ihdr);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", "");
  AtomicFile out(path);
  out.stream().write(png.data(), static_cast<std::streamsize>(png.size()));
  out.commit();
}

}  // namespace roadbrdf::surface
