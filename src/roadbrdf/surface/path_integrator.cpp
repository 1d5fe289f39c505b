#include "roadbrdf/surface/path_integrator.h"

#include <algorithm>
#include <cmath>

#include "roadbrdf/core/math.h"
#include "roadbrdf/surface/frame.h"
#include "roadbrdf/surface/render.h"

namespace roadbrdf::surface {

namespace {

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

}  // namespace

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
void PathIntegrator::source_delta_paths(const PathJob& job, const RenderSettings& s, Rng& rng, double* contrib,
                                        Scratch& scratch) const {
  double* beta = scratch.beta.data();
  double* f = scratch.f.data();
  const double u1 = rng.uniform(), u2 = rng.uniform();
  SurfaceHit hit;
  if (!tracer_.intersect(tracer_.point_above(u1, u2), Vec3{-job.wi.x, -job.wi.y, -job.wi.z}, hit)) return;
  if (!materials_.has_delta(hit.material)) return;
  // Detector direction for the connections.
  double det_scale = 1.0;
  const Vec3 w_det = detector_direction(job, rng, det_scale);
  Vec3 w_in = job.wi;  // direction towards where the light comes from, at the current vertex
  bool mirror = true;  // the first reflection is the delta part
  for (std::size_t w = 0; w < m_; ++w) beta[w] = 1.0;
  for (int vertex = 1;; ++vertex) {
    const bool has_delta = materials_.has_delta(hit.material);
    Vec3 t, b;
    make_basis(hit.n, t, b);
    const Vec3 wi_l = to_local(w_in, t, b, hit.n);
    if (wi_l.z <= 0.0) return;
    const Vec3 p{hit.p.x, hit.p.y, hit.p.z + tracer_.offset()};
    if (vertex > 1 && w_det.z > 0.0) {
      // Connection of this vertex's smooth part to the detector.
      const Vec3 wd_l = to_local(w_det, t, b, hit.n);
      SurfaceHit shadow;
      if (wd_l.z > 0.0 && !tracer_.intersect(p, w_det, shadow)) {
        materials_.evaluate(hit.material, local_geometry(wi_l, wd_l, materials_.reads_angles(hit.material)), f);
        const double k = det_scale * wd_l.z / w_det.z;
        for (std::size_t w = 0; w < m_; ++w) contrib[w] += beta[w] * f[w] * k;
      }
    }
    Vec3 w_new;
    if (vertex == 1) {
      mirror = true;
    } else {
      mirror = has_delta && rng.uniform() < 0.5;
    }
    const double branch_weight = (vertex == 1 || !has_delta) ? 1.0 : 2.0;
    if (mirror) {
      const Vec3 wl{-wi_l.x, -wi_l.y, wi_l.z};
      w_new = wl.x * t + wl.y * b + wl.z * hit.n;
      materials_.scale_by_delta_reflectance(hit.material, wi_l.z, branch_weight, beta);
    } else {
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const Vec3 wl = cosine_direction(u1, u2);
      if (!(wl.z > 0.0)) return;
      w_new = wl.x * t + wl.y * b + wl.z * hit.n;
      materials_.evaluate(hit.material, local_geometry(wi_l, wl, materials_.reads_angles(hit.material)), f);
      for (std::size_t w = 0; w < m_; ++w) beta[w] *= branch_weight * kPi * f[w];
    }
    if (vertex >= s.rr_start_bounce && !russian_roulette(beta, m_, rng)) return;
    if (!tracer_.intersect(p, w_new, hit)) {
      // Escaped: seen by the detector only after a mirror (a smooth last vertex was connected above).
      if (!mirror || w_new.z <= 0.0) return;
      double k = 1.0;
      if (!job.hemisphere) {
        if (!(job.cos_delta < 1.0) || dot(w_new, job.w_center) < job.cos_delta) return;
        k = 1.0 / (2.0 * kPi * (1.0 - job.cos_delta) * w_new.z);
      }
      for (std::size_t w = 0; w < m_; ++w) contrib[w] += k * beta[w];
      return;
    }
    if (s.max_bounces > 0 && vertex >= s.max_bounces) return;  // the next vertex would be one too many
    w_in = Vec3{-w_new.x, -w_new.y, -w_new.z};
  }
}

Vec3 PathIntegrator::detector_direction(const PathJob& job, Rng& rng, double& scale) const {
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
bool PathIntegrator::continue_direction(int material, const Vec3& wo_l, const RenderSettings& s, Rng& rng, Vec3& wl,
                                        double& weight) const {
  const bool use_table = s.sampling == Sampling::brdf;
  const double c = use_table ? s.brdf_sampling_fraction : 0.0;
  double p_table = 0.0;
  if (use_table && rng.uniform() < c) {
    const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
    wl = materials_.sampler(material).sample(wo_l, u1, u2, u3, p_table);
  } else {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    wl = cosine_direction(u1, u2);
    if (!use_table) {
      weight = kPi;
      return wl.z > 0.0;
    }
    if (c > 0.0) p_table = materials_.sampler(material).pdf(wo_l, wl);
  }
  if (!(wl.z > 0.0)) return false;
  weight = wl.z / (c * p_table + (1.0 - c) * wl.z / kPi);
  return true;
}

void PathIntegrator::sample(const PathJob& job, const RenderSettings& s, Rng& rng, double* contrib,
                            Scratch& scratch) const {
  double* beta = scratch.beta.data();
  double* f = scratch.f.data();
  for (std::size_t w = 0; w < m_; ++w) contrib[w] = 0.0;
  // Detector direction (the albedo's factor pi is in the initial throughput below).
  double unused_scale = 1.0;
  Vec3 w_out = detector_direction(job, rng, unused_scale);
  // The light paths use the scratch space before the detector path does.
  if (materials_.any_delta()) source_delta_paths(job, s, rng, contrib, scratch);
  // Cone directions below the horizon see nothing.
  if (w_out.z <= 0.0) return;
  // Sight line through a uniformly drawn point of the period.
  const double u1 = rng.uniform(), u2 = rng.uniform();
  Vec3 origin = tracer_.point_above(u1, u2);
  Vec3 dir{-w_out.x, -w_out.y, -w_out.z};
  for (std::size_t w = 0; w < m_; ++w) beta[w] = job.hemisphere ? kPi : 1.0;  // albedo = pi f

  for (int bounce = 1;; ++bounce) {
    SurfaceHit hit;
    if (!tracer_.intersect(origin, dir, hit)) break;
    Vec3 t, b;
    make_basis(hit.n, t, b);
    const Vec3 wo_l = to_local(w_out, t, b, hit.n);
    if (wo_l.z <= 0.0) break;  // grazing numerical corner case: no radiance
    // Raised vertically, not along the normal: a point above a height field stays above it even
    // at a steep concave edge, where an offset along one facet's normal can end below the other.
    const Vec3 p{hit.p.x, hit.p.y, hit.p.z + tracer_.offset()};
    // Next-event estimation towards the collimated source.
    const double cos_src = dot(hit.n, job.wi);
    if (cos_src > 0.0) {
      SurfaceHit shadow;
      if (!tracer_.intersect(p, job.wi, shadow)) {
        materials_.evaluate(hit.material,
                            local_geometry(to_local(job.wi, t, b, hit.n), wo_l, materials_.reads_angles(hit.material)),
                            f);
        const double k = cos_src * job.inv_cos_i;
        for (std::size_t w = 0; w < m_; ++w) contrib[w] += beta[w] * f[w] * k;
      }
    }
    if (s.max_bounces > 0 && bounce >= s.max_bounces) break;
    // Continuation.
    const bool has_delta = materials_.has_delta(hit.material);
    Vec3 w_new;
    bool mirror = false;
    double branch_weight = 1.0;
    if (has_delta) {
      branch_weight = 2.0;
      mirror = rng.uniform() < 0.5;
    }
    if (mirror) {
      const Vec3 wl{-wo_l.x, -wo_l.y, wo_l.z};
      w_new = wl.x * t + wl.y * b + wl.z * hit.n;
      materials_.scale_by_delta_reflectance(hit.material, wo_l.z, branch_weight, beta);
    } else {
      Vec3 wl;
      double weight = 0.0;
      if (!continue_direction(hit.material, wo_l, s, rng, wl, weight)) break;
      w_new = wl.x * t + wl.y * b + wl.z * hit.n;
      materials_.evaluate(hit.material, local_geometry(wl, wo_l, materials_.reads_angles(hit.material)), f);
      for (std::size_t w = 0; w < m_; ++w) beta[w] *= branch_weight * weight * f[w];
    }
    if (bounce >= s.rr_start_bounce && !russian_roulette(beta, m_, rng)) break;
    origin = p;
    dir = w_new;
    w_out = Vec3{-w_new.x, -w_new.y, -w_new.z};
  }
}

}  // namespace roadbrdf::surface
