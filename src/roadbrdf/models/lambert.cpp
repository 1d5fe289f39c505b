// The lambert model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/lambert.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory lambert_factory() { return factory_of<Lambert>(); }

}  // namespace roadbrdf
