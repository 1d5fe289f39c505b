// Non-negative least squares for the fitted mixing weights (method_fitted.cpp, method_shadowed.cpp).
#pragma once

#include <cstddef>
#include <vector>

namespace roadbrdf::mixing {

// Non-negative least squares min |A x - b|^2, x >= 0, from the normal equations G = A^T A
// (K x K row-major) and h = A^T b (Lawson & Hanson 1974, ch. 23 active-set algorithm).
std::vector<double> nnls_normal(const std::vector<double>& G, const std::vector<double>& h, std::size_t K);

}  // namespace roadbrdf::mixing
