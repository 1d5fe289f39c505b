#include "roadbrdf/lighting/luminaire_file.h"

#include "roadbrdf/core/error.h"

namespace roadbrdf::lighting {

Luminaire read_luminaire(const std::string& path, Diagnostics& /*diagnostics*/) {
  throw FileError(path, 0, 0, "luminaire files cannot be read yet");
}

}  // namespace roadbrdf::lighting
