#!/usr/bin/env python3
"""Reference values for tests/sediment/test_published_parameter_sets.cpp.

Each model is evaluated here at 40 significant digits with mpmath (1.3), directly in the form and
the time convention of its source paper, sharing no code with sediment/:

  Biot-Stoll  Stoll's two equations of motion (R. D. Stoll, Sediment Acoustics, Springer 1989,
              ch. 2; Stoll & Kan, J. Acoust. Soc. Am. 70, 149 (1981)) for fields exp(i(w t - l x)),
              solved as the 2x2 determinant in l^2, with the frame moduli K_b (1 + i delta_b/pi),
              mu (1 + i delta_s/pi) and Biot's viscous correction F(kappa) from mpmath's Kelvin
              functions (M. A. Biot, J. Acoust. Soc. Am. 28, 179 (1956)).
  EDFM        the same determinant with K_b = mu = 0 (K. L. Williams, J. Acoust. Soc. Am. 110,
              2276 (2001)).
  GS, VGS(l)  k_p = (w/c0) [1 + (gamma_p + 4/3 gamma_s)/(rho0 c0^2) Psi]^(-1/2) for
              exp(i(w t - k x)) (M. J. Buckingham, J. Acoust. Soc. Am. 108, 2796 (2000); 117, 137
              (2005); 127, 2099 (2010)).

A wave exp(i(w t - l x)) that decays along +x has Im l < 0: attenuation = -Im l [Np/m], speed =
w / Re l [m/s]. The library uses exp(i(k x - w t)); the two must agree on both numbers.

Run: python3 tests/sediment/independent_reference.py
"""
import mpmath as mp

mp.mp.dps = 40
PI = mp.pi


def biot_f(kappa):
    """Biot's F(kappa) = (kappa/4) T / (1 - 2T/(i kappa)), T = (ber' + i bei') / (ber + i bei)."""
    k = mp.mpf(kappa)
    ber, bei = mp.ber(0, k), mp.bei(0, k)
    dber = mp.diff(lambda x: mp.ber(0, x), k)
    dbei = mp.diff(lambda x: mp.bei(0, x), k)
    t = (dber + 1j * dbei) / (ber + 1j * bei)
    return (k / 4) * t / (1 - 2 * t / (1j * k))


def stoll_fast_wave(p, f):
    """Fast compressional wave of Stoll's Biot medium: (attenuation Np/m, speed m/s)."""
    w = 2 * PI * mp.mpf(f)
    beta, rho_s, k_s, rho_f, k_f = (mp.mpf(p[n]) for n in ("porosity", "rho_s", "K_s", "rho_w", "K_w"))
    eta, perm, alpha, a = (mp.mpf(p[n]) for n in ("eta", "permeability", "tortuosity", "pore_size"))
    k_b = mp.mpf(p["K_b"]) * (1 + 1j * mp.mpf(p["delta_b"]) / PI)
    mu = mp.mpf(p["mu"]) * (1 + 1j * mp.mpf(p["delta_s"]) / PI)
    d = k_s * (1 + beta * (k_s / k_f - 1))
    h = (k_s - k_b) ** 2 / (d - k_b) + k_b + mp.mpf(4) / 3 * mu
    c = k_s * (k_s - k_b) / (d - k_b)
    m_mod = k_s**2 / (d - k_b)
    rho = beta * rho_f + (1 - beta) * rho_s
    m = alpha * rho_f / beta
    kappa = a * mp.sqrt(w * rho_f / eta)
    drag = 1j * w * biot_f(kappa) * eta / perm
    # det [[H L - rho w^2, rho_f w^2 - C L], [C L - rho_f w^2, m w^2 - drag - M L]] = 0, L = l^2.
    qa = -h * m_mod + c * c
    qb = h * (m * w**2 - drag) + rho * w**2 * m_mod - 2 * c * rho_f * w**2
    qc = -rho * w**2 * (m * w**2 - drag) + rho_f**2 * w**4
    if abs(qa) == 0:
        roots = [-qc / qb]
    else:
        disc = mp.sqrt(qb * qb - 4 * qa * qc)
        roots = [(-qb + disc) / (2 * qa), (-qb - disc) / (2 * qa)]
    fast = min(roots, key=abs)  # the fast wave has the smaller wavenumber
    l = mp.sqrt(fast)
    if mp.re(l) < 0:
        l = -l
    return -mp.im(l), w / mp.re(l)


def grain_shearing_wave(p, f, tau_p=None):
    """Buckingham's compressional wave: (attenuation Np/m, speed m/s)."""
    w = 2 * PI * mp.mpf(f)
    n_por, rho_s, rho_w, k_s, k_w = (mp.mpf(p[n]) for n in ("porosity", "rho_s", "rho_w", "K_s", "K_w"))
    rho0 = n_por * rho_w + (1 - n_por) * rho_s
    k0 = 1 / (n_por / k_w + (1 - n_por) / k_s)
    c0 = mp.sqrt(k0 / rho0)
    n = mp.mpf(p["n"])
    psi = (1j * w) ** n  # T = 1 s
    if tau_p is not None:
        psi *= (1 + 1 / (1j * w * mp.mpf(tau_p))) ** (n - 1)
    chi = (mp.mpf(p["gamma_p"]) + mp.mpf(4) / 3 * mp.mpf(p["gamma_s"])) / (rho0 * c0**2)
    factor = (1 + chi * psi) ** mp.mpf(-0.5)
    return -w / c0 * mp.im(factor), c0 / mp.re(factor)


# SAX99 medium sand. Mixture: porosity, densities and bulk moduli as Buckingham (2010) uses them for
# SAX99. Pore space and frame: permeability 2.5e-11 m^2, tortuosity 1.35, frame moduli 4.36e7 Pa and
# 2.92e7 Pa with loss 2.08e6 / 4.36e7 = 1.38e6 / 2.92e7 = 0.0477 = delta/pi (delta = 0.15), the values
# quoted for SAX99 after Williams et al. (2002); pore size a = sqrt(8 alpha k / beta) = 2.65e-5 m
# (a bundle of tubes with the same permeability and tortuosity).
SAX99 = {
    "porosity": "0.385", "rho_s": "2690", "K_s": "3.2e10", "rho_w": "1023", "K_w": "2.395e9",
    "eta": "1.0e-3", "permeability": "2.5e-11", "tortuosity": "1.35",
    "K_b": "4.36e7", "mu": "2.92e7", "delta_b": "0.15", "delta_s": "0.15",
}
SAX99["pore_size"] = mp.nstr(mp.sqrt(8 * mp.mpf("1.35") * mp.mpf("2.5e-11") / mp.mpf("0.385")), 6)
SAX99_EDFM = dict(SAX99, K_b="0", mu="0", delta_b="0", delta_s="0")

# Buckingham (2005) reference sediment, the GS defaults.
GS_2005 = {"porosity": "0.377", "rho_s": "2730", "rho_w": "1005", "K_s": "3.6e10", "K_w": "2.374e9",
           "gamma_p": "3.888e8", "gamma_s": "4.588e7", "n": "0.0851"}
# Buckingham (2010) SAX99, the VGS(lambda) defaults.
VGS_2010 = {"porosity": "0.385", "rho_s": "2690", "rho_w": "1023", "K_s": "3.2e10", "K_w": "2.395e9",
            "gamma_p": "3.796e8", "gamma_s": "1.711e7", "n": "0.0617"}
VGS_TAU_P = "1.2e-4"

FREQUENCIES = ["100", "1e3", "1e4", "1e5", "4e5"]


def row(f, wave):
    alpha, c = wave
    return "    {%s, %s, %s}," % (f, mp.nstr(alpha, 17, min_fixed=-3, max_fixed=0), mp.nstr(c, 17))


if __name__ == "__main__":
    print("pore size a [m] =", SAX99["pore_size"])
    for name, fn in (("Biot-Stoll SAX99", lambda f: stoll_fast_wave(SAX99, f)),
                     ("EDFM SAX99", lambda f: stoll_fast_wave(SAX99_EDFM, f)),
                     ("GS Buckingham 2005", lambda f: grain_shearing_wave(GS_2005, f)),
                     ("VGS(lambda) Buckingham 2010", lambda f: grain_shearing_wave(VGS_2010, f, VGS_TAU_P))):
        print("//", name, ": {frequency [Hz], attenuation [Np/m], speed [m/s]}")
        for f in FREQUENCIES:
            print(row(f, fn(f)))
