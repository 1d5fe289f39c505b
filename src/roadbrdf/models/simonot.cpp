// The simonot model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/simonot.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory simonot_factory() { return factory_of<Simonot>(); }

}  // namespace roadbrdf
