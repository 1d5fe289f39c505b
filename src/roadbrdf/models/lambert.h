// Lambertian (ideal diffuse) reflector: f = rho / pi.
// Report eq. 2.12; Lambert, Photometria (1760).
#pragma once

#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

struct Lambert {
  static constexpr const char* kName = "lambert";
  static constexpr int kMaxParameters = 1;
  enum Parameter { kAlbedo = 0 };

  static std::vector<OptionInfo> options() { return {}; }
  static ModelDescription describe(const OptionSet&) {
    ModelDescription d;
    d.summary = "Lambertian (ideal diffuse) reflector";
    d.citation = "Report eq. 2.12";
    d.parameters = {
        {"albedo", "1", "diffuse (hemispherical) albedo rho", 0.5, 0.0, 1.0, true, true},
    };
    d.mirror_lobe = false;
    return d;
  }
  explicit Lambert(const OptionSet&) {}

  template <typename T>
  T operator()(const T* p, const Geometry&) const {
    return p[kAlbedo] * kInvPi;
  }
};

}  // namespace roadbrdf
