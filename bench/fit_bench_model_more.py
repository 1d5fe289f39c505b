"""Independent NumPy implementations of the models of `roadbrdf models` that bench/fit_bench_model.py does not
cover, written from the papers (with the conventions the model headers specify: BRDF in sr^-1, both directions
pointing away from the surface, phi_r = phi_i is the backscatter side), for the fitting benchmark of every model
(bench/fit_bench_all.sh). Each function takes a Geometry (bench/fit_bench_model.py) and the full parameter
vector in the order of `roadbrdf models`. Where the paper's form needs an integral (Simonot's hemispherical
Fresnel reflectance, Kelemen & Szirmay-Kalos' specular albedo), it is evaluated by a plain Gauss-Legendre rule,
as a user would."""
import numpy as np
from fit_bench_model import fresnel, torrance_sparrow

INV_PI = 1.0 / np.pi


def half_vector(g):
    s = g.wi + g.wr
    return s / np.sqrt((s * s).sum(axis=0))


def lambert(g, p):
    """Lambert: f = rho / pi."""
    return np.full(g.ci.shape, p[0] * INV_PI)


def ross_li(g, p):
    """RossThick-LiSparseR (Lucht, Schaaf & Strahler 2000, eqs. 37-46 with h/b = 2, b/r = 1; Wanner et al. 1995):
    BRDF = (f_iso + f_vol K_vol + f_geo K_geo) / pi. phi = relative azimuth, 0 = hot spot side."""
    f_iso, f_vol, f_geo = p
    ts, tv = g.ti, g.tr
    phi = g.phi_r - g.phi_i
    cos_xi = np.clip(np.cos(ts) * np.cos(tv) + np.sin(ts) * np.sin(tv) * np.cos(phi), -1.0, 1.0)
    xi = np.arccos(cos_xi)
    k_vol = ((np.pi / 2 - xi) * cos_xi + np.sin(xi)) / (np.cos(ts) + np.cos(tv)) - np.pi / 4
    tan_s, tan_v = np.tan(ts), np.tan(tv)
    sec_s, sec_v = 1.0 / np.cos(ts), 1.0 / np.cos(tv)
    d2 = np.maximum(tan_s ** 2 + tan_v ** 2 - 2.0 * tan_s * tan_v * np.cos(phi), 0.0)
    cos_t = np.clip(2.0 * np.sqrt(d2 + (tan_s * tan_v * np.sin(phi)) ** 2) / (sec_s + sec_v), -1.0, 1.0)
    t = np.arccos(cos_t)
    overlap = (t - np.sin(t) * cos_t) * (sec_s + sec_v) / np.pi
    k_geo = overlap - sec_s - sec_v + 0.5 * (1.0 + cos_xi) * sec_s * sec_v
    return (f_iso + f_vol * k_vol + f_geo * k_geo) / np.pi


def retro_phong(g, p):
    """Spieringhs et al. 2023 / report eq. 3.27, lobes clamped at 0:
    f = kd/pi + ks(ti) (n+2)/(2 pi) max(0, mirror(wi).wr)^n + kr(ti) (n+2)/(2 pi) max(0, wi.wr)^n,
    kr = k1 (1 - cos ti) + k2, ks = k3 exp(k4 (1 - cos ti))."""
    kd, n, k1, k2, k3, k4 = p
    omc = 1.0 - g.ci
    kr = k1 * omc + k2
    ks = k3 * np.exp(k4 * omc)
    norm = (n + 2.0) / (2.0 * np.pi)
    cs = -g.wi[0] * g.wr[0] - g.wi[1] * g.wr[1] + g.wi[2] * g.wr[2]
    cr = (g.wi * g.wr).sum(axis=0)
    spec = np.where(cs > 0.0, np.maximum(cs, 1e-300) ** n, 0.0)
    retro = np.where(cr > 0.0, np.maximum(cr, 1e-300) ** n, 0.0)
    return kd / np.pi + norm * (ks * spec + kr * retro)


def lafortune(g, p):
    """Lafortune et al. 1997 eq. 4, one isotropic lobe (C_y = C_x), per-lobe clamp, plus k_d/pi:
    f = kd/pi + rho max(0, Cx (u_x v_x + u_y v_y) + Cz u_z v_z)^n."""
    kd, rho, cx, cz, n = p
    base = cx * (g.wi[0] * g.wr[0] + g.wi[1] * g.wr[1]) + cz * g.wi[2] * g.wr[2]
    return kd / np.pi + np.where(base > 0.0, rho * np.maximum(base, 1e-300) ** n, 0.0)


def torrance_sparrow_only(g, p):
    """Torrance-Sparrow with GGX, Smith height-correlated masking, exact Fresnel (bench/fit_bench_model.py)."""
    return torrance_sparrow(g, p[0], p[1], p[2])


def schlick(c, f0):
    m = 1.0 - np.clip(c, 0.0, 1.0)
    return f0 + (1.0 - f0) * m ** 5


def ashikhmin_shirley(g, p):
    """Ashikhmin & Shirley 2000, eqs. 4 and 5 (no k_d/k_s weights):
    f_s = sqrt((nu+1)(nv+1))/(8 pi) (n.h)^((nu (h.u)^2 + nv (h.v)^2)/(1 - (n.h)^2)) / ((h.k) max(n.k1, n.k2)) F(h.k)
    f_d = 28 rd/(23 pi) (1 - rs) (1 - (1 - n.k1/2)^5)(1 - (1 - n.k2/2)^5), F Schlick with R_s."""
    rd, rs, nu, nv = p
    h = half_vector(g)
    hk = (h * g.wi).sum(axis=0)
    sin2 = h[0] ** 2 + h[1] ** 2
    safe = np.where(sin2 > 0.0, sin2, 1.0)
    expo = np.where(sin2 > 0.0, (nu * h[0] ** 2 + nv * h[1] ** 2) / safe, 0.0)
    spec = (np.sqrt((nu + 1.0) * (nv + 1.0)) / (8.0 * np.pi) * h[2] ** expo
            / (hk * np.maximum(g.ci, g.cr)) * schlick(hk, rs))
    diff = (28.0 * rd / (23.0 * np.pi) * (1.0 - rs) * (1.0 - (1.0 - 0.5 * g.ci) ** 5)
            * (1.0 - (1.0 - 0.5 * g.cr) ** 5))
    return diff + spec


def burley(g, p):
    """Burley 2012 (section 5.3 diffuse with F_D90 = 0.5 + 2 r cos^2 theta_d; GGX D with alpha = r^2; Smith G
    with Walter's GGX G1 = 2/(1 + sqrt(1 + alpha^2 tan^2)), alpha_g = r^2 (2014 addendum); Schlick F with
    F0 = ((n-1)/(n+1))^2); f = f_d + specular F D G / (4 cos_i cos_r)."""
    rho, r, spec_w, ior = p
    h = half_vector(g)
    cd = (h * g.wi).sum(axis=0)
    fd90 = 0.5 + 2.0 * r * cd ** 2
    fd = rho / np.pi * (1.0 + (fd90 - 1.0) * (1.0 - g.ci) ** 5) * (1.0 + (fd90 - 1.0) * (1.0 - g.cr) ** 5)
    a = r * r
    d = a * a / (np.pi * (a * a * h[2] ** 2 + 1.0 - h[2] ** 2) ** 2)

    def g1(c):
        tan2 = (1.0 - c * c) / (c * c)
        return 2.0 / (1.0 + np.sqrt(1.0 + a * a * tan2))
    f0 = ((ior - 1.0) / (ior + 1.0)) ** 2
    return fd + spec_w * schlick(cd, f0) * d * g1(g.ci) * g1(g.cr) / (4.0 * g.ci * g.cr)


_MU64, _W64 = np.polynomial.legendre.leggauss(64)
_MU64, _W64 = 0.5 * (_MU64 + 1.0), 0.5 * _W64


def simonot(g, p):
    """Simonot 2009, flat interfaced Lambertian facet (report eq. 3.19 with d theta restored), smooth part:
    f = rho (1/eta^2)(1 - R(ti))(1 - R(tr)) / (pi (1 - rho r10)), 1 - r10 = (1/eta^2)(1 - r01),
    r01 = int_0^1 R(mu) 2 mu dmu (exact dielectric Fresnel R; 64-node Gauss-Legendre)."""
    rho, eta = p
    r01 = (2.0 * _W64 * _MU64 * fresnel(_MU64, eta)).sum()
    r10 = 1.0 - (1.0 - r01) / eta ** 2
    return rho / eta ** 2 * (1.0 - fresnel(g.ci, eta)) * (1.0 - fresnel(g.cr, eta)) / (np.pi * (1.0 - rho * r10))


class KskQuadrature:
    """Gauss-Legendre rules for the specular albedo rho_s(mu) = int f_s cos theta_r dw_r (theta_r, phi_r over
    the hemisphere; phi symmetric) and rho_bar = 2 int_0^1 rho_s(mu) mu dmu."""
    def __init__(self, n_theta=96, n_phi=96, n_mu=48):
        x, w = np.polynomial.legendre.leggauss(n_theta)
        t = 0.25 * np.pi * (x + 1.0)
        wt = 0.25 * np.pi * w * np.sin(t) * np.cos(t)            # cos theta_r dw_r = cos sin dtheta dphi
        x, w = np.polynomial.legendre.leggauss(n_phi)
        ph = 0.5 * np.pi * (x + 1.0)
        wp = 0.5 * np.pi * w * 2.0                                # phi in [0, pi], doubled
        T, P = np.meshgrid(t, ph, indexing="ij")
        self.wr = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)]).reshape(3, -1)
        self.weight = np.outer(wt, wp).ravel()
        x, w = np.polynomial.legendre.leggauss(n_mu)
        self.mu_nodes = 0.5 * (x + 1.0)
        self.mu_weights = 0.5 * w


def ksk_specular(cos_h, cos_ih, alpha, f0):
    """Kelemen & Szirmay-Kalos specular term P_H(h) F(l.h) / (4 (l.h)^2), P_H Beckmann (report eq. 3.8)."""
    c2 = cos_h * cos_h
    dens = np.where(cos_h > 0.0, np.exp(-(1.0 - c2) / (c2 * alpha * alpha)) / (np.pi * alpha ** 2 * c2 * c2), 0.0)
    return dens * schlick(cos_ih, f0) / (4.0 * cos_ih * cos_ih)


def ksk_albedo(q, mu, alpha, f0):
    """rho_s at each incidence cosine of mu (1-d array), by the quadrature q."""
    s = np.sqrt(np.maximum(0.0, 1.0 - mu * mu))
    wi = np.stack([s, np.zeros_like(mu), mu])                # incidence in the x-z plane
    hsum = wi[:, :, None] + q.wr[:, None, :]
    ln = np.sqrt((hsum * hsum).sum(axis=0))
    fs = ksk_specular(hsum[2] / ln, 0.5 * ln, alpha, f0)
    return fs @ q.weight


class KskGeometry:
    def __init__(self, g, q=None):
        self.g = g
        self.q = q or KskQuadrature()
        s = g.wi + g.wr
        ln = np.sqrt((s * s).sum(axis=0))
        self.cos_h, self.cos_ih = s[2] / ln, 0.5 * ln
        # distinct incidence / view cosines (the instrument grid has few)
        self.mu, inv = np.unique(np.concatenate([g.ci, g.cr]), return_inverse=True)
        n = len(g.ci)
        self.idx_i, self.idx_r = inv[:n], inv[n:]


def kelemen_szirmay_kalos(kg, p):
    """Kelemen & Szirmay-Kalos 2001 (report eq. 3.20, section 3.4), Beckmann density:
    f = P_H F(l.h)/(4 (l.h)^2) + rho_d (1 - rho_s(ti))(1 - rho_s(tr)) / (pi (1 - rho_bar)),
    Schlick F with F0 = ((n-1)/(n+1))^2; the albedos by quadrature (KskQuadrature)."""
    rho, alpha, ior = p
    f0 = ((ior - 1.0) / (ior + 1.0)) ** 2
    q = kg.q
    rs = ksk_albedo(q, np.concatenate([kg.mu, q.mu_nodes]), alpha, f0)
    rs_grid, rs_nodes = rs[:len(kg.mu)], rs[len(kg.mu):]
    rho_bar = 2.0 * (q.mu_weights * q.mu_nodes * rs_nodes).sum()
    matte = rho * (1.0 - rs_grid[kg.idx_i]) * (1.0 - rs_grid[kg.idx_r]) / (np.pi * (1.0 - rho_bar))
    return ksk_specular(kg.cos_h, kg.cos_ih, alpha, f0) + matte
