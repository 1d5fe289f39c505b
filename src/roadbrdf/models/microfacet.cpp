#include "roadbrdf/models/microfacet.h"

#include <map>
#include <memory>
#include <mutex>

namespace roadbrdf {
namespace microfacet {

const QuadratureRule& gauss_legendre_01(int n) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<QuadratureRule>> cache;
  // Fast path for the rule used in inner loops.
  static const QuadratureRule rule64 = gauss_legendre(64, 0.0, 1.0);
  if (n == 64) return rule64;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[n];
  if (!slot) slot = std::make_unique<QuadratureRule>(gauss_legendre(n, 0.0, 1.0));
  return *slot;
}

}  // namespace microfacet
}  // namespace roadbrdf
