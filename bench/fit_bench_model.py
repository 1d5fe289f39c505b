"""Independent NumPy reimplementation of oren-nayar+torrance-sparrow (roadbrdf defaults: Oren-Nayar
full model; Torrance-Sparrow with GGX, Smith height-correlated masking, exact dielectric Fresnel),
written from the papers' formulas for the fitting benchmark (bench/fit_bench.sh).

Oren & Nayar, SIGGRAPH 1994, eqs. 30 and 37; Walter et al., EGSR 2007, eqs. 20, 33 (GGX D) and the
GGX Smith Lambda (Heitz, JCGT 2014, eq. 72 / 99); Fresnel: Born & Wolf 1.5.2.
Parameters (composite order): on_weight, albedo, sigma [rad], ts_weight, ks, roughness (alpha), ior.
"""
import numpy as np


class Geometry:
    def __init__(self, theta_i, phi_i, theta_r, phi_r):
        """Angles in degrees (arrays)."""
        ti, pi_, tr, pr = (np.radians(np.asarray(a, dtype=float)) for a in (theta_i, phi_i, theta_r, phi_r))
        self.ti, self.tr = ti, tr
        self.phi_i, self.phi_r = pi_, pr
        self.wi = np.stack([np.sin(ti) * np.cos(pi_), np.sin(ti) * np.sin(pi_), np.cos(ti)])
        self.wr = np.stack([np.sin(tr) * np.cos(pr), np.sin(tr) * np.sin(pr), np.cos(tr)])
        self.cdp = np.where((ti > 0) & (tr > 0), np.cos(pr - pi_), 0.0)
        # Oren-Nayar geometry factors
        a = np.maximum(ti, tr)
        b = np.minimum(ti, tr)
        self.alpha, self.beta = a, b
        self.tan_beta = np.tan(b)
        self.sin_alpha = np.sin(a)
        self.two_beta_pi = 2.0 * b / np.pi
        self.tan_half = np.tan(0.5 * (a + b))
        # half vector
        s = self.wi + self.wr
        ln = np.sqrt((s * s).sum(axis=0))
        self.cos_h = s[2] / ln
        self.cos_ih = 0.5 * ln
        self.ci = self.wi[2]
        self.cr = self.wr[2]


def oren_nayar(g, rho, sigma):
    s2 = sigma * sigma
    c = g.cdp
    c1 = 1.0 - 0.5 * s2 / (s2 + 0.33)
    c2b = 0.45 * s2 / (s2 + 0.09)
    c2 = np.where(c >= 0.0, c2b * g.sin_alpha, c2b * (g.sin_alpha - g.two_beta_pi ** 3))
    c3 = 0.125 * s2 / (s2 + 0.09) * (4.0 * g.alpha * g.beta / np.pi ** 2) ** 2
    direct = rho / np.pi * (c1 + c * g.tan_beta * c2 + (1.0 - np.abs(c)) * g.tan_half * c3)
    inter = 0.17 * rho * rho / np.pi * s2 / (s2 + 0.13) * (1.0 - c * g.two_beta_pi ** 2)
    return direct + inter


def fresnel(cos_i, eta):
    cos_i = np.clip(cos_i, 0.0, 1.0)
    sin2_t = (1.0 - cos_i ** 2) / eta ** 2
    cos_t = np.sqrt(np.maximum(0.0, 1.0 - sin2_t))
    rs = ((cos_i - eta * cos_t) / (cos_i + eta * cos_t)) ** 2
    rp = ((eta * cos_i - cos_t) / (eta * cos_i + cos_t)) ** 2
    return np.where(sin2_t >= 1.0, 1.0, 0.5 * (rs + rp))


def torrance_sparrow(g, ks, alpha, ior):
    a2 = alpha * alpha
    t = 1.0 + (a2 - 1.0) * g.cos_h ** 2
    d = np.where(g.cos_h > 0.0, a2 / (np.pi * t * t), 0.0)
    def cos_lambda(c):
        c = np.clip(c, 0.0, 1.0)
        return 0.5 * (np.sqrt(c * c + a2 * np.maximum(0.0, 1.0 - c * c)) - c)
    li, lr = cos_lambda(g.ci), cos_lambda(g.cr)
    den = g.ci * g.cr + g.cr * li + g.ci * lr
    gc = np.where(den > 0.0, 1.0 / np.where(den > 0.0, den, 1.0), 0.0)
    return ks * fresnel(g.cos_ih, ior) * d * gc * 0.25


def composite(g, p):
    on_w, rho, sigma, ts_w, ks, alpha, ior = p
    return on_w * oren_nayar(g, rho, sigma) + ts_w * torrance_sparrow(g, ks, alpha, ior)


def oren_nayar_only(g, p):
    """Oren-Nayar alone (parameters albedo, sigma [rad])."""
    return oren_nayar(g, p[0], p[1])


def h_hapke2002(x, w):
    """Hapke, Icarus 157:523-534 (2002), eq. 13: 1/H = 1 - w x [r0 + (1 - 2 r0 x)/2 ln((1 + x)/x)],
    r0 = (1 - gamma)/(1 + gamma), gamma = sqrt(1 - w); H(0) = 1."""
    gamma = np.sqrt(1.0 - w)
    r0 = (1.0 - gamma) / (1.0 + gamma)
    xs = np.maximum(x, 1e-300)
    inv = 1.0 - w * x * (r0 + 0.5 * (1.0 - 2.0 * r0 * x) * np.log((1.0 + xs) / xs))
    return np.where(x > 0.0, 1.0 / inv, 1.0)


class HapkeGeometry:
    """Geometry-only terms of the Hapke BRDF: mu0, mu, cos g and tan(g/2) (g = phase angle between the
    incident and reflected directions, both pointing away from the surface)."""
    def __init__(self, g):
        self.mu0 = np.maximum(g.ci, 0.0)
        self.mu = np.maximum(g.cr, 0.0)
        self.cos_g = np.clip((g.wi * g.wr).sum(axis=0), -1.0, 1.0)
        s = np.sqrt(((g.wi + g.wr) ** 2).sum(axis=0))
        d = np.sqrt(((g.wi - g.wr) ** 2).sum(axis=0))
        self.tan_half = d / s


def hapke(hg, p):
    """Hapke IMSA BRDF f = r/mu0 = w/(4 pi) /(mu0 + mu) {[1 + B(g)] p(g) + H(mu0) H(mu) - 1} (Hapke, JGR 86,
    1981), SHOE B(g) = B0/(1 + tan(g/2)/h) (Hapke, Icarus 67, 1986), Henyey-Greenstein
    p(g) = (1 - xi^2)/(1 + 2 xi cos g + xi^2)^1.5, H from Hapke (2002). Parameters w, b0, h, xi."""
    w, b0, h, xi = p
    b = b0 * h / (h + hg.tan_half)
    phase = (1.0 - xi * xi) / (1.0 + 2.0 * xi * hg.cos_g + xi * xi) ** 1.5
    hh = h_hapke2002(hg.mu0, w) * h_hapke2002(hg.mu, w)
    return w / (4.0 * np.pi) / (hg.mu0 + hg.mu) * ((1.0 + b) * phase + hh - 1.0)
