#include "roadbrdf/surface/render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/surface/frame.h"
#include "roadbrdf/surface/path_integrator.h"
#include "roadbrdf/surface/scheduler.h"

namespace roadbrdf::surface {

struct Renderer::Impl {
  Impl(const HeightField& field, std::vector<RenderMaterial> materials, std::size_t wavelength_count)
      : tracer(field), materials(std::move(materials), wavelength_count), integrator(tracer, this->materials) {}
  HeightFieldTracer tracer;
  MaterialSet materials;
  PathIntegrator integrator;

  std::vector<Estimate> run(const std::vector<PathJob>& jobs, const RenderSettings& s) const;
};

namespace {

// The paths of a list of jobs, for the scheduler.
class JobPaths final : public PathSource {
 public:
  JobPaths(const PathIntegrator& integrator, const std::vector<PathJob>& jobs, const RenderSettings& s, std::size_t m)
      : integrator_(integrator), jobs_(jobs), settings_(s), m_(m) {}
  std::size_t wavelength_count() const override { return m_; }
  std::uint64_t stream(std::size_t job) const override { return jobs_[job].stream; }
  std::unique_ptr<Workspace> workspace() const override { return std::make_unique<Scratch>(m_); }
  void path(std::size_t job, Rng& rng, Workspace& workspace, double* values) const override {
    integrator_.sample(jobs_[job], settings_, rng, values, static_cast<Scratch&>(workspace).paths);
  }

 private:
  struct Scratch final : Workspace {
    explicit Scratch(std::size_t m) : paths(m) {}
    PathIntegrator::Scratch paths;
  };
  const PathIntegrator& integrator_;
  const std::vector<PathJob>& jobs_;
  const RenderSettings& settings_;
  std::size_t m_;
};

PathJob brdf_job(const Geometry& g, const RenderSettings& s, std::uint64_t stream) {
  if (!(s.acceptance_half_angle_deg >= 0.0 && s.acceptance_half_angle_deg <= 45.0)) {
    throw InputError("render: acceptance half-angle must be in [0, 45] deg");
  }
  const double ci = g.wi.z;
  if (!(ci > 1e-6)) throw InputError("render: theta_i = 90 deg gives no irradiance on the mean plane");
  PathJob job;
  job.wi = g.wi;
  job.inv_cos_i = 1.0 / ci;
  job.w_center = g.wr;
  make_basis(g.wr, job.t_center, job.b_center);
  job.cos_delta = std::cos(deg_to_rad(s.acceptance_half_angle_deg));
  job.stream = stream;
  return job;
}

}  // namespace

std::vector<Estimate> Renderer::Impl::run(const std::vector<PathJob>& jobs, const RenderSettings& s) const {
  return run_estimates(JobPaths(integrator, jobs, s, materials.wavelength_count()), jobs.size(), s);
}

Renderer::Renderer(const HeightField& field, std::vector<RenderMaterial> materials, std::size_t wavelength_count) {
  validate(field);
  if (materials.size() != field.materials.size()) throw InputError("render: one material per surface material needed");
  impl_ = std::make_unique<Impl>(field, std::move(materials), wavelength_count);
}

Renderer::~Renderer() = default;

bool Renderer::intersect(const Vec3& o, const Vec3& d, Hit& hit) const { return impl_->tracer.intersect(o, d, hit); }

Estimate Renderer::brdf(const Geometry& g, const RenderSettings& settings, std::uint64_t stream) const {
  return impl_->run({brdf_job(g, settings, stream)}, settings).front();
}

std::vector<Estimate> Renderer::brdf(const std::vector<Geometry>& geometries, const RenderSettings& settings) const {
  std::vector<PathJob> jobs;
  for (std::size_t k = 0; k < geometries.size(); ++k) jobs.push_back(brdf_job(geometries[k], settings, k));
  return impl_->run(jobs, settings);
}

Estimate Renderer::directional_albedo(double theta_i, double phi_i, const RenderSettings& settings,
                                      std::uint64_t stream) const {
  const Geometry g = geometry_from_radians(theta_i, phi_i, 0.0, 0.0);
  PathJob job = brdf_job(g, settings, stream);
  job.hemisphere = true;
  return impl_->run({job}, settings).front();
}

double Estimate::worst_relative_error() const {
  double worst = 0.0;
  for (std::size_t w = 0; w < mean.size(); ++w) {
    if (standard_error[w] == 0.0) continue;
    worst = std::max(worst,
                     mean[w] != 0.0 ? standard_error[w] / std::fabs(mean[w]) : std::numeric_limits<double>::infinity());
  }
  return worst;
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
  d.metadata["instrument"] =
      "roadbrdf virtual gonioreflectometer (Monte Carlo path tracing of a periodic height field)";
  d.metadata["quantity"] =
      "BRDF averaged over the detector cone (uniform in solid angle) and the whole sample period; sigma = Monte "
      "Carlo standard error";
  std::ostringstream a;
  a << settings.acceptance_half_angle_deg;
  d.metadata["acceptance_half_angle_deg"] = a.str();
  d.metadata["sampling"] = settings.sampling == Sampling::brdf
                               ? "brdf (tabulated BRDF sampler mixed with cosine sampling, one-sample MIS, "
                                 "BRDF fraction " +
                                     std::to_string(settings.brdf_sampling_fraction) + ")"
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
