// Material map of a generated virtual sample (generate.h): the mastic is the flat fill at the matrix
// level, so no facet that rises above that level can be mastic. A cell whose centre lies just outside
// a grain while one of its nodes is on the grain is the grain's steep flank; labelled mastic, it gave
// the mastic a large tilted area (26 % of the mastic cells of the virtual F1 at 0.2 mm cells), lit at
// oblique geometries where the real mastic, lying in the pits, is shadowed (docs/virtual-study.md).
#include <gtest/gtest.h>
#include "support/materials.h"

#include <algorithm>

#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/height_field.h"

namespace rs = roadbrdf::surface;

namespace {

using roadbrdf::test::lambert;

}  // namespace

TEST(SurfaceVirtualMaterialMap, EveryMasticCellIsFlatAtTheMatrixLevelAndGrainsKeepTheirCentres) {
  rs::SampleRecipe recipe;
  recipe.name = "two classes";
  recipe.matrix = lambert(0.05, "mastic");
  rs::GrainClass fine, coarse;
  fine.material = lambert(0.3, "2/6");
  fine.d_min_mm = 2;
  fine.d_max_mm = 6;
  fine.volume_fraction = 0.15;
  coarse.material = lambert(0.4, "6/10");
  coarse.d_min_mm = 6;
  coarse.d_max_mm = 10;
  coarse.volume_fraction = 0.3;
  recipe.classes = {fine, coarse};
  rs::GeneratorSettings s;
  s.size_mm = 24.0;
  s.cell_size_mm = 0.2;
  s.seed = 3;
  s.matrix_level = 0.7;
  const rs::GeneratedSample g = rs::generate_sample(recipe, s);
  const rs::HeightField& f = g.field;
  const double level = g.matrix_level_mm;
  long mastic = 0, flank = 0;
  for (int j = 0; j < f.ny; ++j) {
    for (int i = 0; i < f.nx; ++i) {
      const double top = std::max({f.height(i, j), f.height(i + 1, j), f.height(i, j + 1), f.height(i + 1, j + 1)});
      if (f.material_at(i, j) == 0) {
        ++mastic;
        EXPECT_LE(top, level + 1e-12) << "mastic cell (" << i << ", " << j << ") rises to " << top << " mm";
      } else if (top > level) {
        ++flank;
      }
    }
  }
  // Both kinds exist: a real mastic floor, and grains poking out of it.
  EXPECT_GT(mastic, f.nx * f.ny / 20);
  EXPECT_GT(flank, f.nx * f.ny / 20);
}
