// The resolver of a command's BRDF source lives in the modelfile layer (below io); this header keeps
// its former place for the modules that include it from here.
#pragma once

#include "roadbrdf/modelfile/model_source.h"
