#include "roadbrdf/photometry/marking_contrast.h"

#include <fmt/core.h>

#include <cmath>

namespace roadbrdf::photometry {

nlohmann::json MarkingContrast::to_json() const {
  nlohmann::json j;
  j["pavement"] = pavement;
  j["definition"] = "C = (L_marking - L_road) / L_road";
  j["headlamp"] = nullptr;
  if (headlamp) {
    const HeadlampContrast& h = *headlamp;
    nlohmann::json a = {{"distance_m", h.distance_m},
                        {"headlamp_height_m", h.headlamp_height_m},
                        {"eye_height_m", h.eye_height_m},
                        {"RL_marking", h.rl_marking},
                        {"RL_road", h.rl_road},
                        {"contrast", h.contrast},
                        {"light", nullptr}};
    if (h.light) {
      const HeadlampLight& l = *h.light;
      a["light"] = {{"file", l.file},
                    {"C_deg", l.c_deg},
                    {"gamma_deg", l.gamma_deg},
                    {"intensity_cd", l.intensity_cd},
                    {"distance_m", l.distance_m},
                    {"illuminance_perpendicular_lx", l.illuminance_perpendicular_lx},
                    {"illuminance_lx", l.illuminance_lx},
                    {"L_marking_cd_m2", l.L_marking},
                    {"L_road_cd_m2", l.L_road}};
    }
    j["headlamp"] = std::move(a);
  }
  j["installation"] = nullptr;
  if (installation) {
    const InstallationContrast& b = *installation;
    nlohmann::json observers = nlohmann::json::array();
    const auto values = [](const std::vector<double>& v) {
      nlohmann::json a = nlohmann::json::array();
      for (double x : v) a.push_back(std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr));
      return a;
    };
    for (const ObserverContrast& o : b.observers) {
      observers.push_back({{"lane", o.lane + 1},
                           {"L_av_marking_cd_m2", o.L_av_marking},
                           {"L_av_road_cd_m2", o.L_av_road},
                           {"L_min_marking_cd_m2", o.L_min_marking},
                           {"L_min_road_cd_m2", o.L_min_road},
                           {"L_marking_cd_m2", values(o.L_marking)},
                           {"L_road_cd_m2", values(o.L_road)},
                           {"contrast", values(o.contrast)},
                           {"contrast_of_averages", o.contrast_of_averages},
                           {"contrast_min", o.contrast_min},
                           {"contrast_max", o.contrast_max},
                           {"contrast_mean", o.contrast_mean},
                           {"contrast_of_averages_true_alpha", o.contrast_of_averages_true_alpha
                                                                   ? nlohmann::json(*o.contrast_of_averages_true_alpha)
                                                                   : nlohmann::json(nullptr)}});
    }
    j["installation"] = {{"file", b.installation},
                         {"grid_points", b.grid_points},
                         {"x_m", b.x_m},
                         {"y_m", b.y_m},
                         {"contrast_of_averages", b.contrast_of_averages},
                         {"contrast_min", b.contrast_min},
                         {"contrast_max", b.contrast_max},
                         {"observers", std::move(observers)}};
  }
  j["units"] = {{"RL", "mcd m^-2 lx^-1"}, {"L", "cd/m^2"}, {"illuminance", "lx"}, {"contrast", "1"}};
  return j;
}

std::string MarkingContrast::summary_text() const {
  std::string text = "contrast against " + pavement + ", C = (L_marking - L_road) / L_road\n";
  if (headlamp) {
    const HeadlampContrast& h = *headlamp;
    text += fmt::format(
        "  headlamp at {:g} m (lamp {:.2f} m, eye {:.2f} m): R_L marking {:.2f}, road {:.2f} "
        "mcd m^-2 lx^-1, C = {:.4g}\n",
        h.distance_m, h.headlamp_height_m, h.eye_height_m, h.rl_marking, h.rl_road, h.contrast);
    if (h.light) {
      const HeadlampLight& l = *h.light;
      text += fmt::format(
          "    I(C {:.0f}, gamma {:.2f}) = {:.4g} cd, E = {:.4g} lx on the road ({:.4g} lx facing the "
          "lamp), L marking {:.4g}, road {:.4g} cd/m^2\n",
          l.c_deg, l.gamma_deg, l.intensity_cd, l.illuminance_lx, l.illuminance_perpendicular_lx, l.L_marking,
          l.L_road);
    }
  }
  if (installation) {
    const InstallationContrast& b = *installation;
    text += fmt::format("  installation ({} grid points): C of the averages {:.4g}, grid points {:.4g} to {:.4g}\n",
                        b.grid_points, b.contrast_of_averages, b.contrast_min, b.contrast_max);
    for (const ObserverContrast& o : b.observers) {
      text += fmt::format(
          "    observer lane {}: L_av marking {:.4g}, road {:.4g} cd/m^2, C {:.4g} (points {:.4g} "
          "to {:.4g}, mean {:.4g})",
          o.lane + 1, o.L_av_marking, o.L_av_road, o.contrast_of_averages, o.contrast_min, o.contrast_max,
          o.contrast_mean);
      if (o.contrast_of_averages_true_alpha) {
        text += fmt::format("; true alpha {:.4g}", *o.contrast_of_averages_true_alpha);
      }
      text += '\n';
    }
  }
  return text;
}

}  // namespace roadbrdf::photometry
