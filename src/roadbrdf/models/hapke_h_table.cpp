// Table of the exact H function: see hapke_h_table.h for the method.
#include "roadbrdf/models/hapke_h_table.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

namespace roadbrdf::hapke {
namespace {

constexpr int kBlockSize = kHTableNodesX * kHTableNodesG;
constexpr int kBlockCount = kHTableOctaves * kHTableGammaPanels;

struct BlockStore {
  std::array<std::atomic<const double*>, kBlockCount> blocks{};
  std::mutex mutex;  // guards building and `owned`
  std::vector<std::unique_ptr<double[]>> owned;
};

BlockStore& store() {
  static BlockStore s;
  return s;
}

// Tensor Chebyshev interpolant through the first-kind Chebyshev points (degree n - 1 in each
// variable): c_ab = (2/n)(2/m) sum_p sum_q f(t_p, s_q) cos(a theta_p) cos(b phi_q), halved for a = 0
// and for b = 0 (the discrete orthogonality of T_a at the Chebyshev points; Mason & Handscomb,
// "Chebyshev Polynomials", 2003, sec. 6.3).
std::unique_ptr<double[]> build_block(int octave, int panel) {
  const int nx = kHTableNodesX, ng = kHTableNodesG;
  std::vector<double> f(kBlockSize);
  for (int p = 0; p < nx; ++p) {
    const double t = std::cos(kPi * (p + 0.5) / nx);
    const double x = std::ldexp(std::exp2(0.5 * (t - 1.0)), -octave);  // t = 2 log2(x 2^k) + 1
    for (int q = 0; q < ng; ++q) {
      const double s = std::cos(kPi * (q + 0.5) / ng);
      const double gamma = (s + 2.0 * panel + 1.0) / (2.0 * kHTableGammaPanels);
      f[p * ng + q] = h_exact(x, 1.0 - gamma * gamma);
    }
  }
  auto c = std::make_unique<double[]>(kBlockSize);
  for (int a = 0; a < nx; ++a) {
    for (int b = 0; b < ng; ++b) {
      double sum = 0.0;
      for (int p = 0; p < nx; ++p) {
        const double ca = std::cos(kPi * a * (p + 0.5) / nx);
        for (int q = 0; q < ng; ++q) sum += f[p * ng + q] * ca * std::cos(kPi * b * (q + 0.5) / ng);
      }
      c[a * ng + b] = sum * (a == 0 ? 1.0 : 2.0) / nx * (b == 0 ? 1.0 : 2.0) / ng;
    }
  }
  return c;
}

}  // namespace

const double* h_table_block(int octave, int gamma_panel) {
  BlockStore& s = store();
  std::atomic<const double*>& slot = s.blocks[octave * kHTableGammaPanels + gamma_panel];
  const double* block = slot.load(std::memory_order_acquire);
  if (block != nullptr) return block;
  std::lock_guard<std::mutex> lock(s.mutex);
  block = slot.load(std::memory_order_relaxed);
  if (block != nullptr) return block;
  s.owned.push_back(build_block(octave, gamma_panel));
  block = s.owned.back().get();
  slot.store(block, std::memory_order_release);
  return block;
}

void h_table_series(double gamma, double* series) {
  const int panel = std::min(static_cast<int>(gamma * kHTableGammaPanels), kHTableGammaPanels - 1);
  const double s = 2.0 * kHTableGammaPanels * gamma - (2.0 * panel + 1.0);
  double tg[kHTableNodesG];
  tg[0] = 1.0;
  tg[1] = s;
  for (int b = 2; b < kHTableNodesG; ++b) tg[b] = 2.0 * s * tg[b - 1] - tg[b - 2];
  for (int octave = 0; octave < kHTableOctaves; ++octave) {
    const double* c = h_table_block(octave, panel);
    for (int a = 0; a < kHTableNodesX; ++a) {
      double r = 0.0;
      for (int b = 0; b < kHTableNodesG; ++b) r += c[a * kHTableNodesG + b] * tg[b];
      series[octave * kHTableNodesX + a] = r;
    }
  }
}

bool h_table_point(double x, HTablePoint& point) {
  if (!(x <= 1.0 && x >= std::ldexp(1.0, -kHTableOctaves))) return false;
  // As in h_table_evaluate: octave k (x in [2^-(k+1), 2^-k]) and t = 2 log2(x 2^k) + 1 in [-1, 1].
  int e = 0;
  const double m = std::frexp(x, &e);
  int octave = -e;
  double t = 2.0 * std::log2(m) + 1.0;
  if (octave < 0) {  // x = 1
    octave = 0;
    t = 1.0;
  }
  point.octave = octave;
  point.tx[0] = 1.0;
  point.tx[1] = t;
  for (int a = 2; a < kHTableNodesX; ++a) point.tx[a] = 2.0 * t * point.tx[a - 1] - point.tx[a - 2];
  return true;
}

double h_table_evaluate(double x, double gamma, double* dh_dgamma) {
  // Octave k (x in [2^-(k+1), 2^-k]) and t = 2 log2(x 2^k) + 1 in [-1, 1].
  int e = 0;
  const double m = std::frexp(x, &e);  // x = m 2^e, m in [1/2, 1)
  int octave = -e;
  double t = 2.0 * std::log2(m) + 1.0;
  if (octave < 0) {  // x = 1
    octave = 0;
    t = 1.0;
  }
  // Gamma panel j (gamma in [j/8, (j+1)/8]) and s = 16 gamma - 2j - 1 in [-1, 1].
  const int panel = std::min(static_cast<int>(gamma * kHTableGammaPanels), kHTableGammaPanels - 1);
  const double s = 2.0 * kHTableGammaPanels * gamma - (2.0 * panel + 1.0);
  const double* c = h_table_block(octave, panel);
  // T_a(t), T_b(s) by the three-term recurrence T_{n+1} = 2 z T_n - T_{n-1}.
  double tx[kHTableNodesX], tg[kHTableNodesG];
  tx[0] = 1.0;
  tx[1] = t;
  for (int a = 2; a < kHTableNodesX; ++a) tx[a] = 2.0 * t * tx[a - 1] - tx[a - 2];
  tg[0] = 1.0;
  tg[1] = s;
  for (int b = 2; b < kHTableNodesG; ++b) tg[b] = 2.0 * s * tg[b - 1] - tg[b - 2];
  // Contract over t first: q_b = sum_a c_ab T_a(t) (independent accumulators, one per b), then
  // H = sum_b q_b T_b(s) and dH/ds = sum_b q_b T_b'(s).
  double q[kHTableNodesG];
  for (int b = 0; b < kHTableNodesG; ++b) q[b] = c[b] * tx[0];
  for (int a = 1; a < kHTableNodesX; ++a) {
    const double* row = c + static_cast<std::ptrdiff_t>(a) * kHTableNodesG;
    for (int b = 0; b < kHTableNodesG; ++b) q[b] += row[b] * tx[a];
  }
  double value = 0.0;
  for (int b = 0; b < kHTableNodesG; ++b) value += q[b] * tg[b];
  if (dh_dgamma != nullptr) {
    // T_b'(s) by differentiating the recurrence: T'_{n+1} = 2 T_n + 2 s T'_n - T'_{n-1}.
    double dg[kHTableNodesG];
    dg[0] = 0.0;
    dg[1] = 1.0;
    for (int b = 2; b < kHTableNodesG; ++b) dg[b] = 2.0 * tg[b - 1] + 2.0 * s * dg[b - 1] - dg[b - 2];
    double slope = 0.0;
    for (int b = 1; b < kHTableNodesG; ++b) slope += q[b] * dg[b];
    *dh_dgamma = slope * (2.0 * kHTableGammaPanels);  // ds/dgamma
  }
  return value;
}

double h_table_evaluate_slopes(double x, double gamma, double* dh_dx, double* dh_dgamma) {
  const double value = h_table_evaluate(x, gamma, dh_dgamma);
  // dH/dt = sum_a sum_b c_ab T_a'(t) T_b(s), T_a' by differentiating the recurrence (as for s).
  int e = 0;
  const double m = std::frexp(x, &e);
  int octave = -e;
  double t = 2.0 * std::log2(m) + 1.0;
  if (octave < 0) {  // x = 1
    octave = 0;
    t = 1.0;
  }
  const int panel = std::min(static_cast<int>(gamma * kHTableGammaPanels), kHTableGammaPanels - 1);
  const double s = 2.0 * kHTableGammaPanels * gamma - (2.0 * panel + 1.0);
  const double* c = h_table_block(octave, panel);
  double tx[kHTableNodesX], dx[kHTableNodesX], tg[kHTableNodesG];
  tx[0] = 1.0;
  tx[1] = t;
  dx[0] = 0.0;
  dx[1] = 1.0;
  for (int a = 2; a < kHTableNodesX; ++a) {
    tx[a] = 2.0 * t * tx[a - 1] - tx[a - 2];
    dx[a] = 2.0 * tx[a - 1] + 2.0 * t * dx[a - 1] - dx[a - 2];
  }
  tg[0] = 1.0;
  tg[1] = s;
  for (int b = 2; b < kHTableNodesG; ++b) tg[b] = 2.0 * s * tg[b - 1] - tg[b - 2];
  double slope = 0.0;
  for (int a = 1; a < kHTableNodesX; ++a) {
    double row = 0.0;
    for (int b = 0; b < kHTableNodesG; ++b) row += c[a * kHTableNodesG + b] * tg[b];
    slope += row * dx[a];
  }
  if (dh_dx != nullptr) *dh_dx = slope * 2.0 / (x * std::log(2.0));
  return value;
}

}  // namespace roadbrdf::hapke
