#!/usr/bin/env python3
"""Build the demo ingredient library (demo-ingredients.json) from published optical constants.

The ingredients of the five demo recipes are taken from the recipe generator
(../make_demo_recipes.py, same Mie coefficients and indices, same names, so the
demo database links every recipe component to its ingredient), and a few more
metals are added for mirror flakes. Every spectrum keeps its literature source.
An installed PaintLab has no ../shared folder, so the result is committed and
compiled into the database library (database/CMakeLists.txt embeds it).

Handbook values (not in the optical-constants folder):
- Densities in g/cm3 at 20-25 °C from the CRC Handbook of Chemistry and
  Physics (97th ed., 2016, "Physical Constants of Inorganic Compounds" and
  "Density of Solids"): rutile TiO2 4.23, Al 2.70, Ag 10.5, Au 19.3, Cu 8.96,
  Cr 7.19, hematite 5.25, graphitic carbon 2.2 (carbon black is 1.8-2.1;
  1.8 is used); muscovite mica 2.8 (2.76-2.88); PMMA 1.18 (polymer handbook).
- Mica (muscovite) refractive index 1.58 in the visible (handbook value; the
  folder has no mica file).
- Interference flake density: thickness-weighted mean of mica and the two
  TiO2 coatings (2 t_TiO2 * 4.23 + t_mica * 2.8) / (2 t_TiO2 + t_mica).

Run: python3 packaging/demo/ingredients/make_demo_ingredients.py [--data DIR]
A rerun on the same inputs gives the same bytes.
"""

import argparse
import json
import os
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

import make_demo_recipes as demo  # noqa: E402
from optical_constants import Material  # noqa: E402

CRC = "CRC Handbook of Chemistry and Physics, 97th ed. (2016)"
DENSITY = {  # g/cm3, with where from
    "pmma": (1.18, "PMMA, J. E. Mark (ed.), Physical Properties of Polymers Handbook, 2nd ed. (2007)"),
    "tio2": (4.23, f"rutile TiO2, {CRC}"),
    "al": (2.70, f"aluminium, {CRC}"),
    "ag": (10.5, f"silver, {CRC}"),
    "au": (19.3, f"gold, {CRC}"),
    "cu": (8.96, f"copper, {CRC}"),
    "cr": (7.19, f"chromium, {CRC}"),
    "fe2o3": (5.25, f"hematite, {CRC}"),
    "carbon_black": (1.8, "carbon black, 1.8-2.1 g/cm3 (Donnet, Bansal & Wang, Carbon Black, 2nd ed., 1993)"),
    "mica": (2.8, f"muscovite mica, 2.76-2.88 g/cm3, {CRC}"),
}
MICA_SOURCE = "muscovite mica n = 1.58 in the visible (handbook value; refractiveindex.info has no mica file)"
EXTRA_METALS = {  # key: (file, ingredient name, density key, tags)
    "silver": ("main__Ag__nk__Johnson.yml", "silver flakes (Johnson & Christy)", "ag", ["metal", "silver"]),
    "gold": ("main__Au__nk__Johnson.yml", "gold bronze flakes (Johnson & Christy)", "au", ["metal", "gold"]),
    "copper": ("main__Cu__nk__Johnson.yml", "copper bronze flakes (Johnson & Christy)", "cu", ["metal", "copper"]),
    "chromium": ("main__Cr__nk__Johnson.yml", "chromium flakes (Johnson & Christy)", "cr", ["metal", "chromium"]),
    "aluminium_mcpeak": ("main__Al__nk__McPeak.yml", "aluminium flakes (McPeak)", "al", ["metal", "aluminium"]),
}


def publication_year(source):
    """Year of the measured data: the first "(YYYY)" of the literature reference, else the first year named."""
    found = re.search(r"\((\d{4})\)", source) or re.search(r"\b(1[89]\d\d|20\d\d)\b", source)
    return found.group(1) if found else ""


def spectrum(value, unit, source):
    """An ingredient spectrum: the recipe generator's value (number or table), unit, source and data year."""
    out = {"unit": unit, "source": source}
    year = publication_year(source)
    if year:
        out["date"] = year
    if isinstance(value, dict):
        out["wavelengths_nm"] = value["wavelengths_nm"]
        out["values"] = value["values"]
    else:
        out["value"] = value
    return out


def density(key):
    value, source = DENSITY[key]
    return {"density_g_cm3": value, "density_source": source}


def binder_ingredient(binder, name, tags, thickness):
    b = binder.json(name)
    source = demo.cite(binder.material)
    return {"kind": "binder", "name": name,
            "description": "Cured acrylic film; PMMA refractive index as a proxy, no absorption.",
            "source": source, "tags": ["binder", "acrylic"] + tags, **density("pmma"),
            "limits": {"min_thickness_um": thickness[0], "max_thickness_um": thickness[1]},
            "spectra": {"refractive_index": spectrum(b["refractive_index"], "1", source),
                        "absorption_per_um": spectrum(0.0, "1/µm", "non-absorbing (assumed)")}}


def components(recipes):
    """Every component of the demo recipes, by name (first occurrence)."""
    found = {}
    for recipe in recipes.values():
        for layer in recipe["layers"]:
            for c in layer["components"]:
                found.setdefault(c["name"], c)
    return found


def pigment_ingredient(c, density_key, tags, max_fraction):
    return {"kind": "pigment", "name": c["name"], "description": "Mie coefficients per unit volume fraction.",
            "source": c["source"], "tags": ["pigment"] + tags, **density(density_key),
            "limits": {"max_volume_fraction": max_fraction},
            "hg_g": c["hg_g"], "particle_diameter_um": c["particle_diameter_um"],
            "spectra": {"sigma_a_per_um": spectrum(c["sigma_a_per_um"], "1/µm", c["source"]),
                        "sigma_s_per_um": spectrum(c["sigma_s_per_um"], "1/µm", c["source"])}}


def mirror_ingredient(name, source, n, k, density_key, tags):
    return {"kind": "mirror_flake", "name": name,
            "description": "Metal flakes; reflectance from the metal's complex index by Fresnel.",
            "source": source, "tags": ["flake", "mirror"] + tags, **density(density_key),
            "limits": {"max_volume_fraction": 0.2},
            # Typical of cornflake/silver-dollar aluminium pigments (Wissling, Metallic Effect Pigments, 2006).
            "diameter_um": 18, "diameter_sd_um": 6, "thickness_um": 0.3, "orientation_spread_deg": 12,
            "spectra": {"n": spectrum(n, "1", source), "k": spectrum(k, "1", source)}}


def pearl_ingredient(c):
    t_tio2, t_mica = c["tio2_thickness_nm"], c["mica_thickness_nm"]
    rho = (2 * t_tio2 * DENSITY["tio2"][0] + t_mica * DENSITY["mica"][0]) / (2 * t_tio2 + t_mica)
    return {"kind": "interference_flake", "name": c["name"],
            "description": "TiO2 / mica / TiO2 pearl pigment.", "source": c["source"],
            "tags": ["flake", "pearl", "interference"],
            "density_g_cm3": round(rho, 3),
            "density_source": f"thickness-weighted mean of {DENSITY['tio2'][1]} and {DENSITY['mica'][1]}",
            "limits": {"max_volume_fraction": 0.15},
            # Diameter spread: commercial 5-25 µm grades (Pfaff, Special Effect Pigments, 2008).
            "diameter_um": c["diameter_um"], "diameter_sd_um": 5,
            "orientation_spread_deg": c["orientation_spread_deg"],
            "mica_thickness_nm": t_mica, "mica_thickness_spread_nm": c["mica_thickness_spread_nm"],
            "tio2_thickness_nm": t_tio2, "tio2_thickness_spread_nm": c["tio2_thickness_spread_nm"],
            "spectra": {"mica_refractive_index": spectrum(c["mica_refractive_index"], "1", MICA_SOURCE),
                        "tio2_refractive_index": spectrum(c["tio2_refractive_index"], "1", c["source"])}}


def substrate_ingredient(name, albedo):
    return {"kind": "substrate", "name": name, "description": "Primed panel, flat grey.",
            "source": "nominal value, not a measurement", "tags": ["substrate", "primer"],
            "substrate_kind": "lambertian",
            "spectra": {"albedo": spectrum(albedo, "1", "nominal value, not a measurement")}}


def build(data_dir):
    mat = demo.load_materials(data_dir)
    recipes, _ = demo.build_recipes(mat)
    binder = demo.Binder(mat["pmma"])
    comp = components(recipes)
    out = [
        binder_ingredient(binder, "acrylic clear coat (PMMA index as proxy)", ["clear coat"], (35, 50)),
        binder_ingredient(binder, "acrylic basecoat (PMMA index as proxy)", ["basecoat"], (12, 25)),
        binder_ingredient(binder, "acrylic mid-coat (PMMA index as proxy)", ["mid-coat"], (10, 20)),
        pigment_ingredient(comp["iron oxide red (hematite)"], "fe2o3", ["red", "iron oxide"], 0.2),
        pigment_ingredient(comp["carbon black"], "carbon_black", ["black", "carbon"], 0.05),
        pigment_ingredient(comp["titanium dioxide white (rutile)"], "tio2", ["white", "titanium dioxide"], 0.25),
    ]
    al = comp["aluminium flakes"]
    out.append(mirror_ingredient(al["name"], al["source"], al["n"], al["k"], "al", ["aluminium"]))
    for key, (file, name, dkey, tags) in EXTRA_METALS.items():
        m = Material(data_dir / file)
        source = f"{demo.cite(m)}, interpolated linearly to 380-780 nm every 10 nm"
        n = demo.spectrum([m.n(w) for w in demo.WAVELENGTHS_NM])
        k = demo.spectrum([m.k(w) for w in demo.WAVELENGTHS_NM])
        out.append(mirror_ingredient(name, source, n, k, dkey, tags))
    out.append(pearl_ingredient(comp["blue interference pearl (TiO2 on mica)"]))
    out.append(pearl_ingredient(comp["silver-white pearl (TiO2 on mica)"]))
    out.append(substrate_ingredient("grey primer (albedo 0.30)", 0.3))
    out.append(substrate_ingredient("light grey primer (albedo 0.60)", 0.6))
    return {"format": "paintlab-ingredients", "format_version": 1,
            "generated_by": "packaging/demo/ingredients/make_demo_ingredients.py", "ingredients": out}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", type=Path,
                        default=Path(os.environ.get("PAINTLAB_OPTICAL_CONSTANTS", demo.DEFAULT_DATA)))
    parser.add_argument("--out", type=Path, default=HERE / "demo-ingredients.json")
    args = parser.parse_args()
    doc = build(args.data)
    args.out.write_text(json.dumps(doc, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    print(f"wrote {args.out}: {len(doc['ingredients'])} ingredients")


if __name__ == "__main__":
    main()
