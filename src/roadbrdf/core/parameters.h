// Declarations of model parameters and options: the single source of truth used by the
// command line, the fitter, the Python module and the generated documentation.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace roadbrdf {

// One continuous, fittable parameter of a model.
struct ParameterInfo {
  std::string name;         // as files and scripts spell it, e.g. "albedo"
  std::string unit;         // "1" for dimensionless, "rad", "sr^-1"...
  std::string description;  // one line, in the field's words
  double default_value = 0.0;
  double lower = 0.0;  // inclusive bounds
  double upper = 1.0;
  bool spectral = true;  // may vary with wavelength
  // True for amplitudes the BRDF is linear in (albedo, k_d, k_s...): the fitter may solve them directly.
  bool linear = false;
};

// One discrete choice of a model (profile, distribution, H-function...). Not fitted.
struct OptionInfo {
  std::string name;
  std::string description;
  std::vector<std::string> values;  // allowed values; empty means "a number" (e.g. a lobe count)
  std::string default_value;
};

// Options as given by the user: name -> value.
using OptionSet = std::map<std::string, std::string>;

// Another name under which the literature knows a model with some of its options fixed, e.g.
// "cook-torrance" = torrance-sparrow with Cook & Torrance's 1982 choices. Declared by the model
// (static aliases()); the registry resolves it. The fixed options cannot be changed under the alias
// (that would no longer be the published model): the model's own name gives every choice.
struct ModelAlias {
  std::string name;         // CLI spelling, e.g. "cook-torrance"
  std::string model;        // the model it selects, e.g. "torrance-sparrow"
  std::string description;  // one line: what the alias stands for
  std::string citation;     // where the fixed choices come from
  OptionSet options;        // the fixed options
};

struct ModelDescription {
  std::string name;      // CLI spelling, e.g. "oren-nayar"
  std::string summary;   // one line
  std::string citation;  // paper and equation the implementation follows
  std::vector<ParameterInfo> parameters;
  std::vector<OptionInfo> options;
  OptionSet option_values;  // the resolved options (defaults filled in)
  bool reciprocal = true;
  bool energy_conserving = true;
  bool non_negative = true;  // f >= 0 for every geometry and every parameter set inside the bounds
  bool has_delta = false;    // has an ideal specular part, handled separately from the smooth BRDF
  // Whether the BRDF may have a lobe about the mirror direction narrow enough for the first nodes of
  // the black-sky (mu, dphi) rule to miss at grazing incidence (a microfacet or Phong specular lobe
  // of small roughness). black_sky() cross-checks that rule with the mirror-polar rule from a sun
  // zenith of 70 deg (albedo/hemisphere.h) unless a model declares false: a diffuse model, or one whose
  // narrowest feature at any parameter within its bounds is broad enough; tests/albedo/mirror_lobe_test.cpp
  // checks the claim at every corner of the parameter box and at 70-89.9 deg. Composites and
  // mixtures: true if any component's is.
  bool mirror_lobe = true;
  // The value at exactly grazing directions (theta_i or theta_r = 90 deg, Geometry::grazing_i/_r): the
  // limit of the BRDF as the direction approaches the horizon with the other one held fixed, wherever
  // that limit is finite. Where it is not (the BRDF diverges like 1/cos or tan of a zenith angle), the
  // value there is 0, and `grazing_zero` says where, in words ("" when the limit is finite everywhere).
  // model_properties_test checks both claims on a grid of 89.999, 90 deg and their mixes.
  std::string grazing_zero;
  // Registered models this one equals at some parameter values inside its bounds (nested models):
  // name -> the values ("sigma = 0"). A fit worse than a fit of a model it nests is flagged
  // (fitting/fit_request.h). Composites nest their components without listing them.
  std::vector<std::pair<std::string, std::string>> reduces_to;
  // Azimuthal isotropy: the BRDF depends on the azimuths only through phi_r - phi_i (turning the
  // sample about its normal changes nothing), for every parameter set. A model anisotropic in general
  // may be isotropic where pairs of its parameters are equal (Ashikhmin-Shirley n_u = n_v, anisotropic
  // Lafortune C_x = C_y of every lobe): those pairs are listed in `isotropic_when_equal`. Composites
  // and mixtures combine both from their components (combine_isotropy).
  bool isotropic = true;
  std::vector<std::pair<std::string, std::string>> isotropic_when_equal;
  // Where the physics allows a wider range than a parameter's declared [lower, upper] (the default
  // fitting range): name -> [lower, upper], declared once in the model's describe(). `fit --bounds`
  // may ask for any range inside it; values given with -p or read from files may lie anywhere in it.
  std::map<std::string, std::pair<double, double>> physical_bounds;

  // Index of a parameter by name, or nullopt.
  std::optional<std::size_t> parameter_index(const std::string& parameter_name) const;
  std::vector<double> default_parameters() const;
  // The physical range of parameter k: physical_bounds, or its declared [lower, upper].
  std::pair<double, double> physical_range(std::size_t k) const;
};

// Resolve user options against declared options: fills defaults, rejects unknown names and values.
// Throws InputError with a message naming the model and the option.
OptionSet resolve_options(const std::string& model, const std::vector<OptionInfo>& declared, const OptionSet& given);

// Read a numeric option (for options declared with empty `values`). Throws InputError.
int integer_option(const std::string& model, const OptionSet& options, const std::string& name, int lo, int hi);

// Whether the BRDF is azimuthally isotropic at this parameter set (parameter_count() values), from
// `isotropic` and `isotropic_when_equal` alone.
bool is_isotropic_at(const ModelDescription& description, const double* params);

// The isotropy of a sum or mixture of components into `combined`: isotropic if every component is;
// otherwise isotropic where every anisotropic component is, i.e. where all their pairs (prefixed
// "PREFIX.") are equal; never if one component is never isotropic.
void combine_isotropy(ModelDescription& combined, const ModelDescription& component, const std::string& prefix);

// Check a parameter vector against the declared bounds; throws InputError naming the first
// offending parameter.
void check_parameters(const ModelDescription& description, const std::vector<double>& values);

}  // namespace roadbrdf
