// Albedo of a virtual sample measured by the virtual gonioreflectometer (the last step of the chain
// components -> virtual sample -> mixing prediction compared with simulation -> albedo).
//
// Black-sky albedo (directional-hemispherical reflectance) at sun zenith theta_s:
//     A(theta_s) = int_hemisphere f(w_s, w) cos(theta) dw,
// estimated by Renderer::directional_albedo (the path estimator with the detector direction drawn
// cosine-weighted over the hemisphere; standard error from the paths). Sun azimuth 0 in the sample
// frame (the virtual samples are statistically isotropic).
// White-sky albedo (bihemispherical reflectance under isotropic illumination):
//     W = 2 int_0^1 A(mu) mu dmu,   mu = cos(theta_s)
// by an n-point Gauss-Legendre rule in mu on [0, 1] (exact when A(mu) is a polynomial of degree
// <= 2n - 2), each node an independent Monte Carlo estimate: W = sum_k 2 w_k mu_k A(mu_k), standard
// error sqrt(sum_k (2 w_k mu_k)^2 se_k^2). The quadrature error is not in that standard error; with the
// default n = 8 it is below 1e-4 for the Oren-Nayar and Hapke families (tests/surface/
// surface_virtual_albedo_test.cpp compares a flat sample with the deterministic albedo quadrature).
// Same definitions as albedo/hemisphere.h (report eqs. 2.19-2.21).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/render.h"

namespace roadbrdf::surface {

struct VirtualAlbedo {
  std::vector<double> wavelengths;                   // nm
  std::vector<double> sun_zenith_deg;                // black-sky angles
  std::vector<std::vector<double>> black_sky;        // [angle][wavelength]
  std::vector<std::vector<double>> black_sky_error;  // standard errors, same layout
  std::vector<double> white_sky;                     // per wavelength (empty unless asked)
  std::vector<double> white_sky_error;               // standard error (Monte Carlo part only)
  int white_sky_nodes = 0;                           // Gauss-Legendre nodes in mu (0: not computed)
  long paths = 0;                                    // total paths
  std::vector<bool> converged;                       // per black-sky angle (adaptive runs), then per node

  // Keys: wavelengths, sun_zenith (the black-sky angles [deg]), black_sky, black_sky_error
  // ([angle][wavelength]), white_sky, white_sky_error, white_sky_nodes, paths, converged.
  nlohmann::json to_json() const;
};

// Black-sky albedo at the given sun zenith angles [deg, 0 <= theta < 90] and, if white_sky_nodes > 0,
// the white-sky albedo by that many Gauss-Legendre nodes. Throws InputError for bad angles/wavelengths.
VirtualAlbedo render_albedo(const HeightField& field, const std::vector<double>& sun_zenith_deg,
                            const std::vector<double>& wavelengths, const RenderSettings& settings,
                            int white_sky_nodes = 8);

// The albedo table of a virtual sample (CSV, laid out like the albedo command's): a comment line
// naming `surface_name`, then wavelength_nm, white_sky, white_sky_error (when computed) and
// black_sky_<Z>deg, black_sky_error_<Z>deg per sun zenith Z; dimensionless reflectances with their
// Monte Carlo standard errors. Written atomically (core/atomic_file.h).
void write_virtual_albedo(const std::string& path, const VirtualAlbedo& albedo, const std::string& surface_name);

}  // namespace roadbrdf::surface
