// The burley model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/burley.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory burley_factory() { return factory_of<Burley>(); }

}  // namespace roadbrdf
