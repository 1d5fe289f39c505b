// The lafortune model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/lafortune.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory lafortune_factory() { return factory_of<Lafortune>(); }

}  // namespace roadbrdf
