// Reading luminaire photometry files: EULUMDAT (.ldt) and IES LM-63 (.ies), chosen by the file's
// content (an IES file starts with "IESNA" or "TILT="; the extension only breaks ties).
#pragma once

#include <string>
#include <string_view>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/lighting/luminaire.h"

namespace roadbrdf::lighting {

// The luminaire of `path`, its distribution expanded to every C-plane and in candela for the
// luminaire as rated. What a reader has to say (a flux that disagrees with the intensities, other
// lamp sets kept in the metadata) goes to `diagnostics`. Throws FileError naming file, line and
// column for a malformed file.
Luminaire read_luminaire(const std::string& path, Diagnostics& diagnostics);

// The same from a file's content; `name` is the file named in errors and in Luminaire::file.
Luminaire parse_luminaire(std::string_view content, const std::string& name, Diagnostics& diagnostics);

}  // namespace roadbrdf::lighting
