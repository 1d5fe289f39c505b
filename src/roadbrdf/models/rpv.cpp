// The rpv model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/rpv.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory rpv_factory() { return factory_of<RahmanPintyVerstraete>(); }

}  // namespace roadbrdf
