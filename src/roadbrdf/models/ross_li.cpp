// The ross-li model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/ross_li.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory ross_li_factory() { return factory_of<RossLi>(); }

}  // namespace roadbrdf
