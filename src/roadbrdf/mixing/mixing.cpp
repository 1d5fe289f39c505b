// The method table and mix(): the dispatcher over the methods of method_table.h.
#include "roadbrdf/mixing/mixing.h"

#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/method_support.h"
#include "roadbrdf/mixing/method_table.h"

namespace roadbrdf::mixing {

const std::vector<MethodEntry>& method_table() {
  static const std::vector<MethodEntry> table{
      {Method::kAreal, "areal",
       "areal mixing, area fractions from the formulation (projected area per mass 3/(2 rho D), binder coverage)",
       false, true, &mix_areal},
      {Method::kFitted, "fitted", "linear mixing, weights fitted to the measured mixture by non-negative least squares",
       true, true, &mix_fitted},
      {Method::kMastic, "mastic", "measured mastic + coarse aggregate classes, areal mixing", false, true, &mix_mastic},
      {Method::kHapke, "hapke",
       "intimate Hapke mixing: w from white-sky albedo (IMSA H1), weights M/(rho D), phase terms by c w", false, false,
       &mix_hapke},
      {Method::kShadowed, "shadowed",
       "nonlinear fitted mixing: coarse aggregates shadow the matrix, exp(-s (tan theta_i + tan theta_r))", true, false,
       &mix_shadowed},
  };
  return table;
}

const MethodEntry& method_entry(Method method) {
  for (const MethodEntry& e : method_table()) {
    if (e.method == method) return e;
  }
  throw InputError("internal: mixing method missing from the method table");
}

std::string to_string(Method method) {
  for (const MethodEntry& e : method_table()) {
    if (e.method == method) return e.name;
  }
  return "?";
}

Method method_from_string(const std::string& text) {
  std::string names;
  for (const MethodEntry& e : method_table()) {
    if (text == e.name) return e.method;
    names += (names.empty() ? "" : ", ") + std::string(e.name);
  }
  throw InputError("unknown mixing method '" + text + "' (" + names + ")");
}

std::vector<Method> all_methods() {
  std::vector<Method> methods;
  for (const MethodEntry& e : method_table()) methods.push_back(e.method);
  return methods;
}

bool method_needs_data(Method method) { return method_entry(method).needs_data; }

bool method_is_linear(Method method) { return method_entry(method).linear; }

MixResult mix(const MixInputs& inputs, Method method, const MixSettings& settings, const SpectralDataset* data,
              const std::vector<std::size_t>* training) {
  const MethodEntry& entry = method_entry(method);
  MixResult r;
  r.method = method;
  r.description = entry.description;
  if (entry.needs_data && !data) {
    throw InputError("mixing method '" + std::string(entry.name) + "' is fitted to a measured mixture: give `data`");
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
