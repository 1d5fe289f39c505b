// The ashikhmin-shirley model's factory: its adapter and the fitter's Jet instantiations compile here
// (model_factory.h).
#include "roadbrdf/models/ashikhmin_shirley.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory ashikhmin_shirley_factory() { return factory_of<AshikhminShirley>(); }

}  // namespace roadbrdf
