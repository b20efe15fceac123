#!/usr/bin/python3
"""Fit the fast model's validity rule (engine/src/model_validity.cpp) to the
comparison report's grid (docs/fast_vs_full.csv).

    expected = A * E(tau, T) * x^p / (x^p + x0^p)

E(tau, T) = 2 / (1 + T) * (1 - exp(-(1 + T) tau)) / (1 - exp(-2 tau)) - 1 is the
hiding excess of single scattering with fully correlated ways in and out
(model_validity.cpp derives it), tau = (1 - T) * coverage / mu the extinction
optical thickness along the refracted beam, T the flake's straight-on
transmittance (0 for metal; the interference and dielectric platelets'
values are computed here as the engine does, at normal incidence and
averaged over 400-700 nm, by a transfer-matrix copy that is checked against
the engine in tests/engine/test_model_validity.cpp only through the fitted
result), and x = d / min(H, ell) with ell = t / (c (1 - T)).

Least squares over all rows (grid and small-flake series) weighted by
1 / (se^2 + floor^2), by a coarse then a fine search over (A, x0, p);
standard library only. Prints the constants, the residuals and the largest
residual (the test's tolerance).

    /usr/bin/python3 tools/compare_report/fit_boundary.py [docs/fast_vs_full.csv]
"""

import cmath
import csv
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from compare_report import BINDER_INDEX, FILM_UM, TYPES  # noqa: E402

MU = math.sqrt(1.0 - (math.sin(math.radians(45.0)) / BINDER_INDEX) ** 2)
# A floor on the weight's error: the rule is a curve, not an interpolation;
# points with a tiny standard error should not dominate the fit.
FLOOR = 0.03


def film_rt(n0, layers, n_sub, wl):
    """Normal-incidence reflectance and transmittance of a thin-film stack
    (characteristic matrices, Born & Wolf 1.6); layers = [(n, d_nm)]."""
    m11, m12, m21, m22 = 1, 0, 0, 1
    for n, d in layers:
        delta = 2 * math.pi * n * d / wl
        c, s = cmath.cos(delta), cmath.sin(delta)
        a11, a12, a21, a22 = c, 1j * s / n, 1j * n * s, c
        m11, m12, m21, m22 = m11 * a11 + m12 * a21, m11 * a12 + m12 * a22, m21 * a11 + m22 * a21, m21 * a12 + m22 * a22
    denom = n0 * m11 + n0 * n_sub * m12 + m21 + n_sub * m22
    r = (n0 * m11 + n0 * n_sub * m12 - m21 - n_sub * m22) / denom
    t = 2 * n0 / denom
    return abs(r) ** 2, (n_sub / n0) * abs(t) ** 2


def platelet_t(kind):
    """Straight-on transmittance at normal incidence, averaged over the
    thickness spreads (5-point Gauss-Hermite per layer) and over 400-700 nm
    weighted by the reflectance."""
    if kind == "mirror":
        return 0.0
    if kind == "interference":
        mica, smica, tio2, stio2, nm, nt = 350, 40, 120, 8, 1.58, 2.65
    else:
        mica, smica, tio2, stio2, nm, nt = 250, 40, 0, 0, 2.0, 2.65
    # Standard-normal nodes (probabilists' Gauss-Hermite, 5 points).
    nodes = [(-2.856970, 0.011257), (-1.355626, 0.222076), (0.0, 0.533333), (1.355626, 0.222076),
             (2.856970, 0.011257)]
    rt_sum = 0.0
    r_sum = 0.0
    for wl in range(400, 701, 10):
        r_mean = 0.0
        t_mean = 0.0
        for zm, wm in nodes:
            for zt, wt in nodes:
                layers = [(nt, tio2 + zt * stio2), (nm, mica + zm * smica), (nt, tio2 + zt * stio2)]
                layers = [(n, d) for n, d in layers if d > 0]
                r, t = film_rt(BINDER_INDEX, layers, BINDER_INDEX, wl)
                r_mean += wm * wt * r
                t_mean += wm * wt * t
        # Weighted by R: the band mean of f is made where the flakes reflect.
        rt_sum += r_mean * t_mean
        r_sum += r_mean
    return rt_sum / r_sum


def excess(tau, T):
    return 2 / (1 + T) * math.expm1(-(1 + T) * tau) / math.expm1(-2 * tau) - 1


def features(row, T):
    c = float(row["volume_fraction"])
    d = float(row["diameter_um"])
    t = TYPES[row["flake_type"]]["thickness_um"]
    tau = (1 - T) * c * FILM_UM / t / MU
    sigma = (1 - T) * c / t
    x = d * max(1 / FILM_UM, sigma)
    return tau, x


def rule(a, x0, p, tau_excess, x):
    return a * tau_excess * x**p / (x**p + x0**p)


def fit(rows):
    """Least-squares constants (A, x0, p) over the grid rows; coarse then fine search."""
    T = {k: platelet_t(k) for k in TYPES}
    data = []
    for r in rows:
        tau, x = features(r, T[r["flake_type"]])
        data.append((excess(tau, T[r["flake_type"]]), x, float(r["weighted_rel"]), float(r["weighted_rel_se"])))

    def cost(a, x0, p):
        return sum((rule(a, x0, p, e, x) - y) ** 2 / (se**2 + FLOOR**2) for e, x, y, se in data)

    best = min((cost(a, x0, p), a, x0, p) for a in [0.5 + 0.1 * i for i in range(16)]
               for x0 in [0.25 * i for i in range(1, 33)] for p in [0.4 + 0.2 * i for i in range(14)])
    _, a0, x00, p0 = best
    best = min((cost(a, x0, p), a, x0, p) for a in [a0 - 0.1 + 0.01 * i for i in range(21)]
               for x0 in [max(0.01, x00 - 0.25 + 0.025 * i) for i in range(21)]
               for p in [max(0.1, p0 - 0.2 + 0.02 * i) for i in range(21)])
    return {"chi2": best[0], "A": best[1], "x0": best[2], "p": best[3], "T": T}


def predict(constants, kind, diameter_um, volume_fraction):
    T = constants["T"][kind]
    row = {"flake_type": kind, "diameter_um": diameter_um, "volume_fraction": volume_fraction}
    tau, x = features(row, T)
    return rule(constants["A"], constants["x0"], constants["p"], excess(tau, T), x)


def main():
    path = Path(sys.argv[1]) if len(sys.argv) > 1 else HERE.parent.parent / "docs" / "fast_vs_full.csv"
    # The grid and the small-flake series: the latter pins the rule where the
    # 10 % boundary falls for dense flakes (diameters of 1-2 µm).
    rows = list(csv.DictReader(open(path, encoding="utf-8")))
    k = fit(rows)
    print("flake transmittance (400-700 nm mean):", {t: round(v, 4) for t, v in k["T"].items()})
    print(f"A = {k['A']:.3f}, x0 = {k['x0']:.3f}, p = {k['p']:.2f}, chi2 = {k['chi2']:.1f} over {len(rows)} points")
    worst = 0.0
    for r in rows:
        model = predict(k, r["flake_type"], float(r["diameter_um"]), float(r["volume_fraction"]))
        y, se = float(r["weighted_rel"]), float(r["weighted_rel_se"])
        worst = max(worst, abs(model - y))
        print(f"{r['flake_type']:12s} d {float(r['diameter_um']):4g} c {float(r['volume_fraction']):5g} "
              f"s {float(r['spread_deg']):3g}: measured {100 * y:+6.1f} +- {100 * se:4.1f} %, rule {100 * model:6.1f} %,"
              f" residual {100 * (model - y):+6.1f} %")
    print(f"largest |residual| {100 * worst:.1f} %")


if __name__ == "__main__":
    main()
