#!/usr/bin/env python3
"""Generate PaintLab's bundled demo recipes from published optical constants.

Reads refractiveindex.info material files (CC0) from the shared data folder,
samples them at 380..780 nm every 10 nm, derives pigment absorption and
scattering per unit volume fraction with Mie theory (bhmie.py), and writes
recipe JSON files (schema_version 1) to packaging/demo/recipes/.
Standard library only; the output is deterministic (same inputs, same bytes).

    python3 packaging/demo/make_demo_recipes.py [--data DIR] [--out DIR]

See packaging/demo/README.md for what each recipe is and where its
numbers come from.
"""

import argparse
import json
import math
import os
import sys
from pathlib import Path

sys.dont_write_bytecode = True  # leave no __pycache__ in the source tree
from bhmie import bhmie, rayleigh, sphere_coefficients
from interference import flake_reflectance, hue_name, lab_d65
from optical_constants import Material

HERE = Path(__file__).resolve().parent
DEFAULT_DATA = HERE.parent.parent.parent / "shared" / "data" / "optical-constants"
WAVELENGTHS_NM = list(range(380, 781, 10))  # 41 bands, the engine's colorimetric grid
SIGNIFICANT_DIGITS = 5
MIE = "Mie theory for monodisperse spheres (Bohren & Huffman 1983, BHMIE algorithm), independent scattering"

FILES = {
    "pmma": "organic__C5H8O2n_-_polymethyl_methacrylate__nk__Sultanova.yml",
    "pmma_beadie": "organic__C5H8O2n_-_polymethyl_methacrylate__nk__Beadie.yml",
    "hematite_o": "main__Fe2O3__nk__Querry-o.yml",
    "hematite_e": "main__Fe2O3__nk__Querry-e.yml",
    "aluminium": "main__Al__nk__Rakic.yml",
    "carbon": "main__C__nk__Hagemann.yml",
    "rutile_o": "main__TiO2__nk__Devore-o.yml",
    "rutile_e": "main__TiO2__nk__Devore-e.yml",
}

MICA_INDEX = 1.58  # muscovite, handbook value (the database has no mica file)


# ---------------------------------------------------------------- numbers


def sig(value, digits=SIGNIFICANT_DIGITS):
    """Round to significant digits; integers stay integers."""
    if isinstance(value, int):
        return value
    if value == 0.0:
        return 0.0
    return float(f"{value:.{digits}g}")


def spectrum(values):
    """A recipe spectrum on the 41-band grid (a plain number if constant)."""
    rounded = [sig(v) for v in values]
    if all(v == rounded[0] for v in rounded):
        return rounded[0]
    return {"wavelengths_nm": WAVELENGTHS_NM, "values": rounded}


def to_json(obj, level=0):
    """JSON with two-space indentation and number arrays on one line."""
    pad, inner = "  " * level, "  " * (level + 1)
    if isinstance(obj, dict):
        items = [f"{inner}{json.dumps(k)}: {to_json(v, level + 1)}" for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}" if items else "{}"
    if isinstance(obj, list):
        if all(isinstance(v, (int, float)) for v in obj):
            return "[" + ", ".join(to_json(v) for v in obj) + "]"
        return "[\n" + ",\n".join(inner + to_json(v, level + 1) for v in obj) + "\n" + pad + "]"
    if isinstance(obj, bool) or obj is None:
        return json.dumps(obj)
    if isinstance(obj, float):
        if not math.isfinite(obj):
            raise ValueError("non-finite number in a recipe")
        return repr(obj)
    if isinstance(obj, int):
        return str(obj)
    return json.dumps(obj, ensure_ascii=False)


# ---------------------------------------------------------------- checks


def mie_self_check():
    """Compare bhmie() with published values; returns False on a mismatch."""
    cases = [
        # (label, x, m, reference (q_ext, q_sca, q_back or None, g or None))
        ("Bohren & Huffman 1983 App. A: m=1.55, x=2*pi*0.525/0.6328=5.2128",
         2.0 * math.pi * 0.525 / 0.6328, 1.55, (3.10543, 3.10543, 2.92534, None)),
        ("Wiscombe 1979 (NCAR TN-140): m=1.5, x=10", 10.0, 1.5, (2.881999, 2.881999, None, 0.742913)),
        ("Wiscombe 1979: m=1.5+0.1i, x=10", 10.0, 1.5 + 0.1j, (2.459791, 1.235144, None, 0.922350)),
        ("Wiscombe 1979: m=1.5+0.1i, x=100", 100.0, 1.5 + 0.1j, (2.089822, 1.132134, None, 0.950392)),
    ]
    ok = True
    print("Mie check (bhmie.py against published values):")
    for label, x, m, ref in cases:
        got = bhmie(x, m)
        names = ("Qext", "Qsca", "Qback", "g")
        parts = []
        for name, value, expected in zip(names, got, ref):
            if expected is None:
                continue
            good = abs(value - expected) <= 2e-5 * max(1.0, abs(expected))
            ok &= good
            parts.append(f"{name} {value:.6f} (ref {expected}){'' if good else ' MISMATCH'}")
        print(f"  {label}: " + ", ".join(parts))
    for x in (0.01, 0.05):
        m = 1.75 + 0.7j
        q_ext, q_sca, _, _ = bhmie(x, m)
        r_abs, r_sca = rayleigh(x, m)
        good = abs((q_ext - q_sca) / r_abs - 1.0) < 0.01 and abs(q_sca / r_sca - 1.0) < 0.01
        ok &= good
        print(f"  Rayleigh limit (agrees to O(x²)) m={m}, x={x}: Qabs {q_ext - q_sca:.6e} vs 4x Im((m²-1)/(m²+2)) {r_abs:.6e}, "
              f"Qsca {q_sca:.6e} vs 8/3 x⁴|(m²-1)/(m²+2)|² {r_sca:.6e}{'' if good else ' MISMATCH'}")
    return ok


# ---------------------------------------------------------------- ingredients


def load_materials(data_dir):
    materials = {}
    for key, name in FILES.items():
        path = data_dir / name
        if not path.is_file():
            sys.exit(f"error: {path} not found (use --data to point at the optical-constants folder)")
        materials[key] = Material(path)
    return materials


def cite(material):
    return f"{material.reference} [refractiveindex.info {material.database_path}]"


def extrapolation_note(material):
    """Say where a formula is used outside its stated wavelength range."""
    outside = material.outside_range(WAVELENGTHS_NM)
    if not outside:
        return ""
    lo, hi = material.range_um
    kind = "formula extrapolated" if material.kinds[0].startswith("formula") else "data held constant"
    below = [w for w in outside if w < lo * 1000.0]
    above = [w for w in outside if w > hi * 1000.0]
    sides = ([f"below {lo * 1000:g} nm"] if below else []) + ([f"above {hi * 1000:g} nm"] if above else [])
    return f"{kind} {' and '.join(sides)}"


class Binder:
    """Refractive index of the cured binder on the grid; PMMA as a proxy."""

    def __init__(self, material):
        self.material = material
        self.n = [material.n(w) for w in WAVELENGTHS_NM]

    def __call__(self, wavelength_nm):
        return self.material.n(wavelength_nm)

    def json(self, name):
        return {"name": name, "refractive_index": spectrum(self.n), "absorption_per_um": 0.0}


def mie_pigment(variants, diameter_um, binder):
    """Per-unit-volume-fraction sigma_a, sigma_s (1/µm) and g at 550 nm of
    spheres; `variants` = [(material, weight)] averages the cross sections of
    a uniaxial crystal's ordinary and extraordinary indices (randomly
    oriented grains: 2/3 o + 1/3 e)."""
    sigma_a, sigma_s, g_all = [], [], []
    for w in WAVELENGTHS_NM:
        sa = ss = gs = 0.0
        for material, weight in variants:
            a, s, g = sphere_coefficients(w, diameter_um, material.nk(w), binder(w))
            sa += weight * a
            ss += weight * s
            gs += weight * s * g
        sigma_a.append(sa)
        sigma_s.append(ss)
        g_all.append(gs / ss)
    return sigma_a, sigma_s, g_all[WAVELENGTHS_NM.index(550)], g_all


def pigment(name, source, volume_fraction, coefficients, diameter_um):
    sigma_a, sigma_s, g550, _ = coefficients
    return {
        "kind": "pigment", "name": name, "source": source, "volume_fraction": volume_fraction,
        "sigma_a_per_um": spectrum(sigma_a), "sigma_s_per_um": spectrum(sigma_s),
        "hg_g": sig(g550, 4), "particle_diameter_um": diameter_um,
    }


def interference_flake(name, source, volume_fraction, diameter_um, spread_deg, mica_nm, mica_sd_nm, tio2_nm,
                       tio2_sd_nm, rutile):
    return {
        "kind": "interference_flake", "name": name, "source": source, "volume_fraction": volume_fraction,
        "diameter_um": diameter_um, "orientation_spread_deg": spread_deg,
        "mica_thickness_nm": mica_nm, "mica_thickness_spread_nm": mica_sd_nm,
        "tio2_thickness_nm": tio2_nm, "tio2_thickness_spread_nm": tio2_sd_nm,
        "mica_refractive_index": MICA_INDEX,
        "tio2_refractive_index": spectrum([rutile.n(w) for w in WAVELENGTHS_NM]),
    }


def pearl_colour(binder, rutile, mica_nm, mica_sd_nm, tio2_nm, tio2_sd_nm):
    """Colour word, CIELAB and reflectance peak of the flake at normal incidence."""
    reflectance = flake_reflectance(binder, rutile.n, lambda w: MICA_INDEX, mica_nm, mica_sd_nm, tio2_nm, tio2_sd_nm)
    L, C, h = lab_d65(reflectance)
    peak = WAVELENGTHS_NM[reflectance.index(max(reflectance))]
    return hue_name(C, h), (L, C, h), peak, max(reflectance)


def lambertian(albedo):
    return {"kind": "lambertian", "albedo": albedo}


def clear_coat(binder, thickness_um=40):
    return {"name": "clear coat", "thickness_um": thickness_um,
            "binder": binder.json("acrylic clear coat (PMMA index as proxy)"), "components": []}


# ---------------------------------------------------------------- recipes


def build_recipes(mat):
    binder = Binder(mat["pmma"])
    binder_note = (f"Binder index: PMMA (Sultanova et al. 2009, refractiveindex.info {mat['pmma'].database_path}; "
                   f"{extrapolation_note(mat['pmma'])}) as a proxy for an acrylic or polyurethane film.")
    rutile = mat["rutile_o"]
    recipes = {}
    report = []

    # Pigments by Mie theory.
    d_hem, d_cb, d_tio2 = 0.25, 0.04, 0.23
    hematite = mie_pigment([(mat["hematite_o"], 2.0 / 3.0), (mat["hematite_e"], 1.0 / 3.0)], d_hem, binder)
    carbon = mie_pigment([(mat["carbon"], 1.0)], d_cb, binder)
    white = mie_pigment([(mat["rutile_o"], 2.0 / 3.0), (mat["rutile_e"], 1.0 / 3.0)], d_tio2, binder)
    hem_source = (f"{MIE}, d={d_hem} µm in the PMMA-index binder, from the hematite (alpha-Fe2O3) n,k of "
                  f"{cite(mat['hematite_o'])} and its extraordinary-ray file Querry-e.yml, cross sections averaged "
                  "2/3 ordinary + 1/3 extraordinary (randomly oriented uniaxial grains); hg_g = Mie asymmetry "
                  "parameter at 550 nm")
    cb_source = (f"{MIE}, d={d_cb} µm primary particles (carbon black) in the PMMA-index binder, from the carbon "
                 f"n,k of {cite(mat['carbon'])} as a carbon-black proxy; hg_g = Mie asymmetry parameter at 550 nm")
    white_source = (f"{MIE}, d={d_tio2} µm (pigmentary rutile) in the PMMA-index binder, from the rutile TiO2 "
                    f"dispersion formulas of {cite(mat['rutile_o'])} and Devore-e.yml, cross sections averaged "
                    "2/3 ordinary + 1/3 extraordinary; k = 0 (the source gives n only, so the absorption edge "
                    f"below ~410 nm is missing), {extrapolation_note(rutile)}; hg_g = Mie asymmetry parameter at 550 nm")
    for label, coeff, d in (("hematite", hematite, d_hem), ("carbon black", carbon, d_cb),
                            ("rutile white", white, d_tio2)):
        i450, i550, i650 = (WAVELENGTHS_NM.index(w) for w in (450, 550, 650))
        report.append(f"  {label:13s} d={d} µm: sigma_a/c = {coeff[0][i450]:.4g}, {coeff[0][i550]:.4g}, "
                      f"{coeff[0][i650]:.4g} 1/µm; sigma_s/c = {coeff[1][i450]:.4g}, {coeff[1][i550]:.4g}, "
                      f"{coeff[1][i650]:.4g} 1/µm (450, 550, 650 nm); g(550) = {coeff[2]:.3f} "
                      f"(g range {min(coeff[3]):.3f}-{max(coeff[3]):.3f})")

    grey_primer = lambertian(0.3)
    primer_note = ("The primer is a nominal flat grey (Lambertian albedo 0.30), not a measured one.")
    thickness_note = ("Film builds are typical automotive values (basecoat 12-25 µm, clear coat 35-50 µm; "
                      "Streitberger & Dössel, Automotive Paints and Coatings, 2008).")

    # 1. Solid red: hematite basecoat under a clear coat.
    c_hem = 0.10
    recipes["solid-red.json"] = {
        "schema_version": 1,
        "name": "Solid red (iron oxide)",
        "description": (
            "A solid (pigment-only) red: 25 µm basecoat of iron-oxide red (hematite, alpha-Fe2O3, 10 % by volume, "
            f"0.25 µm grains) under a 40 µm clear coat, on a grey primer. Pigment absorption and scattering come "
            f"from Mie theory applied to the measured n,k of hematite (Querry 1985). {binder_note} "
            f"{thickness_note} {primer_note} Generated by packaging/demo/make_demo_recipes.py."),
        "ambient": {"refractive_index": 1.0},
        "layers": [
            clear_coat(binder),
            {"name": "basecoat", "thickness_um": 25, "binder": binder.json("acrylic basecoat (PMMA index as proxy)"),
             "components": [pigment("iron oxide red (hematite)", hem_source, c_hem, hematite, d_hem)]},
        ],
        "substrate": grey_primer,
    }

    # 2. Silver metallic: aluminium flakes.
    al = mat["aluminium"]
    al_source = (f"Aluminium n,k of {cite(al)}, interpolated linearly to 380-780 nm every 10 nm; flake size, "
                 "thickness and loading typical of cornflake/silver-dollar aluminium pigments "
                 "(Wissling, Metallic Effect Pigments, 2006)")
    c_al, t_al, base_al = 0.04, 0.3, 15
    recipes["silver-metallic.json"] = {
        "schema_version": 1,
        "name": "Silver metallic (aluminium flakes)",
        "description": (
            f"A silver metallic: 15 µm basecoat with aluminium flakes (18 µm across, 0.3 µm thick, 4 % by volume, "
            f"12° orientation spread, about {c_al * base_al / t_al:.1f} flake layers of coverage) under a 40 µm "
            f"clear coat, on a grey primer. Flake reflectance follows from the complex index of evaporated "
            f"aluminium (Rakić 1995) via Fresnel. {binder_note} {thickness_note} {primer_note} "
            "Generated by packaging/demo/make_demo_recipes.py."),
        "ambient": {"refractive_index": 1.0},
        "layers": [
            clear_coat(binder),
            {"name": "basecoat", "thickness_um": base_al,
             "binder": binder.json("acrylic basecoat (PMMA index as proxy)"),
             "components": [{
                 "kind": "mirror_flake", "name": "aluminium flakes", "source": al_source,
                 "volume_fraction": c_al, "diameter_um": 18, "thickness_um": t_al, "orientation_spread_deg": 12,
                 "n": spectrum([al.n(w) for w in WAVELENGTHS_NM]),
                 "k": spectrum([al.k(w) for w in WAVELENGTHS_NM])}]},
        ],
        "substrate": grey_primer,
    }

    # 3. Two-layer pearlescent: blue interference pearl over carbon black.
    pearl = dict(mica_nm=350, mica_sd_nm=40, tio2_nm=120, tio2_sd_nm=8)
    name, lab, peak, r_max = pearl_colour(binder, rutile, **pearl)
    if name != "blue":
        sys.exit(f"error: the two-layer pearl is meant to be blue but its flakes reflect {name} (h={lab[2]:.0f})")
    report.append(f"  pearl TiO2 {pearl['tio2_nm']} nm on mica {pearl['mica_nm']} nm: {name}, "
                  f"L*={lab[0]:.1f} C*={lab[1]:.1f} h={lab[2]:.0f}°, reflectance peak {r_max:.2f} at {peak} nm "
                  "(normal incidence, in the binder)")
    pearl_source = (f"TiO2-coated mica (rutile on muscovite): TiO2 index from the rutile ordinary-ray formula of "
                    f"{cite(rutile)}, {extrapolation_note(rutile)}; mica n = {MICA_INDEX} (muscovite handbook value). "
                    f"TiO2 {pearl['tio2_nm']} nm gives a second-order blue interference colour (normal-incidence "
                    f"reflectance peak near {peak} nm, CIELAB hue {lab[2]:.0f}°); layer thicknesses and sizes "
                    "in the range of commercial pearl pigments (Pfaff, Special Effect Pigments, 2008)")
    c_pearl, c_cb = 0.06, 0.01
    recipes["pearlescent-two-layer.json"] = {
        "schema_version": 1,
        "name": "Blue pearl over black (two layers)",
        "description": (
            "A two-layer pearlescent: blue interference pearl. A 15 µm basecoat holds TiO2-coated mica flakes "
            f"(6 % by volume, 18 µm across, mica {pearl['mica_nm']}±{pearl['mica_sd_nm']} nm, rutile "
            f"{pearl['tio2_nm']}±{pearl['tio2_sd_nm']} nm on each face) whose thin-film reflection is a "
            f"second-order blue (peak near {peak} nm), and 1 % carbon black that absorbs the light the flakes "
            "let through, so the blue shows at the specular angle over a near-black flop; 40 µm clear coat on "
            "top, grey primer below. Rutile index: Devore 1951; mica n=1.58 (handbook); carbon black absorption "
            f"by Mie theory from the n,k of carbon (Hagemann 1975). {binder_note} {thickness_note} {primer_note} "
            "Generated by packaging/demo/make_demo_recipes.py."),
        "ambient": {"refractive_index": 1.0},
        "layers": [
            clear_coat(binder),
            {"name": "basecoat", "thickness_um": 15, "binder": binder.json("acrylic basecoat (PMMA index as proxy)"),
             "components": [
                 interference_flake("blue interference pearl (TiO2 on mica)", pearl_source, c_pearl, 18, 10,
                                    pearl["mica_nm"], pearl["mica_sd_nm"], pearl["tio2_nm"], pearl["tio2_sd_nm"],
                                    rutile),
                 pigment("carbon black", cb_source, c_cb, carbon, d_cb)]},
        ],
        "substrate": grey_primer,
    }

    # 4. Three-layer white pearl: clear / pearl mid-coat / white ground coat.
    silver = dict(mica_nm=350, mica_sd_nm=40, tio2_nm=60, tio2_sd_nm=6)
    s_name, s_lab, s_peak, s_max = pearl_colour(binder, rutile, **silver)
    if s_name != "silver-white":
        sys.exit(f"error: the tri-coat pearl is meant to be silver-white but reflects {s_name}")
    report.append(f"  pearl TiO2 {silver['tio2_nm']} nm on mica {silver['mica_nm']} nm: {s_name}, "
                  f"L*={s_lab[0]:.1f} C*={s_lab[1]:.1f} h={s_lab[2]:.0f}°, reflectance max {s_max:.2f}")
    silver_source = (f"TiO2-coated mica: TiO2 index from the rutile ordinary-ray formula of {cite(rutile)}, "
                     f"{extrapolation_note(rutile)}; mica n = {MICA_INDEX} (muscovite handbook value). TiO2 "
                     f"{silver['tio2_nm']} nm gives a first-order silver-white interference (CIELAB chroma "
                     f"{s_lab[1]:.0f} at normal incidence); sizes as for fine white pearls (Pfaff 2008)")
    c_white = 0.15
    recipes["three-layer.json"] = {
        "schema_version": 1,
        "name": "White pearl tri-coat",
        "description": (
            "A three-layer (tri-coat) white pearl: 40 µm clear coat / 12 µm pearl mid-coat with silver-white "
            f"TiO2-coated mica flakes (3 % by volume, 15 µm across, rutile {silver['tio2_nm']} nm, mica "
            f"{silver['mica_nm']} nm) / 25 µm white ground coat with rutile TiO2 pigment (15 % by volume, "
            "0.23 µm), on a light grey primer (nominal flat albedo 0.6). The white's scattering comes from Mie "
            "theory with the rutile index of Devore 1951 (no absorption: the source gives n only, so the violet "
            f"end is somewhat too bright). {binder_note} {thickness_note} "
            "Generated by packaging/demo/make_demo_recipes.py."),
        "ambient": {"refractive_index": 1.0},
        "layers": [
            clear_coat(binder),
            {"name": "pearl mid-coat", "thickness_um": 12,
             "binder": binder.json("acrylic mid-coat (PMMA index as proxy)"),
             "components": [
                 interference_flake("silver-white pearl (TiO2 on mica)", silver_source, 0.03, 15, 12,
                                    silver["mica_nm"], silver["mica_sd_nm"], silver["tio2_nm"],
                                    silver["tio2_sd_nm"], rutile)]},
            {"name": "white ground coat", "thickness_um": 25,
             "binder": binder.json("acrylic basecoat (PMMA index as proxy)"),
             "components": [pigment("titanium dioxide white (rutile)", white_source, c_white, white, d_tio2)]},
        ],
        "substrate": lambertian(0.6),
    }

    # 5. Raw-medium validation slab.
    recipes["raw-medium-slab.json"] = {
        "schema_version": 1,
        "name": "Raw medium slab (validation)",
        "description": (
            "Validation case, not a paint: one index-matched slab (binder and ambient index 1.0, so no Fresnel "
            "reflection) of an isotropic scatterer with single-scattering albedo 0.9 and optical thickness 1 "
            "(Henyey-Greenstein g = 0) over a black substrate. Its reflectance and transmittance can be compared "
            "with published radiative-transfer tables for a homogeneous plane-parallel layer (e.g. van de Hulst, "
            "Multiple Light Scattering, 1980) or an independent adding-doubling code. thickness_um is nominal: "
            "the raw medium's optical thickness replaces it."),
        "ambient": {"refractive_index": 1.0},
        "layers": [
            {"name": "slab", "thickness_um": 1,
             "binder": {"name": "index-matched (vacuum)", "refractive_index": 1.0, "absorption_per_um": 0.0},
             "components": [{"kind": "raw_medium", "name": "isotropic scatterer",
                             "source": "synthetic validation values (albedo 0.9, optical thickness 1, g 0)",
                             "albedo": 0.9, "optical_thickness": 1.0, "hg_g": 0.0}]},
        ],
        "substrate": {"kind": "black"},
    }

    # Film opacity figures for the log.
    i550 = WAVELENGTHS_NM.index(550)
    report.append(f"  solid red basecoat: optical thickness at 550 nm = "
                  f"{c_hem * (hematite[0][i550] + hematite[1][i550]) * 25:.1f}")
    report.append(f"  white ground coat: scattering optical thickness at 550 nm = {c_white * white[1][i550] * 25:.1f}")
    report.append(f"  pearl basecoat: carbon black absorption optical thickness at 550 nm = "
                  f"{c_cb * carbon[0][i550] * 15:.2f}")
    diffs = [abs(mat["pmma"].n(w) - mat["pmma_beadie"].n(w)) for w in WAVELENGTHS_NM]
    report.append(f"  binder n(PMMA, Sultanova) = {binder.n[0]:.4f} .. {binder.n[-1]:.4f}; "
                  f"max difference to Beadie 2015 over 380-780 nm = {max(diffs):.4f}")
    return recipes, report


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", type=Path,
                        default=Path(os.environ.get("PAINTLAB_OPTICAL_CONSTANTS", DEFAULT_DATA)),
                        help="folder of refractiveindex.info .yml files (default: %(default)s)")
    parser.add_argument("--out", type=Path, default=HERE / "recipes", help="output folder (default: %(default)s)")
    args = parser.parse_args()

    if not mie_self_check():
        sys.exit("error: the Mie code does not reproduce the published values")
    materials = load_materials(args.data)
    for key in ("pmma", "rutile_o", "rutile_e"):
        note = extrapolation_note(materials[key])
        if note:
            print(f"note: {materials[key].database_path}: {note}")
    recipes, report = build_recipes(materials)
    print("Derived values:")
    print("\n".join(report))

    args.out.mkdir(parents=True, exist_ok=True)
    for filename, recipe in recipes.items():
        path = args.out / filename
        path.write_text(to_json(recipe) + "\n", encoding="utf-8")
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
