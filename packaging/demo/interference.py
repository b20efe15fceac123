"""Interference colour of a TiO2 / mica / TiO2 flake, to name a pearl pigment.

Only a design aid for the demo recipes (the engine computes the real thing,
at every angle and both polarisations): normal-incidence reflectance of the
flake embedded in the binder, by the characteristic-matrix method (Born &
Wolf, Principles of Optics, sec. 1.6), averaged over Gaussian thickness
spreads; its colour as CIELAB under D65 with the CIE 1931 2° observer.

The observer uses the multi-lobe Gaussian fit of Wyman, Sloan & Shirley,
"Simple Analytic Approximations to the CIE XYZ Color Matching Functions",
JCGT 2(2), 2013 (error well below what naming a hue needs); D65 is the CIE
table (CIE 015:2018) at 10 nm from 380 to 780 nm.
"""

import cmath
import math

WAVELENGTHS_NM = list(range(380, 781, 10))

# CIE standard illuminant D65, relative SPD, 380..780 nm every 10 nm.
D65 = [49.9755, 54.6482, 82.7549, 91.486, 93.4318, 86.6823, 104.865, 117.008, 117.812, 114.861, 115.923,
       108.811, 109.354, 107.802, 104.79, 107.689, 104.405, 104.046, 100.0, 96.3342, 95.788, 88.6856,
       90.0062, 89.5991, 87.6987, 83.2886, 83.6992, 80.0268, 80.2146, 82.2778, 78.2842, 69.7213, 71.6091,
       74.349, 61.604, 69.8856, 75.087, 63.5927, 46.4182, 66.8054, 63.3828]


def _lobe(lam, mu, s1, s2):
    t = (lam - mu) / (s1 if lam < mu else s2)
    return math.exp(-0.5 * t * t)


def cmf_1931(lam):
    """CIE 1931 2° colour matching functions (Wyman et al. 2013 fit)."""
    x = 1.056 * _lobe(lam, 599.8, 37.9, 31.0) + 0.362 * _lobe(lam, 442.0, 16.0, 26.7) \
        - 0.065 * _lobe(lam, 501.1, 20.4, 26.2)
    y = 0.821 * _lobe(lam, 568.8, 46.9, 40.5) + 0.286 * _lobe(lam, 530.9, 16.3, 31.1)
    z = 1.217 * _lobe(lam, 437.0, 11.8, 36.0) + 0.681 * _lobe(lam, 459.0, 26.0, 13.8)
    return x, y, z


def lab_d65(reflectance):
    """CIELAB (L*, C*ab, h_ab in degrees) of a reflectance on WAVELENGTHS_NM."""
    xyz = [0.0, 0.0, 0.0]
    white = [0.0, 0.0, 0.0]
    for lam, s, r in zip(WAVELENGTHS_NM, D65, reflectance):
        cmf = cmf_1931(lam)
        for i in range(3):
            xyz[i] += s * cmf[i] * r
            white[i] += s * cmf[i]

    def f(t):
        return t ** (1.0 / 3.0) if t > (6.0 / 29.0) ** 3 else t / (3.0 * (6.0 / 29.0) ** 2) + 4.0 / 29.0

    fx, fy, fz = (f(xyz[i] / white[i]) for i in range(3))
    L, a, b = 116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)
    return L, math.hypot(a, b), math.degrees(math.atan2(b, a)) % 360.0


def hue_name(chroma, hue_deg):
    """A plain colour word for a CIELAB hue angle (coarse, for descriptions)."""
    if chroma < 8.0:
        return "silver-white"
    for limit, name in ((15, "magenta"), (45, "red"), (70, "orange"), (105, "gold"), (135, "yellow-green"),
                        (180, "green"), (225, "turquoise"), (290, "blue"), (330, "violet")):
        if hue_deg < limit:
            return name
    return "magenta"


def stack_reflectance(n_outer, layers, wavelength_nm):
    """Normal-incidence reflectance of thin layers [(index, thickness_nm), ...]
    between two half-spaces of index n_outer (characteristic matrices)."""
    m11, m12, m21, m22 = 1.0 + 0j, 0j, 0j, 1.0 + 0j
    for n, d in layers:
        delta = 2.0 * math.pi * n * d / wavelength_nm
        c, s = cmath.cos(delta), cmath.sin(delta)
        a11, a12, a21, a22 = c, 1j * s / n, 1j * n * s, c
        m11, m12, m21, m22 = m11 * a11 + m12 * a21, m11 * a12 + m12 * a22, m21 * a11 + m22 * a21, m21 * a12 + m22 * a22
    b = m11 + m12 * n_outer
    cc = m21 + m22 * n_outer
    r = (n_outer * b - cc) / (n_outer * b + cc)
    return abs(r) ** 2


def _gauss_nodes(mean, sd, count=13):
    """Equally spaced nodes over +-2.5 sd with normalised Gaussian weights."""
    if sd <= 0.0:
        return [(mean, 1.0)]
    nodes = [mean + sd * (-2.5 + 5.0 * i / (count - 1)) for i in range(count)]
    weights = [math.exp(-0.5 * ((t - mean) / sd) ** 2) for t in nodes]
    total = sum(weights)
    return [(t, w / total) for t, w in zip(nodes, weights) if t > 0.0]


def flake_reflectance(n_binder, n_tio2, n_mica, mica_nm, mica_sd_nm, tio2_nm, tio2_sd_nm):
    """Mean normal-incidence reflectance spectrum of TiO2/mica/TiO2 flakes
    (both coatings of one flake equally thick), n_* are callables of nm."""
    out = []
    for lam in WAVELENGTHS_NM:
        nb, nt, nm = n_binder(lam), n_tio2(lam), n_mica(lam)
        total = 0.0
        for dm, wm in _gauss_nodes(mica_nm, mica_sd_nm):
            for dt, wt in _gauss_nodes(tio2_nm, tio2_sd_nm):
                total += wm * wt * stack_reflectance(nb, [(nt, dt), (nm, dm), (nt, dt)], lam)
        out.append(total)
    return out
