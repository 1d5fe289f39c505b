// Method "hapke": intimate mixing (Hapke 1981 eq. 17) with cross-section weights M/(rho D) from the
// formulation and single-scattering albedos inverted from each end-member's white-sky albedo
// (mixing.h; the mixture's form is MixtureModel kind "hapke", mixture_model.h).
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/calibration.h"
#include "roadbrdf/mixing/method_support.h"
#include "roadbrdf/mixing/method_table.h"
#include "roadbrdf/models/hapke_imsa.h"

namespace roadbrdf::mixing {

using namespace detail;

void mix_hapke(const MethodCall& call, MixResult& r, std::vector<std::size_t>& members) {
  const MixInputs& inputs = call.inputs;
  const Formulation& f = inputs.formulation;
  std::vector<double> c(members.size(), 0.0);
  for (std::size_t i = 0; i < f.components.size(); ++i) {
    const Component& comp = f.components[i];
    c[member_position(members, member_of_component(inputs, i))] +=
        comp.mass_percent / (comp.density * effective_diameter_mm(f, comp));
  }
  // Calibrated effective cross-sections (calibration.h): c_e = k_e sum M/(rho D).
  double total = 0.0;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const std::string& name = inputs.end_members[members[k]].name;
    const double factor = cross_section_factor(call.settings, name);
    c[k] *= factor;
    total += c[k];
    if (!call.settings.cross_section_factors.empty()) r.settings["cross_section_factor." + name] = factor;
  }
  for (double& x : c) x /= total;
  const std::vector<double> grid = output_grid(inputs, members, call.settings, call.data);
  // Single-scattering albedos: invert the white-sky albedo of each end-member at each wavelength.
  const std::size_t rows = grid.empty() ? 1 : grid.size();
  std::vector<std::vector<double>> w(members.size(), std::vector<double>(rows));
  for (std::size_t k = 0; k < members.size(); ++k) {
    const EndMember& em = inputs.end_members[members[k]];
    const std::vector<double> albedo = inputs.albedo_cache->white_sky(*em.model, grid);
    for (std::size_t q = 0; q < rows; ++q) {
      try {
        w[k][q] = invert_imsa_white_sky_albedo(albedo[q]);
      } catch (const InputError& e) {
        std::ostringstream msg;
        msg << "hapke mixing: end-member '" << em.name << "'";
        if (!grid.empty()) msg << " at " << grid[q] << " nm";
        msg << ": " << e.what();
        throw InputError(msg.str());
      }
    }
  }
  r.mixture = make_mixture(MixtureKind::kHapke, inputs, members);
  const std::size_t K = members.size();
  r.model = std::make_shared<const SpectralModel>(
      build_table(r.mixture, inputs, members, grid, [&](std::size_t q, double* row) {
        for (std::size_t k = 0; k < K; ++k) {
          row[k] = c[k];
          row[K + k] = w[k][q];
        }
      }));
  r.weights = c;
  r.settings["binder_film_thickness_mm"] = f.binder_film_thickness_mm;
}

}  // namespace roadbrdf::mixing
