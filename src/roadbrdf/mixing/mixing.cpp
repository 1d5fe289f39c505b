// The method table and mix(): the dispatcher over the methods of method_table.h.
#include "roadbrdf/mixing/mixing.h"

#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/method_support.h"
#include "roadbrdf/mixing/method_table.h"

namespace roadbrdf::mixing {

const MethodEntry& method_entry(Method method) {
  static const MethodEntry table[] = {
      {Method::kAreal, false, true, &mix_areal},        // weights from the formulation
      {Method::kFitted, true, true, &mix_fitted},       // weights fitted to the measured mixture
      {Method::kMastic, false, true, &mix_mastic},      // measured mastic and coarse aggregates
      {Method::kHapke, false, false, &mix_hapke},       // intimate: single-scattering albedos mix
      {Method::kShadowed, true, false, &mix_shadowed},  // shadowing fitted to the measured mixture
  };
  for (const MethodEntry& e : table) {
    if (e.method == method) return e;
  }
  throw InputError("internal: mixing method missing from the method table");
}

bool method_needs_data(Method method) { return method_entry(method).needs_data; }

bool method_is_linear(Method method) { return method_entry(method).linear; }

MixResult mix(const MixInputs& inputs, Method method, const MixSettings& settings, const SpectralDataset* data,
              const std::vector<std::size_t>* training) {
  const MethodEntry& entry = method_entry(method);
  MixResult r;
  r.method = method;
  r.description = description_of(method);
  if (entry.needs_data && !data) {
    throw InputError("mixing method '" + name_of(method) + "' is fitted to a measured mixture: give `data`");
  }
  std::vector<std::size_t> members = detail::component_members(inputs);
  entry.run(MethodCall{inputs, settings, data, training}, r, members);
  for (std::size_t e : members) {
    r.end_members.push_back(inputs.end_members[e].name);
    r.end_member_fits.push_back(inputs.end_members[e].fit_path);
  }
  return r;
}

}  // namespace roadbrdf::mixing
