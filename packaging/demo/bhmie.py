"""Mie scattering by a homogeneous sphere, after Bohren & Huffman's BHMIE.

C. F. Bohren, D. R. Huffman, Absorption and Scattering of Light by Small
Particles (Wiley 1983), Appendix A: the logarithmic derivative
D_n(mx) by downward recurrence, the Riccati-Bessel functions psi_n, chi_n
by upward recurrence, the coefficients a_n, b_n (eq. 4.88), and the
efficiencies (eqs. 4.61, 4.62) and asymmetry parameter (eq. 4.80).
Time dependence exp(-iwt): an absorbing medium has m = n + ik with k > 0.
Pure Python (complex arithmetic), no numpy.
"""

import math


def bhmie(x, m):
    """Efficiencies of a sphere of size parameter x = 2 pi a / lambda (lambda in
    the surrounding medium) and relative index m (complex, relative to that
    medium). Returns (q_ext, q_sca, q_back, g)."""
    if not x > 0.0:
        raise ValueError("size parameter must be positive")
    m = complex(m)
    y = m * x
    x_stop = x + 4.0 * x ** (1.0 / 3.0) + 2.0
    n_stop = int(x_stop)
    n_max = int(max(x_stop, abs(y))) + 15

    # D_n(y) = psi_n'(y)/psi_n(y), downward from D_{n_max} = 0 (stable).
    d = [0j] * (n_max + 1)
    for n in range(n_max - 1, 0, -1):
        en = n + 1
        d[n] = en / y - 1.0 / (d[n + 1] + en / y)

    psi0, psi1 = math.cos(x), math.sin(x)
    chi0, chi1 = -math.sin(x), math.cos(x)
    xi1 = complex(psi1, -chi1)
    q_sca = 0.0
    g_sum = 0.0
    ext_sum = 0.0
    back_sum = 0j
    an_prev = bn_prev = 0j
    for n in range(1, n_stop + 1):
        psi = (2.0 * n - 1.0) * psi1 / x - psi0
        chi = (2.0 * n - 1.0) * chi1 / x - chi0
        xi = complex(psi, -chi)
        da = d[n] / m + n / x
        db = d[n] * m + n / x
        an = (da * psi - psi1) / (da * xi - xi1)
        bn = (db * psi - psi1) / (db * xi - xi1)
        w = 2.0 * n + 1.0
        q_sca += w * (abs(an) ** 2 + abs(bn) ** 2)
        ext_sum += w * (an + bn).real
        back_sum += w * (-1.0) ** n * (an - bn)
        # Asymmetry: B&H eq. 4.80 (sum over n of the two cross terms).
        g_sum += (w / (n * (n + 1.0))) * (an.real * bn.real + an.imag * bn.imag)
        if n > 1:
            g_sum += ((n - 1.0) * (n + 1.0) / n) * (
                an_prev.real * an.real + an_prev.imag * an.imag + bn_prev.real * bn.real + bn_prev.imag * bn.imag)
        an_prev, bn_prev = an, bn
        psi0, psi1 = psi1, psi
        chi0, chi1 = chi1, chi
        xi1 = complex(psi1, -chi1)

    g = 2.0 * g_sum / q_sca if q_sca > 0.0 else 0.0
    q_sca *= 2.0 / (x * x)
    q_ext = 2.0 / (x * x) * ext_sum
    q_back = abs(back_sum) ** 2 / (x * x)
    return q_ext, q_sca, q_back, g


def rayleigh(x, m):
    """Small-sphere limit (B&H eqs. 5.8, 5.9): (q_abs, q_sca)."""
    alpha = (m * m - 1.0) / (m * m + 2.0)
    return 4.0 * x * alpha.imag, 8.0 / 3.0 * x ** 4 * abs(alpha) ** 2


def sphere_coefficients(wavelength_nm, diameter_um, n_particle, n_binder):
    """Absorption and scattering per unit volume fraction (1/µm) and g for
    monodisperse spheres in a binder, independent scattering:
    sigma/c = C/V = Q * pi a^2 / (4/3 pi a^3) = 3 Q / (2 d)."""
    lam_medium_um = wavelength_nm / 1000.0 / n_binder
    x = math.pi * diameter_um / lam_medium_um
    q_ext, q_sca, _, g = bhmie(x, complex(n_particle) / n_binder)
    # A real index absorbs nothing; q_ext - q_sca would only carry round-off.
    q_abs = max(q_ext - q_sca, 0.0) if complex(n_particle).imag != 0.0 else 0.0
    scale = 3.0 / (2.0 * diameter_um)
    return scale * q_abs, scale * q_sca, g
