// The CSV table `roadbrdf albedo` prints without --json, written from the JSON report alone (so
// that the two can never disagree): a commented header with the notes, one row per wavelength, then
// the broadband and luminous values as comment lines.
#include <fmt/core.h>

#include <sstream>

#include "roadbrdf/albedo/report.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/json_input.h"

namespace roadbrdf::albedo {

namespace {

using Rows = std::vector<std::vector<double>>;

// A standard uncertainty in the table: "nan" where undefined (JSON null).
std::string u_text(const nlohmann::json& v) {
  return v.is_null() ? std::string("nan") : fmt::format("{:.2e}", v.get<double>());
}

// " u INDEPENDENT (correlated CORRELATED)" after a broadband value, or nothing.
std::string broadband_u_text(const nlohmann::json& u) {
  return u.is_null() ? std::string()
                     : fmt::format(" u {} (correlated {})", u_text(u.at("independent")), u_text(u.at("correlated")));
}

// The per-wavelength part of the report.
struct Columns {
  std::vector<double> zeniths, wavelengths, white, white_error;
  Rows black, black_error, blue, blue_error, diffuse;
  bool spectral = false;
  nlohmann::json uncertainty;  // null or the report's "uncertainty"
};

Columns columns_of(const nlohmann::json& j) {
  Columns c;
  c.zeniths = j.at("sun_zenith_deg").get<std::vector<double>>();
  c.wavelengths = j.at("wavelengths").get<std::vector<double>>();
  c.spectral = j.at("spectral").get<bool>();
  c.white = j.at("white_sky").get<std::vector<double>>();
  c.white_error = j.at("white_sky_error").get<std::vector<double>>();
  c.black = j.at("black_sky").get<Rows>();
  c.black_error = j.at("black_sky_error").get<Rows>();
  if (!j.at("blue_sky").is_null()) {
    c.blue = j.at("blue_sky").get<Rows>();
    c.blue_error = j.at("blue_sky_error").get<Rows>();
    c.diffuse = j.at("diffuse_fraction").get<Rows>();
  }
  c.uncertainty = j.contains("uncertainty") ? j.at("uncertainty") : nlohmann::json(nullptr);
  return c;
}

void write_heading(const Columns& c, std::ostringstream& text) {
  text << (c.spectral ? "wavelength_nm" : "set") << ",white_sky,white_sky_error";
  for (double z : c.zeniths) {
    text << fmt::format(",black_sky_{0:g}deg,black_sky_error_{0:g}deg", z);
    if (!c.blue.empty()) text << fmt::format(",diffuse_fraction_{0:g}deg,blue_sky_{0:g}deg,blue_sky_error_{0:g}deg", z);
  }
  // Standard uncertainties as the last columns.
  if (!c.uncertainty.is_null()) {
    text << ",white_sky_u";
    for (double z : c.zeniths) {
      text << fmt::format(",black_sky_u_{:g}deg", z);
      if (!c.blue.empty()) text << fmt::format(",blue_sky_u_{:g}deg", z);
    }
  }
  text << '\n';
}

void write_row(const Columns& c, std::size_t s, std::ostringstream& text) {
  text << (c.spectral ? fmt::format("{:g}", c.wavelengths[s]) : std::string("-"));
  text << fmt::format(",{:.8f},{:.2e}", c.white[s], c.white_error[s]);
  for (std::size_t z = 0; z < c.zeniths.size(); ++z) {
    text << fmt::format(",{:.8f},{:.2e}", c.black[z][s], c.black_error[z][s]);
    if (!c.blue.empty())
      text << fmt::format(",{:.6f},{:.8f},{:.2e}", c.diffuse[z][s], c.blue[z][s], c.blue_error[z][s]);
  }
  if (!c.uncertainty.is_null()) {
    text << ',' << u_text(c.uncertainty.at("white_sky")[s]);
    for (std::size_t z = 0; z < c.zeniths.size(); ++z) {
      text << ',' << u_text(c.uncertainty.at("black_sky")[z][s]);
      if (!c.blue.empty()) text << ',' << u_text(c.uncertainty.at("blue_sky")[z][s]);
    }
  }
  text << '\n';
}

// "# white_sky ... +- ... u ..." and one line per sun zenith (black-sky, blue-sky).
void write_broadband(const nlohmann::json& b, const Columns& c, std::ostringstream& text) {
  text << fmt::format("# broadband (weighting: {}; solar energy outside the model's wavelength range: {:.4f})\n",
                      b.at("weighting").get<std::string>(), b.at("solar_fraction_outside_range").get<double>());
  const nlohmann::json u = c.uncertainty.is_null() || !c.uncertainty.contains("broadband")
                               ? nlohmann::json(nullptr)
                               : c.uncertainty.at("broadband");
  text << fmt::format("# white_sky {:.6f} +- {:.1e}{}\n", b.at("white_sky").get<double>(),
                      b.at("white_sky_error").get<double>(), u.is_null() ? "" : broadband_u_text(u.at("white_sky")));
  const auto black = b.at("black_sky").get<std::vector<double>>();
  const auto black_error = b.at("black_sky_error").get<std::vector<double>>();
  const bool with_blue = !b.at("blue_sky").is_null();
  for (std::size_t z = 0; z < c.zeniths.size(); ++z) {
    text << fmt::format("# sun zenith {:g} deg: black_sky {:.6f} +- {:.1e}{}", c.zeniths[z], black[z], black_error[z],
                        u.is_null() ? "" : broadband_u_text(u.at("black_sky")[z]));
    if (with_blue) {
      text << fmt::format("  blue_sky {:.6f} +- {:.1e}{}", b.at("blue_sky")[z].get<double>(),
                          b.at("blue_sky_error")[z].get<double>(),
                          u.is_null() || u.at("blue_sky").is_null() ? "" : broadband_u_text(u.at("blue_sky")[z]));
    }
    text << '\n';
  }
}

void write_luminous(const nlohmann::json& l, const Columns& c, std::ostringstream& text) {
  const auto black = l.at("black_sky").get<std::vector<double>>();
  if (black.empty()) return;
  text << fmt::format("# luminous (V(lambda) x {}): white_sky {:.6f}", l.at("illuminant").get<std::string>(),
                      l.at("white_sky").get<double>());
  for (std::size_t z = 0; z < c.zeniths.size(); ++z)
    text << fmt::format("  black_sky_{:g}deg {:.6f}", c.zeniths[z], black[z]);
  text << '\n';
}

}  // namespace

std::string albedo_table(const nlohmann::json& j) {
  const Columns c = columns_of(j);
  std::ostringstream text;
  text << fmt::format("# albedo of {} ({}); dimensionless reflectances, absolute error estimates (tolerance {:g})\n",
                      j.at("model").get<std::string>(), c.spectral ? "fit file" : "constant parameters",
                      j.at("tolerance").get<double>());
  for (const auto& n : j.at("notes").get<std::vector<std::string>>()) text << "# " << n << '\n';
  for (const auto& w : j.at("warnings")) text << "# WARNING: " << w.at("message").get<std::string>() << '\n';
  write_heading(c, text);
  for (std::size_t s = 0; s < c.white.size(); ++s) write_row(c, s, text);
  if (!j.at("broadband").is_null()) write_broadband(j.at("broadband"), c, text);
  if (!j.at("luminous").is_null()) write_luminous(j.at("luminous"), c, text);
  return text.str();
}

void write_albedo_report(const nlohmann::json& report, const std::string& path, bool as_json) {
  AtomicFile out(path);
  if (as_json) {
    write_json(out.stream(), report, 2);
    out.stream() << "\n";
  } else {
    out.stream() << albedo_table(report);
  }
  out.commit();
}

}  // namespace roadbrdf::albedo
