// The oren-nayar model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/oren_nayar.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory oren_nayar_factory() { return factory_of<OrenNayar>(); }

}  // namespace roadbrdf
