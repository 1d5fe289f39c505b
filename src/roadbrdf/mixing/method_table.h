// The mixing methods behind mix() (mixing.h): one table entry and one source file per method
// (method_<name>.cpp). A method chooses its end-members, builds the MixtureModel and its
// per-wavelength parameter table and fills the rest of the MixResult; mix() checks that the methods
// fitted to a measured mixture get one and adds the end-members' names and fit paths.
// Helpers shared by several methods (weights from the formulation, the output wavelength grid,
// parameter tables, the linear least-squares system) are in method_support.h.
#pragma once

#include <cstddef>
#include <vector>

#include "roadbrdf/mixing/mixing.h"

namespace roadbrdf::mixing {

struct MethodCall {
  const MixInputs& inputs;
  const MixSettings& settings;
  const SpectralDataset* data;               // measured mixture, or null (methods that need none)
  const std::vector<std::size_t>* training;  // geometry indices of `data` to fit on; null: all
};

// Fills `result` and sets `members` to the end-members of the mixture (indices into
// inputs.end_members, in the mixture's order). `members` starts as the component end-members
// (every fit file used by a component, in order; not the separate mastic fit).
using MethodFunction = void (*)(const MethodCall& call, MixResult& result, std::vector<std::size_t>& members);

// What mix() needs to know of a method besides its name and description (kMethodNames, mixing.h).
struct MethodEntry {
  Method method;
  bool needs_data;  // fitted to a measured mixture of the formulation itself
  // The mixture is linear in the end-members' BRDFs, f = sum_k a_k f_k with a_k independent of the
  // geometry (MixtureKind::kLinear), so its albedos are the same combination of the end-members'
  // (end_member_cache.h). Declared here only; mixture_albedo checks the mixture's kind agrees.
  bool linear;
  MethodFunction run;
};

const MethodEntry& method_entry(Method method);

void mix_areal(const MethodCall& call, MixResult& result, std::vector<std::size_t>& members);
void mix_fitted(const MethodCall& call, MixResult& result, std::vector<std::size_t>& members);
void mix_mastic(const MethodCall& call, MixResult& result, std::vector<std::size_t>& members);
void mix_hapke(const MethodCall& call, MixResult& result, std::vector<std::size_t>& members);
void mix_shadowed(const MethodCall& call, MixResult& result, std::vector<std::size_t>& members);

}  // namespace roadbrdf::mixing
