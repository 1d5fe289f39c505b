// The hapke model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/hapke.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory hapke_factory() { return factory_of<Hapke>(); }

}  // namespace roadbrdf
