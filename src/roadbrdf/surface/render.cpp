#include "roadbrdf/surface/render.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <sstream>
#include <thread>
#include <utility>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/surface/brdf_sampler.h"

namespace roadbrdf::surface {

// ---- materials --------------------------------------------------------------------------------

std::vector<RenderMaterial> load_materials(const HeightField& field, const std::vector<double>& wavelengths) {
  if (wavelengths.empty()) throw InputError("render: no wavelengths");
  std::vector<RenderMaterial> out;
  for (const MaterialSpec& spec : field.materials) {
    RenderMaterial m;
    m.name = spec.name;
    if (!spec.model.empty()) {
      std::shared_ptr<const Model> model = make_model(spec.model, spec.options);
      const std::vector<double> p = parameters_from_assignments(model->description(), spec.parameters);
      m.model = model;
      for (std::size_t w = 0; w < wavelengths.size(); ++w) m.parameters.insert(m.parameters.end(), p.begin(), p.end());
    } else {
      const SpectralModel sm = read_fit_file(spec.fit_path, spec.fit_model);
      m.model = sm.model_ptr();
      for (double wl : wavelengths) {
        std::vector<double> p;
        if (sm.is_spectral()) {
          try {
            p = sm.parameters_at(wl);
          } catch (const InputError& e) {
            throw InputError("material '" + spec.name + "' (" + spec.fit_path + "): " + e.what());
          }
        } else {
          p = sm.parameter_table();
        }
        m.parameters.insert(m.parameters.end(), p.begin(), p.end());
      }
    }
    m.has_delta = m.model->description().has_delta;
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<double> default_wavelengths(const HeightField& field) {
  double lo = -1e300, hi = 1e300;
  std::vector<double> first;
  for (const MaterialSpec& spec : field.materials) {
    if (!spec.model.empty()) continue;
    const SpectralModel sm = read_fit_file(spec.fit_path, spec.fit_model);
    if (!sm.is_spectral()) continue;
    lo = std::max(lo, sm.wavelengths().front());
    hi = std::min(hi, sm.wavelengths().back());
    if (first.empty()) first = sm.wavelengths();
  }
  if (first.empty()) return {550.0};
  std::vector<double> out;
  for (double w : first) {
    if (w >= lo && w <= hi) out.push_back(w);
  }
  if (out.empty()) throw InputError("the spectral materials of the surface have no common wavelength range");
  return out;
}

// ---- random numbers ---------------------------------------------------------------------------

namespace {

inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// xoshiro256** (Blackman & Vigna 2018), seeded by splitmix64.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    for (auto& s : s_) s = splitmix64(seed);
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t stream, std::uint64_t block) {
  std::uint64_t s = seed;
  std::uint64_t a = splitmix64(s);
  s = a ^ (stream * 0xd1b54a32d192ed03ull + 0x8cb92ba72f3d8dd7ull);
  a = splitmix64(s);
  s = a ^ (block * 0xaef17502108ef2d9ull + 0x3c6ef372fe94f82bull);
  return splitmix64(s);
}

// Orthonormal basis (t, b, n) around a unit vector n (Duff et al., JCGT 6(1) 2017, the
// branchless construction; written from the paper's formulas).
inline void make_basis(const Vec3& n, Vec3& t, Vec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

inline Vec3 to_local(const Vec3& w, const Vec3& t, const Vec3& b, const Vec3& n) {
  return {dot(w, t), dot(w, b), dot(w, n)};
}

// Geometry from two local unit vectors (z = facet normal); both must be in the upper hemisphere.
inline Geometry local_geometry(Vec3 wi, Vec3 wr) {
  wi.z = std::clamp(wi.z, 0.0, 1.0);
  wr.z = std::clamp(wr.z, 0.0, 1.0);
  Geometry g;
  g.wi = wi;
  g.wr = wr;
  g.theta_i = std::acos(wi.z);
  g.theta_r = std::acos(wr.z);
  g.phi_i = std::atan2(wi.y, wi.x);
  g.phi_r = std::atan2(wr.y, wr.x);
  const double si = std::sqrt(wi.x * wi.x + wi.y * wi.y), sr = std::sqrt(wr.x * wr.x + wr.y * wr.y);
  g.cos_delta_phi = (si > 1e-12 && sr > 1e-12) ? std::clamp((wi.x * wr.x + wi.y * wr.y) / (si * sr), -1.0, 1.0) : 0.0;
  return g;
}

}  // namespace

// Cosine-weighted direction about +z (pdf cos(theta)/pi) from two uniform numbers.
inline Vec3 cosine_direction(double u1, double u2) {
  const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
}

// Russian roulette on the throughput beta (m wavelengths): survival q = min(0.95, max |beta|),
// beta /= q. Returns false when the path ends.
inline bool russian_roulette(double* beta, std::size_t m, Rng& rng) {
  double q = 0.0;
  for (std::size_t w = 0; w < m; ++w) q = std::max(q, std::fabs(beta[w]));
  q = std::min(q, 0.95);
  if (q <= 0.0 || rng.uniform() >= q) return false;
  for (std::size_t w = 0; w < m; ++w) beta[w] /= q;
  return true;
}

// ---- scene ------------------------------------------------------------------------------------

struct Renderer::Impl {
  struct Cell {
    double z00, z10, z01, z11, zmax;
    int material;
  };
  int nx = 0, ny = 0;
  double h = 0.1, inv_h = 10.0;
  double hmax = 0.0, hmin = 0.0;
  double eps = 1e-6;
  std::vector<Cell> cells;
  std::vector<RenderMaterial> materials;
  std::vector<BrdfSampler> samplers;  // one per material
  std::size_t m = 0;  // wavelengths
  bool any_delta = false;

  // One kind of estimate: detector cone around w_center (cos_delta = cos of the half-angle), or the
  // whole hemisphere cosine-weighted (albedo).
  struct Job {
    bool hemisphere = false;
    Vec3 w_center, t_center, b_center;
    double cos_delta = 1.0;
    Vec3 wi;
    double inv_cos_i = 1.0;
    std::uint64_t stream = 0;
  };

  bool intersect(const Vec3& o, const Vec3& d, Hit& hit) const;
  // Detector direction of a sample: uniform in the cone (the axis for an ideal detector), or
  // cosine-weighted over the hemisphere for the albedo (then `scale` = pi, the 1/pdf factor of the
  // cosine-weighted albedo integral; else 1).
  Vec3 detector_direction(const Job& job, Rng& rng, double& scale) const;
  void trace(const Job& job, const RenderSettings& s, Rng& rng, double* contrib, double* beta, double* f) const;
  void source_delta_paths(const Job& job, const RenderSettings& s, Rng& rng, double* contrib, double* beta,
                          double* f) const;
  std::vector<Estimate> run(const std::vector<Job>& jobs, const RenderSettings& s) const;
  // Continuation direction (local frame) for the smooth part at a vertex with outgoing direction
  // wo_l; returns false if none (direction at or below the horizon). `weight` = cos / pdf.
  bool continue_direction(int material, const Vec3& wo_l, const RenderSettings& s, Rng& rng, Vec3& wl,
                          double& weight) const;
  void eval(int material, const Geometry& g, double* out) const {
    const RenderMaterial& mat = materials[material];
    mat.model->evaluate_batch(&g, 1, mat.parameters.data(), m, out);
  }
};

Renderer::Renderer(const HeightField& field, std::vector<RenderMaterial> materials, std::size_t wavelength_count)
    : impl_(std::make_unique<Impl>()) {
  validate(field);
  if (materials.size() != field.materials.size()) throw InputError("render: one material per surface material needed");
  Impl& s = *impl_;
  s.nx = field.nx;
  s.ny = field.ny;
  s.h = field.cell_size_mm;
  s.inv_h = 1.0 / s.h;
  s.m = wavelength_count;
  s.materials = std::move(materials);
  for (const auto& mat : s.materials) {
    if (mat.parameters.size() != wavelength_count * mat.model->parameter_count()) {
      throw InputError("render: material '" + mat.name + "' has a wrong parameter table size");
    }
    s.any_delta = s.any_delta || mat.has_delta;
    s.samplers.emplace_back(*mat.model, mat.parameters, wavelength_count);
  }
  s.cells.resize(static_cast<std::size_t>(s.nx) * s.ny);
  s.hmax = -1e300;
  s.hmin = 1e300;
  for (int j = 0; j < s.ny; ++j) {
    for (int i = 0; i < s.nx; ++i) {
      Impl::Cell& c = s.cells[static_cast<std::size_t>(j) * s.nx + i];
      c.z00 = field.height(i, j);
      c.z10 = field.height(i + 1, j);
      c.z01 = field.height(i, j + 1);
      c.z11 = field.height(i + 1, j + 1);
      c.zmax = std::max(std::max(c.z00, c.z10), std::max(c.z01, c.z11));
      c.material = field.material_at(i, j);
      s.hmax = std::max(s.hmax, c.zmax);
      s.hmin = std::min(s.hmin, c.zmax);
    }
  }
  for (double z : field.heights) s.hmin = std::min(s.hmin, z);
  s.eps = 1e-6 * s.h + 1e-9 * (s.hmax - s.hmin);
}

Renderer::~Renderer() = default;

bool Renderer::intersect(const Vec3& o, const Vec3& d, Hit& hit) const { return impl_->intersect(o, d, hit); }

bool Renderer::Impl::intersect(const Vec3& o, const Vec3& d, Hit& hit) const {
  // Rays above the highest point: escape if not going down, else start at the top plane.
  double t = 0.0;
  if (o.z > hmax) {
    if (d.z >= 0.0) return false;
    t = (o.z - hmax) / (-d.z);
  }
  const double ax = o.x * inv_h, ay = o.y * inv_h;  // position in cell units
  const double bx = d.x * inv_h, by = d.y * inv_h;
  const double x0 = ax + t * bx, y0 = ay + t * by;
  long i = static_cast<long>(std::floor(x0)), j = static_cast<long>(std::floor(y0));
  long iw = i % nx, jw = j % ny;
  if (iw < 0) iw += nx;
  if (jw < 0) jw += ny;
  const double inf = std::numeric_limits<double>::infinity();
  const int step_x = bx > 0 ? 1 : (bx < 0 ? -1 : 0);
  const int step_y = by > 0 ? 1 : (by < 0 ? -1 : 0);
  double t_max_x = step_x > 0 ? (static_cast<double>(i + 1) - ax) / bx : (step_x < 0 ? (static_cast<double>(i) - ax) / bx : inf);
  double t_max_y = step_y > 0 ? (static_cast<double>(j + 1) - ay) / by : (step_y < 0 ? (static_cast<double>(j) - ay) / by : inf);
  const double t_delta_x = step_x != 0 ? 1.0 / std::fabs(bx) : inf;
  const double t_delta_y = step_y != 0 ? 1.0 / std::fabs(by) : inf;
  const double dbxy = bx - by;
  // Every ray starts above the surface (camera rays above the highest point, secondary rays raised
  // vertically by eps above a surface point, which is above the height field whatever the local
  // shape), so g = z_ray - z_surface > 0 at the start and the first crossing to g <= 0 is the hit.
  bool armed = true;
  // A ray climbing so slowly that it needs more steps than this is treated as escaping.
  constexpr long kMaxSteps = 1L << 22;
  for (long step = 0; step < kMaxSteps; ++step) {
    double t_exit = std::min(t_max_x, t_max_y);
    if (!(t_exit < inf)) {
      // Vertical ray: it leaves the height range within this distance.
      t_exit = t + (hmax - hmin + 1.0) / std::max(std::fabs(d.z), 1e-300);
    }
    const Cell& c = cells[static_cast<std::size_t>(jw) * nx + iw];
    const double z_enter = o.z + t * d.z, z_exit = o.z + t_exit * d.z;
    if (std::min(z_enter, z_exit) > c.zmax) {
      armed = true;
    } else {
      // Pieces of the ray inside the cell: split where it crosses the diagonal u = v.
      double ts[3] = {t, t_exit, t_exit};
      int n_pts = 2;
      if (dbxy != 0.0) {
        const double td = ((static_cast<double>(i) - ax) - (static_cast<double>(j) - ay)) / dbxy;
        if (td > t && td < t_exit) {
          ts[1] = td;
          ts[2] = t_exit;
          n_pts = 3;
        }
      }
      for (int k = 0; k + 1 < n_pts; ++k) {
        const double ta = ts[k], tb = ts[k + 1];
        const double tm = 0.5 * (ta + tb);
        const double um = ax + tm * bx - static_cast<double>(i), vm = ay + tm * by - static_cast<double>(j);
        // Triangle: u >= v -> (00, 10, 11), z = z00 + (z10-z00) u + (z11-z10) v;
        //           u <  v -> (00, 11, 01), z = z00 + (z11-z01) u + (z01-z00) v.
        const bool lower = um >= vm;
        const double gu = lower ? c.z10 - c.z00 : c.z11 - c.z01;
        const double gv = lower ? c.z11 - c.z10 : c.z01 - c.z00;
        auto g_at = [&](double tt) {
          const double u = ax + tt * bx - static_cast<double>(i), v = ay + tt * by - static_cast<double>(j);
          return (o.z + tt * d.z) - (c.z00 + gu * u + gv * v);
        };
        const double ga = g_at(ta), gb = g_at(tb);
        if (ga > 0.0) armed = true;
        if (armed && gb <= 0.0) {
          const double th = ga > 0.0 ? ta + (tb - ta) * (ga / (ga - gb)) : ta;
          hit.t = th;
          hit.p = o + th * d;
          hit.n = normalize(Vec3{-gu * inv_h, -gv * inv_h, 1.0});
          hit.material = c.material;
          return true;
        }
        if (gb > 0.0) armed = true;
      }
    }
    if (d.z > 0.0 && z_exit > hmax) return false;
    // Next cell.
    if (t_max_x < t_max_y) {
      t = t_max_x;
      t_max_x += t_delta_x;
      i += step_x;
      iw += step_x;
      if (iw == nx) iw = 0;
      if (iw < 0) iw = nx - 1;
    } else {
      if (!(t_max_y < inf)) return false;  // vertical ray that did not hit: cannot happen
      t = t_max_y;
      t_max_y += t_delta_y;
      j += step_y;
      jw += step_y;
      if (jw == ny) jw = 0;
      if (jw < 0) jw = ny - 1;
    }
  }
  return false;
}

// Paths whose first reflection from the source is a delta (mirror) part, estimated from the source
// side (a detector path cannot find them: its next-event estimation evaluates the smooth part, and a
// mirror vertex sends it towards the source with probability 0). One light sub-path per sample:
// y uniform over the period, first hit x_1 of the beam along -w_i; if x_1 has a delta part R, the
// reflected beam (flux fraction beta = R per unit of the flux E_perp cos(theta_i) dA(y) falling on
// dA(y)) leaves along the mirror direction w_s = 2 (n.w_i) n - w_i. Then, vertex by vertex:
//   - the beam escapes: if the last reflection was a mirror, it is seen by the detector when w_s is in
//     its cone: Lbar / (E_perp cos theta_i) = beta 1[w_s in cone] / (Omega cos theta_s) (albedo: beta);
//   - the beam hits x_j (normal n_j, light arriving from w_in): connection to the detector through
//     the smooth part: a flux Phi on dA_j gives radiance f_j(w_in, w) Phi / dA_j towards w, and dA_j
//     covers (n_j.w) dA_j / cos(theta_w) of the mean plane seen along w, so the per-sample value is
//     beta f_j(w_in, w) (n_j.w) V(x_j, w) / cos(theta_w), w uniform in the cone (albedo: w
//     cosine-weighted over the hemisphere and the value times pi);
//   - continuation: through the delta part with probability 1/2 (beta *= 2 R) or the smooth part with
//     a cosine-weighted direction (beta *= 2 pi f_j(w_in, w_new)); Russian roulette as for detector
//     paths. Light carries f(w_in -> w_new) with w_in as the incidence direction (no reciprocity needed).
// Every path of the sample's light transport is counted once: detector paths cover those whose
// vertex next to the source reflects through its smooth part (next-event estimation), these cover
// those whose vertex next to the source is a mirror; within them, a path ending with a smooth
// vertex is counted by that vertex's connection, one ending with a mirror by the escape test.
void Renderer::Impl::source_delta_paths(const Job& job, const RenderSettings& s, Rng& rng, double* contrib,
                                        double* beta, double* f) const {
  const double x = rng.uniform() * nx * h, y = rng.uniform() * ny * h;
  Hit hit;
  if (!intersect(Vec3{x, y, hmax + 1e-3 * h}, Vec3{-job.wi.x, -job.wi.y, -job.wi.z}, hit)) return;
  if (!materials[hit.material].has_delta) return;
  // Detector direction for the connections.
  double det_scale = 1.0;
  const Vec3 w_det = detector_direction(job, rng, det_scale);
  Vec3 w_in = job.wi;  // direction towards where the light comes from, at the current vertex
  bool mirror = true;  // the first reflection is the delta part
  for (std::size_t w = 0; w < m; ++w) beta[w] = 1.0;
  for (int vertex = 1;; ++vertex) {
    const RenderMaterial& mat = materials[hit.material];
    Vec3 t, b;
    make_basis(hit.n, t, b);
    const Vec3 wi_l = to_local(w_in, t, b, hit.n);
    if (wi_l.z <= 0.0) return;
    const Vec3 p{hit.p.x, hit.p.y, hit.p.z + eps};
    if (vertex > 1 && w_det.z > 0.0) {
      // Connection of this vertex's smooth part to the detector.
      const Vec3 wd_l = to_local(w_det, t, b, hit.n);
      Hit shadow;
      if (wd_l.z > 0.0 && !intersect(p, w_det, shadow)) {
        eval(hit.material, local_geometry(wi_l, wd_l), f);
        const double k = det_scale * wd_l.z / w_det.z;
        for (std::size_t w = 0; w < m; ++w) contrib[w] += beta[w] * f[w] * k;
      }
    }
    Vec3 w_new;
    if (vertex == 1) {
      mirror = true;
    } else {
      mirror = mat.has_delta && rng.uniform() < 0.5;
    }
    const double branch_weight = (vertex == 1 || !mat.has_delta) ? 1.0 : 2.0;
    if (mirror) {
      const Vec3 wl{-wi_l.x, -wi_l.y, wi_l.z};
      w_new = wl.x * t + wl.y * b + wl.z * hit.n;
      const std::size_t np = mat.model->parameter_count();
      for (std::size_t w = 0; w < m; ++w) {
        beta[w] *= branch_weight * mat.model->delta_reflectance(mat.parameters.data() + w * np, wi_l.z);
      }
    } else {
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const Vec3 wl = cosine_direction(u1, u2);
      if (!(wl.z > 0.0)) return;
      w_new = wl.x * t + wl.y * b + wl.z * hit.n;
      eval(hit.material, local_geometry(wi_l, wl), f);
      for (std::size_t w = 0; w < m; ++w) beta[w] *= branch_weight * kPi * f[w];
    }
    if (vertex >= s.rr_start_bounce && !russian_roulette(beta, m, rng)) return;
    if (!intersect(p, w_new, hit)) {
      // Escaped: seen by the detector only after a mirror (a smooth last vertex was connected above).
      if (!mirror || w_new.z <= 0.0) return;
      double k = 1.0;
      if (!job.hemisphere) {
        if (!(job.cos_delta < 1.0) || dot(w_new, job.w_center) < job.cos_delta) return;
        k = 1.0 / (2.0 * kPi * (1.0 - job.cos_delta) * w_new.z);
      }
      for (std::size_t w = 0; w < m; ++w) contrib[w] += k * beta[w];
      return;
    }
    if (s.max_bounces > 0 && vertex >= s.max_bounces) return;  // the next vertex would be one too many
    w_in = Vec3{-w_new.x, -w_new.y, -w_new.z};
  }
}

Vec3 Renderer::Impl::detector_direction(const Job& job, Rng& rng, double& scale) const {
  scale = 1.0;
  if (job.hemisphere) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    scale = kPi;
    return cosine_direction(u1, u2);
  }
  if (job.cos_delta < 1.0) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    const double ca = 1.0 - u1 * (1.0 - job.cos_delta);  // uniform in solid angle
    const double sa = std::sqrt(std::max(0.0, 1.0 - ca * ca)), phi = 2.0 * kPi * u2;
    return (sa * std::cos(phi)) * job.t_center + (sa * std::sin(phi)) * job.b_center + ca * job.w_center;
  }
  return job.w_center;
}

// Cosine sampling: pdf cos/pi, weight pi. BRDF sampling: with probability c from the material's
// table (brdf_sampler.h), else cosine-weighted; whichever was drawn, the weight uses the mixture
// density c p_table(w) + (1 - c) cos/pi, i.e. the one-sample model of multiple importance sampling
// with the balance heuristic (Veach 1997, sec. 9.2.4), unbiased because the mixture is the exact
// density of the drawn direction and is > 0 wherever f cos > 0.
bool Renderer::Impl::continue_direction(int material, const Vec3& wo_l, const RenderSettings& s, Rng& rng, Vec3& wl,
                                        double& weight) const {
  const bool use_table = s.sampling == Sampling::brdf;
  const double c = use_table ? s.brdf_sampling_fraction : 0.0;
  double p_table = 0.0;
  if (use_table && rng.uniform() < c) {
    const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
    wl = samplers[material].sample(wo_l, u1, u2, u3, p_table);
  } else {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    wl = cosine_direction(u1, u2);
    if (!use_table) {
      weight = kPi;
      return wl.z > 0.0;
    }
    if (c > 0.0) p_table = samplers[material].pdf(wo_l, wl);
  }
  if (!(wl.z > 0.0)) return false;
  weight = wl.z / (c * p_table + (1.0 - c) * wl.z / kPi);
  return true;
}

void Renderer::Impl::trace(const Job& job, const RenderSettings& s, Rng& rng, double* contrib, double* beta,
                           double* f) const {
  for (std::size_t w = 0; w < m; ++w) contrib[w] = 0.0;
  // Detector direction (the albedo's factor pi is in the initial throughput below).
  double unused_scale = 1.0;
  Vec3 w_out = detector_direction(job, rng, unused_scale);
  // beta is scratch here (set below for the detector path).
  if (any_delta) source_delta_paths(job, s, rng, contrib, beta, f);
  // Cone directions below the horizon see nothing.
  if (w_out.z <= 0.0) return;
  // Sight line through a uniformly drawn point of the period.
  const double x = rng.uniform() * nx * h, y = rng.uniform() * ny * h;
  Vec3 origin{x, y, hmax + 1e-3 * h};
  Vec3 dir{-w_out.x, -w_out.y, -w_out.z};
  for (std::size_t w = 0; w < m; ++w) beta[w] = job.hemisphere ? kPi : 1.0;  // albedo = pi f

  for (int bounce = 1;; ++bounce) {
    Hit hit;
    if (!intersect(origin, dir, hit)) break;
    Vec3 t, b;
    make_basis(hit.n, t, b);
    const Vec3 wo_l = to_local(w_out, t, b, hit.n);
    if (wo_l.z <= 0.0) break;  // grazing numerical corner case: no radiance
    // Raised vertically, not along the normal: a point above a height field stays above it even
    // at a steep concave edge, where an offset along one facet's normal can end below the other.
    const Vec3 p{hit.p.x, hit.p.y, hit.p.z + eps};
    // Next-event estimation towards the collimated source.
    const double cos_src = dot(hit.n, job.wi);
    if (cos_src > 0.0) {
      Hit shadow;
      if (!intersect(p, job.wi, shadow)) {
        eval(hit.material, local_geometry(to_local(job.wi, t, b, hit.n), wo_l), f);
        const double k = cos_src * job.inv_cos_i;
        for (std::size_t w = 0; w < m; ++w) contrib[w] += beta[w] * f[w] * k;
      }
    }
    if (s.max_bounces > 0 && bounce >= s.max_bounces) break;
    // Continuation.
    const RenderMaterial& mat = materials[hit.material];
    Vec3 w_new;
    bool mirror = false;
    double branch_weight = 1.0;
    if (mat.has_delta) {
      branch_weight = 2.0;
      mirror = rng.uniform() < 0.5;
    }
    if (mirror) {
      const Vec3 wl{-wo_l.x, -wo_l.y, wo_l.z};
      w_new = wl.x * t + wl.y * b + wl.z * hit.n;
      const std::size_t np = mat.model->parameter_count();
      for (std::size_t w = 0; w < m; ++w) {
        beta[w] *= branch_weight * mat.model->delta_reflectance(mat.parameters.data() + w * np, wo_l.z);
      }
    } else {
      Vec3 wl;
      double weight = 0.0;
      if (!continue_direction(hit.material, wo_l, s, rng, wl, weight)) break;
      w_new = wl.x * t + wl.y * b + wl.z * hit.n;
      eval(hit.material, local_geometry(wl, wo_l), f);
      for (std::size_t w = 0; w < m; ++w) beta[w] *= branch_weight * weight * f[w];
    }
    if (bounce >= s.rr_start_bounce && !russian_roulette(beta, m, rng)) break;
    origin = p;
    dir = w_new;
    w_out = Vec3{-w_new.x, -w_new.y, -w_new.z};
  }
}

double Estimate::worst_relative_error() const {
  double worst = 0.0;
  for (std::size_t w = 0; w < mean.size(); ++w) {
    if (standard_error[w] == 0.0) continue;
    worst = std::max(worst, mean[w] != 0.0 ? standard_error[w] / std::fabs(mean[w])
                                           : std::numeric_limits<double>::infinity());
  }
  return worst;
}

// Blocks of paths are the unit of work: block k of a geometry holds paths [k B, min((k+1) B, N_max))
// and has its own random stream (seed, geometry, k). Fixed mode runs all blocks of every geometry in
// one round. Adaptive mode runs min_blocks blocks per geometry, then in rounds adds blocks to the
// geometries that have not reached the target; after each round the statistics of the completed
// blocks are merged in block order and the decision (stop, or how many blocks to add) depends only on
// them, so the result does not depend on the number of threads or on timing.
std::vector<Estimate> Renderer::Impl::run(const std::vector<Job>& jobs, const RenderSettings& s) const {
  const bool adaptive = s.target_relative_error > 0.0;
  if (s.paths_per_block < 1) throw InputError("render: paths_per_block must be >= 1");
  if (!(s.brdf_sampling_fraction >= 0.0 && s.brdf_sampling_fraction < 1.0)) {
    throw InputError("render: brdf_sampling_fraction must be in [0, 1) (cosine sampling keeps the estimator unbiased)");
  }
  if (!(s.target_relative_error >= 0.0) || !std::isfinite(s.target_relative_error)) {
    throw InputError("render: the target relative error must be >= 0");
  }
  long max_paths = s.samples;
  long min_blocks = 0;
  if (adaptive) {
    if (s.max_samples < 2) throw InputError("render: --max-samples must be >= 2");
    if (s.min_blocks < 1) throw InputError("render: min_blocks must be >= 1");
    if (!(s.absolute_error_floor >= 0.0)) throw InputError("render: the absolute error floor must be >= 0");
    max_paths = s.max_samples;
    min_blocks = s.min_blocks;
  } else {
    if (s.samples < 2) throw InputError("render: at least 2 paths per geometry are needed for a standard error");
  }
  const long B = s.paths_per_block;
  const long max_blocks = (max_paths + B - 1) / B;
  if (!adaptive) min_blocks = max_blocks;
  min_blocks = std::min(min_blocks, max_blocks);

  // Per-geometry running statistics, combined over blocks with the pairwise formula of Chan, Golub &
  // LeVeque (1979); per block Welford's update. No cancellation, so a deterministic estimator (e.g.
  // a flat sample seen by an ideal detector) has exactly 0 error.
  struct Accumulator {
    std::vector<double> mean, m2;
    double n = 0.0;
    long blocks = 0;
  };
  std::vector<Accumulator> acc(jobs.size());
  for (auto& a : acc) {
    a.mean.assign(m, 0.0);
    a.m2.assign(m, 0.0);
  }
  std::vector<long> extra(jobs.size(), min_blocks);  // blocks to add in the next round
  std::vector<Estimate> out(jobs.size());
  unsigned n_threads_max = s.threads > 0 ? static_cast<unsigned>(s.threads) : std::max(1u, std::thread::hardware_concurrency());

  for (;;) {
    std::vector<std::pair<std::size_t, long>> items;  // (job, block)
    for (std::size_t g = 0; g < jobs.size(); ++g) {
      for (long k = 0; k < extra[g]; ++k) items.emplace_back(g, acc[g].blocks + k);
    }
    if (items.empty()) break;
    std::vector<double> sums(items.size() * 2 * m, 0.0);
    std::vector<long> counts(items.size(), 0);
    std::atomic<std::size_t> next{0};
    auto worker = [&]() {
      std::vector<double> contrib(m), beta(m), f(m);
      for (;;) {
        const std::size_t item = next.fetch_add(1);
        if (item >= items.size()) break;
        const auto [job_index, block] = items[item];
        const Job& job = jobs[job_index];
        Rng rng(stream_seed(s.seed, job.stream, static_cast<std::uint64_t>(block)));
        const long count = std::min(B, max_paths - block * B);
        double* mean = sums.data() + item * 2 * m;
        double* m2 = mean + m;
        for (long k = 0; k < count; ++k) {
          trace(job, s, rng, contrib.data(), beta.data(), f.data());
          const double inv = 1.0 / static_cast<double>(k + 1);
          for (std::size_t w = 0; w < m; ++w) {
            const double delta = contrib[w] - mean[w];
            mean[w] += delta * inv;
            m2[w] += delta * (contrib[w] - mean[w]);
          }
        }
        counts[item] = count;
      }
    };
    const unsigned n_threads = static_cast<unsigned>(std::min<std::size_t>(n_threads_max, items.size()));
    if (n_threads <= 1) {
      worker();
    } else {
      std::vector<std::thread> pool;
      for (unsigned k = 0; k < n_threads; ++k) pool.emplace_back(worker);
      for (auto& th : pool) th.join();
    }
    // Merge in (job, block) order.
    for (std::size_t item = 0; item < items.size(); ++item) {
      Accumulator& a = acc[items[item].first];
      const double* bm = sums.data() + item * 2 * m;
      const double nb = static_cast<double>(counts[item]);
      const double nt = a.n + nb;
      for (std::size_t w = 0; w < m; ++w) {
        const double delta = bm[w] - a.mean[w];
        a.mean[w] += delta * (nb / nt);
        a.m2[w] += bm[m + w] + delta * delta * (a.n * nb / nt);
      }
      a.n = nt;
      a.blocks += 1;
    }
    // Estimates and the next round.
    for (std::size_t g = 0; g < jobs.size(); ++g) {
      const Accumulator& a = acc[g];
      Estimate& e = out[g];
      e.paths = static_cast<long>(a.n);
      e.mean = a.mean;
      e.standard_error.resize(m);
      for (std::size_t w = 0; w < m; ++w) e.standard_error[w] = std::sqrt(std::max(0.0, a.m2[w] / (a.n - 1.0)) / a.n);
      extra[g] = 0;
      if (!adaptive) continue;
      // Ratio of the standard error to the tolerance; the paths needed scale with its square.
      double ratio = 0.0;
      for (std::size_t w = 0; w < m; ++w) {
        const double tol = std::max(s.target_relative_error * std::fabs(e.mean[w]), s.absolute_error_floor);
        if (e.standard_error[w] <= tol) continue;
        ratio = std::max(ratio, tol > 0.0 ? e.standard_error[w] / tol : std::numeric_limits<double>::infinity());
      }
      e.converged = ratio == 0.0;
      if (e.converged || a.blocks >= max_blocks) continue;
      // Blocks predicted to reach the target, at least 1, at most 3x those done (a noisy early error
      // estimate cannot launch a huge round), at most up to max_samples.
      const double needed = std::ceil(a.n * std::min(ratio * ratio, 1e12) / static_cast<double>(B));
      long add = static_cast<long>(std::min(needed, 1e15)) - a.blocks;
      add = std::clamp(add, 1L, 3 * a.blocks);
      extra[g] = std::min(add, max_blocks - a.blocks);
    }
    if (!adaptive) break;
  }
  return out;
}

namespace {
Renderer::Impl::Job brdf_job(const Geometry& g, const RenderSettings& s, std::uint64_t stream) {
  if (!(s.acceptance_half_angle_deg >= 0.0 && s.acceptance_half_angle_deg <= 45.0)) {
    throw InputError("render: acceptance half-angle must be in [0, 45] deg");
  }
  const double ci = g.wi.z;
  if (!(ci > 1e-6)) throw InputError("render: theta_i = 90 deg gives no irradiance on the mean plane");
  Renderer::Impl::Job job;
  job.wi = g.wi;
  job.inv_cos_i = 1.0 / ci;
  job.w_center = g.wr;
  make_basis(g.wr, job.t_center, job.b_center);
  job.cos_delta = std::cos(deg_to_rad(s.acceptance_half_angle_deg));
  job.stream = stream;
  return job;
}
}  // namespace

Estimate Renderer::brdf(const Geometry& g, const RenderSettings& settings, std::uint64_t stream) const {
  return impl_->run({brdf_job(g, settings, stream)}, settings).front();
}

std::vector<Estimate> Renderer::brdf(const std::vector<Geometry>& geometries, const RenderSettings& settings) const {
  std::vector<Impl::Job> jobs;
  for (std::size_t k = 0; k < geometries.size(); ++k) jobs.push_back(brdf_job(geometries[k], settings, k));
  return impl_->run(jobs, settings);
}

Estimate Renderer::directional_albedo(double theta_i, double phi_i, const RenderSettings& settings,
                                      std::uint64_t stream) const {
  const Geometry g = geometry_from_radians(theta_i, phi_i, 0.0, 0.0);
  Impl::Job job = brdf_job(g, settings, stream);
  job.hemisphere = true;
  return impl_->run({job}, settings).front();
}

SpectralDataset render_dataset(const HeightField& field, const std::vector<Geometry>& geometries,
                               const std::vector<double>& wavelengths, const RenderSettings& settings,
                               std::vector<Estimate>* estimates) {
  if (geometries.empty()) throw InputError("render: no geometries");
  for (std::size_t k = 0; k < wavelengths.size(); ++k) {
    if (k > 0 && !(wavelengths[k] > wavelengths[k - 1])) throw InputError("render: wavelengths must increase");
  }
  Renderer renderer(field, load_materials(field, wavelengths), wavelengths.size());
  const std::vector<Estimate> est = renderer.brdf(geometries, settings);
  SpectralDataset d;
  d.geometries = geometries;
  d.wavelengths = wavelengths;
  const std::size_t m = wavelengths.size();
  d.brdf.resize(geometries.size() * m);
  d.sigma.resize(geometries.size() * m);
  for (std::size_t g = 0; g < geometries.size(); ++g) {
    for (std::size_t w = 0; w < m; ++w) {
      d.brdf[g * m + w] = est[g].mean[w];
      d.sigma[g * m + w] = est[g].standard_error[w];
    }
  }
  d.metadata["sample"] = field.name.empty() ? std::string("virtual sample") : field.name;
  d.metadata["instrument"] = "roadbrdf virtual gonioreflectometer (Monte Carlo path tracing of a periodic height field)";
  d.metadata["quantity"] =
      "BRDF averaged over the detector cone (uniform in solid angle) and the whole sample period; sigma = Monte "
      "Carlo standard error";
  std::ostringstream a;
  a << settings.acceptance_half_angle_deg;
  d.metadata["acceptance_half_angle_deg"] = a.str();
  d.metadata["sampling"] = settings.sampling == Sampling::brdf
                              ? "brdf (tabulated BRDF sampler mixed with cosine sampling, one-sample MIS, "
                                "BRDF fraction " + std::to_string(settings.brdf_sampling_fraction) + ")"
                              : "cosine";
  if (settings.target_relative_error > 0.0) {
    std::vector<long> paths;
    std::vector<double> worst;
    std::string not_converged;
    for (std::size_t g = 0; g < est.size(); ++g) {
      paths.push_back(est[g].paths);
      worst.push_back(est[g].worst_relative_error());
      if (!est[g].converged) {
        std::ostringstream o;
        const Geometry& gg = geometries[g];
        o << (not_converged.empty() ? "" : "; ") << "geometry " << g + 1 << " (" << rad_to_deg(gg.theta_i) << ","
          << rad_to_deg(gg.phi_i) << "," << rad_to_deg(gg.theta_r) << "," << rad_to_deg(gg.phi_r)
          << " deg): relative error " << worst.back();
        not_converged += o.str();
      }
    }
    std::sort(paths.begin(), paths.end());
    std::sort(worst.begin(), worst.end());
    std::ostringstream o;
    o << settings.target_relative_error << " (per wavelength: sigma <= max(target |BRDF|, "
      << settings.absolute_error_floor << " sr^-1)); at least " << settings.min_blocks * settings.paths_per_block
      << " paths, at most " << settings.max_samples;
    d.metadata["target_relative_error"] = o.str();
    std::ostringstream p;
    p << "min " << paths.front() << ", median " << paths[paths.size() / 2] << ", max " << paths.back();
    d.metadata["paths_per_geometry"] = p.str();
    std::ostringstream w;
    w << "median " << worst[worst.size() / 2] << ", max " << worst.back();
    d.metadata["achieved_relative_error"] = w.str();
    d.metadata["geometries_not_converged"] = not_converged.empty() ? std::string("none") : not_converged;
  } else {
    d.metadata["paths_per_geometry"] = std::to_string(settings.samples);
  }
  d.metadata["seed"] = std::to_string(settings.seed);
  d.metadata["max_bounces"] = settings.max_bounces > 0 ? std::to_string(settings.max_bounces) : "unlimited";
  if (estimates) *estimates = est;
  return d;
}

}  // namespace roadbrdf::surface
