#include "roadbrdf/lighting/luminaire_request.h"

#include <fmt/core.h>

#include <array>
#include <cmath>

#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/luminaire_file.h"

namespace roadbrdf::lighting {

RequestFields<LuminaireRequest> LuminaireRequest::fields() {
  static const RequestField<LuminaireRequest> table[] = {
      {"file", "FILE", "", "Luminaire photometry file: EULUMDAT (.ldt) or IES LM-63 (.ies)", &LuminaireRequest::file,
       FileRole::input, true},
  };
  return table;
}

void LuminaireRequest::validate() const {
  if (file.empty()) throw FieldError("file", "a luminaire file is required");
}

namespace {

const char* format_title(const std::string& format) { return format == "ies" ? "IES LM-63" : "EULUMDAT"; }

}  // namespace

double LuminaireSummary::candela_per_klm_factor() const {
  const double klm = (luminaire.lamp_flux_lm > 0.0 ? luminaire.lamp_flux_lm : luminaire.flux_lm) / 1000.0;
  return klm > 0.0 ? 1.0 / klm : 0.0;
}

LuminaireSummary luminaire_summary(const LuminaireRequest& request) {
  request.validate();
  check_request_files(request);
  LuminaireSummary s{};
  s.luminaire = read_luminaire(request.file, s.diagnostics);
  const Luminaire& lum = s.luminaire;
  const IntensityDistribution& d = lum.distribution;
  s.flux = luminous_flux(d);
  s.max_intensity_cd = -1.0;
  for (std::size_t i = 0; i < d.c_deg.size(); ++i) {
    for (std::size_t j = 0; j < d.gamma_deg.size(); ++j) {
      if (d.at(i, j) > s.max_intensity_cd) {
        s.max_intensity_cd = d.at(i, j);
        s.max_c_deg = d.c_deg[i];
        s.max_gamma_deg = d.gamma_deg[j];
      }
    }
  }
  // The header's luminaire flux: EULUMDAT lamp flux x LORL (or the luminaire's, absolute); an IES
  // file states the lamps' flux only, which the luminaire cannot exceed.
  const double total = s.flux.total_lm();
  const double reference = lum.absolute_photometry || lum.lamp_flux_lm <= 0.0 ? total : lum.lamp_flux_lm;
  s.dlor = reference > 0.0 ? s.flux.downward_lm / reference : 0.0;
  s.ulor = reference > 0.0 ? s.flux.upward_lm / reference : 0.0;
  if (lum.format == "eulumdat") {
    s.header_flux_lm = lum.flux_lm;
  } else {
    s.header_flux_lm = lum.absolute_photometry ? 0.0 : lum.lamp_flux_lm;
  }
  if (total <= 0.0) {
    s.diagnostics.warn("no_light", "every intensity of the file is 0");
  } else if (lum.format == "eulumdat" && std::abs(total - s.header_flux_lm) > kFluxTolerance * s.header_flux_lm) {
    s.diagnostics.warn("flux_mismatch",
                       fmt::format("the flux integrated from the intensities, {:.1f} lm, differs by {:+.1f} % from "
                                   "the header's {:.1f} lm (lamp flux x light output ratio)",
                                   total, 100.0 * (total / s.header_flux_lm - 1.0), s.header_flux_lm));
  } else if (lum.format == "ies" && s.header_flux_lm > 0.0 && total > (1.0 + kFluxTolerance) * s.header_flux_lm) {
    s.diagnostics.warn("flux_mismatch",
                       fmt::format("the flux integrated from the intensities, {:.1f} lm, exceeds the lamps' {:.1f} lm "
                                   "of the header by {:.1f} %",
                                   total, s.header_flux_lm, 100.0 * (total / s.header_flux_lm - 1.0)));
  } else if (lum.format == "ies" && lum.absolute_photometry) {
    s.diagnostics.note("no_header_flux",
                       "absolute photometry: the file states no flux to compare the intensities' "
                       "integral with");
  }
  return s;
}

std::string LuminaireSummary::summary_text() const {
  const Luminaire& lum = luminaire;
  const IntensityDistribution& d = lum.distribution;
  std::string out;
  out += fmt::format("luminaire: {}", lum.name.empty() ? std::string("(no name)") : lum.name);
  if (!lum.manufacturer.empty()) out += fmt::format(" ({})", lum.manufacturer);
  out += "\n";
  out += fmt::format("file: {} ({}, {} photometry)\n", lum.file, format_title(lum.format),
                     lum.absolute_photometry ? "absolute" : "relative");
  out +=
      fmt::format("symmetry: {} ({} C-planes after expansion, {} gamma angles {:g}-{:g} deg)\n", name_of(lum.symmetry),
                  d.c_deg.size(), d.gamma_deg.size(), d.gamma_deg.front(), d.gamma_deg.back());
  if (!lum.absolute_photometry) out += fmt::format("lamp flux: {:.1f} lm\n", lum.lamp_flux_lm);
  out += fmt::format("luminaire flux: {:.1f} lm integrated", flux.total_lm());
  if (header_flux_lm > 0.0 && lum.format == "eulumdat") {
    out += fmt::format(", {:.1f} lm in the header ({:+.2f} %)", header_flux_lm,
                       100.0 * (flux.total_lm() / header_flux_lm - 1.0));
  }
  out += "\n";
  out += fmt::format("maximum intensity: {:.1f} cd ({:.1f} cd/klm) at C {:g} deg, gamma {:g} deg\n", max_intensity_cd,
                     max_intensity_cd * candela_per_klm_factor(), max_c_deg, max_gamma_deg);
  out += fmt::format("DLOR {:.3f}, ULOR {:.3f} (downward {:.1f} lm, upward {:.1f} lm)\n", dlor, ulor, flux.downward_lm,
                     flux.upward_lm);
  if (lum.power_w > 0.0) {
    out += fmt::format("power: {:g} W ({:.1f} lm/W)\n", lum.power_w, flux.total_lm() / lum.power_w);
  }
  return out;
}

nlohmann::json LuminaireSummary::to_json() const {
  const Luminaire& lum = luminaire;
  const IntensityDistribution& d = lum.distribution;
  const double per_klm = candela_per_klm_factor();
  nlohmann::json planes = {{"gamma_deg", d.gamma_deg}, {"unit", "cd/klm"}};
  for (const double c : {0.0, 90.0, 180.0, 270.0}) {
    std::vector<double> values;
    values.reserve(d.gamma_deg.size());
    for (const double g : d.gamma_deg) values.push_back(d.intensity(c, g) * per_klm);
    planes[fmt::format("C{:g}", c)] = values;
  }
  const LuminousArea& area = lum.luminous_area;
  nlohmann::json out = {
      {"file", lum.file},
      {"format", lum.format},
      {"name", lum.name},
      {"manufacturer", lum.manufacturer},
      {"photometry", lum.absolute_photometry ? "absolute" : "relative"},
      {"symmetry", name_of(lum.symmetry)},
      {"c_planes", d.c_deg.size()},
      {"gamma_angles", d.gamma_deg.size()},
      {"gamma_range_deg", {d.gamma_deg.front(), d.gamma_deg.back()}},
      {"lamp_flux_lm", lum.lamp_flux_lm},
      {"header_flux_lm", header_flux_lm},
      {"flux_lm", lum.flux_lm},
      {"integrated_flux_lm", flux.total_lm()},
      {"downward_flux_lm", flux.downward_lm},
      {"upward_flux_lm", flux.upward_lm},
      {"dlor", dlor},
      {"ulor", ulor},
      {"max_intensity_cd", max_intensity_cd},
      {"max_intensity_cd_per_klm", max_intensity_cd * per_klm},
      {"max_intensity_direction_deg", {{"c", max_c_deg}, {"gamma", max_gamma_deg}}},
      {"power_w", lum.power_w},
      {"luminous_area_m",
       {{"along_c0_c180", area.along_c0_m},
        {"along_c90_c270", area.along_c90_m},
        {"circular", area.circular},
        {"heights_c0_c90_c180_c270", area.heights_m}}},
      {"principal_planes", planes},
      {"metadata", lum.metadata},
  };
  const nlohmann::json diagnostics_json = diagnostics.to_json();
  out["notes"] = diagnostics_json["notes"];
  out["warnings"] = diagnostics_json["warnings"];
  return out;
}

}  // namespace roadbrdf::lighting
