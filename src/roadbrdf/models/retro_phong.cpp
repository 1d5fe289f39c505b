// The retro-phong model's factory: its adapter and the fitter's Jet instantiations compile here (model_factory.h).
#include "roadbrdf/models/retro_phong.h"
#include "roadbrdf/models/model_factory.h"

namespace roadbrdf {

ModelFactory retro_phong_factory() { return factory_of<RetroPhong>(); }

}  // namespace roadbrdf
