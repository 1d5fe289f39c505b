// The torrance-sparrow model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/torrance_sparrow.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory torrance_sparrow_factory() { return factory_of<TorranceSparrow>(); }

}  // namespace roadbrdf
