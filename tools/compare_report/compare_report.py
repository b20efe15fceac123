#!/usr/bin/python3
"""Fast vs full model over a grid of flake paints (issue 4, item 5).

Writes one recipe per grid point (flake type x diameter x volume fraction x
orientation spread, then a small-flake series of metal flakes), runs

    paintlab-cli compare RECIPE --json --explicit-flakes --cone 5 --samples N --seed K --preset P

on each (the full model with real flat flakes in an Embree tile against the
fast model's continuum of flakes), plus one control run per (type, volume
fraction, spread) without --explicit-flakes (the full model with the fast
model's own continuum statistics, which do not depend on the diameter): the
control measures the fast model's discretisation error and the Monte Carlo
estimator's bias, so that what remains in the explicit runs is the
continuum approximation itself.

Outputs: docs/fast_vs_full.csv (one row per grid point) and
docs/fast_vs_full.png. Raw JSON per run is kept in --work, and a run whose
JSON exists is not repeated (delete the folder to start over), so an
interrupted grid resumes where it stopped.

Standard library plus matplotlib (Debian python3-matplotlib); see README.md.
"""

import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

sys.dont_write_bytecode = True

HERE = Path(__file__).resolve().parent
REPO = HERE.parent.parent

# The paint: one 20 µm binder layer (a typical basecoat build, 12-25 µm;
# Streitberger & Dössel 2008) of index 1.5 in air over a black substrate, no
# clear coat. Black: every bit of the reflected light has met a flake, so the
# difference is the flake layer's own, not diluted by a substrate both models
# treat identically. No clear coat: a non-scattering coat only adds Fresnel
# trapping, which both models already agree on (docs/VALIDATION.md).
FILM_UM = 20.0
BINDER_INDEX = 1.5

# Flake types. Thickness enters the coverage: flake area per unit film area =
# volume_fraction * FILM_UM / thickness.
TYPES = {
    # Aluminium at 550 nm (Rakić 1995: n 1.015, k 6.63), spectrally flat so the
    # band mean is a luminance-like number; 0.3 µm thick (cornflake pigments).
    "mirror": {"thickness_um": 0.3},
    # The demo's blue pearl: rutile 120 +- 8 nm on mica 350 +- 40 nm.
    "interference": {"thickness_um": 0.35 + 2 * 0.12},
    # A transparent dielectric platelet: an uncoated platelet of index 2.0 (the
    # recipe's allowed maximum; bismuth oxychloride, a real uncoated nacreous
    # pigment, is ~2.0-2.15), 100 +- 20 nm thick: it reflects a few % and
    # transmits the rest. Bare mica (1.58 in a 1.5 binder, 0.07 % per face)
    # is the more common platelet but reflects so little over black that the
    # full model's signal is noise at any affordable budget. 250 nm thick keeps
    # the coverage at the maximum (24 flake layers) affordable for the walk.
    "dielectric": {"thickness_um": 0.25},
}
DIAMETERS_UM = [5.0, 10.0, 20.0, 50.0]
# From low to the technological maximum (engine/src/parameters.cpp: flake
# volume_fraction allowed 0 .. 0.3, typical 0 .. 0.15).
VOLUME_FRACTIONS = [0.01, 0.04, 0.12, 0.30]
SPREADS_DEG = [5.0, 20.0]
SEED = 20261122
CONE_DEG = 5.0


def flake_component(kind, diameter_um, volume_fraction, spread_deg):
    if kind == "mirror":
        return {
            "kind": "mirror_flake",
            "name": "aluminium flakes",
            "source": "Al n, k at 550 nm (Rakic 1995), held constant",
            "volume_fraction": volume_fraction,
            "diameter_um": diameter_um,
            "thickness_um": TYPES[kind]["thickness_um"],
            "orientation_spread_deg": spread_deg,
            "n": 1.015,
            "k": 6.63,
        }
    if kind == "interference":
        return {
            "kind": "interference_flake",
            "name": "blue pearl (TiO2 on mica)",
            "source": "demo pearlescent-two-layer, rutile index 2.65 (Devore 1951 at 550 nm)",
            "volume_fraction": volume_fraction,
            "diameter_um": diameter_um,
            "orientation_spread_deg": spread_deg,
            "mica_thickness_nm": 350,
            "mica_thickness_spread_nm": 40,
            "tio2_thickness_nm": 120,
            "tio2_thickness_spread_nm": 8,
            "mica_refractive_index": 1.58,
            "tio2_refractive_index": 2.65,
        }
    return {
        "kind": "interference_flake",
        "name": "uncoated high-index platelets",
        "source": "a transparent platelet of index 2.0 (BiOCl-like), 250 +- 40 nm, no coating",
        "volume_fraction": volume_fraction,
        "diameter_um": diameter_um,
        "orientation_spread_deg": spread_deg,
        "mica_thickness_nm": 250,
        "mica_thickness_spread_nm": 40,
        "tio2_thickness_nm": 0,
        "tio2_thickness_spread_nm": 0,
        "mica_refractive_index": 2.0,
        "tio2_refractive_index": 2.65,
    }


def absorber(absorption_per_um):
    """A grey, non-scattering absorber at 1 % by volume giving the film the
    absorption coefficient absorption_per_um (1 % carbon black in the demo
    pearlescent gives 0.12-0.22 /um over 400-700 nm)."""
    return {
        "kind": "pigment",
        "name": "grey absorber",
        "source": "a spectrally flat absorber standing for carbon black",
        "volume_fraction": 0.01,
        "sigma_a_per_um": absorption_per_um / 0.01,
        "sigma_s_per_um": 0.0,
        "hg_g": 0.0,
    }


def recipe(kind, diameter_um, volume_fraction, spread_deg, absorption_per_um=0.0):
    components = [flake_component(kind, diameter_um, volume_fraction, spread_deg)]
    if absorption_per_um > 0.0:
        components.append(absorber(absorption_per_um))
    return {
        "schema_version": 1,
        "name": f"{kind} d{diameter_um:g} c{volume_fraction:g} s{spread_deg:g}",
        "description": "Grid point of tools/compare_report/compare_report.py",
        "ambient": {"refractive_index": 1.0},
        "layers": [
            {
                "name": "flake layer",
                "thickness_um": FILM_UM,
                "binder": {"name": "binder", "refractive_index": BINDER_INDEX, "absorption_per_um": 0.0},
                "components": components,
            }
        ],
        "substrate": {"kind": "black"},
    }


def coverage(kind, volume_fraction):
    """Flake area per unit film area (flake layers), as the fast model forms it."""
    return volume_fraction * FILM_UM / TYPES[kind]["thickness_um"]


def run_compare(cli, recipe_path, out_path, samples, preset, explicit):
    if out_path.exists():
        return json.loads(out_path.read_text())
    cmd = [str(cli), "compare", str(recipe_path), "--json", "--samples", str(samples), "--seed", str(SEED),
           "--preset", preset, "--cone", str(CONE_DEG)]
    if explicit:
        cmd.append("--explicit-flakes")
    start = time.monotonic()
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    wall = time.monotonic() - start
    if done.returncode != 0:
        raise SystemExit(f"failed ({done.returncode}): {' '.join(cmd)}\n{done.stderr}")
    result = json.loads(done.stdout)
    result["wall_seconds"] = wall
    result["command"] = " ".join(cmd)
    tmp = out_path.with_suffix(".tmp")
    tmp.write_text(json.dumps(result))
    os.replace(tmp, out_path)
    return result


def summarise(result, lo_nm=400.0, hi_nm=700.0):
    """Per geometry: band means over lo..hi nm of both models, the relative
    difference (mc - fast) / fast and its standard error from the MC's."""
    wl = result["wavelengths_nm"]
    inside = [i for i, w in enumerate(wl) if lo_nm <= w <= hi_nm]
    rows = []
    for g in result["geometries"]:
        fast = sum(g["fast_brdf_per_sr"][i] for i in inside) / len(inside)
        mc = sum(g["mc_brdf_per_sr"][i] for i in inside) / len(inside)
        # Bands are independent runs, so their variances add.
        se = math.sqrt(sum(g["mc_std_error"][i] ** 2 for i in inside)) / len(inside)
        rel = (mc - fast) / fast if fast > 0 else float("nan")
        rel_se = se / fast if fast > 0 else float("nan")
        rows.append({"aspecular": g["aspecular_deg"], "fast": fast, "mc": mc, "se": se, "rel": rel, "rel_se": rel_se})
    return rows


# A geometry whose fast-model f is below this fraction of the brightest of the
# six is dark next to the highlight (for 5 deg flakes over black, 45as75 and
# 45as110 carry ~1e-4 of it): its relative difference is a ratio of two tiny
# numbers, so "worst" and "mean |.|" skip it (the CSV keeps every geometry).
VISIBLE_FRACTION = 0.03


# Paints whose flakes reflect little (interference and dielectric platelets
# at the two lower concentrations: f of a few 1e-2 /sr over black) get this
# many times the base paths, so that their standard errors are not several
# times the others'.
LOW_SIGNAL_FACTOR = 4


def samples_for(kind, volume_fraction, base):
    return base * LOW_SIGNAL_FACTOR if kind != "mirror" and volume_fraction <= 0.04 else base


def visible(geo):
    peak = max(g["fast"] for g in geo)
    return [g for g in geo if g["fast"] >= VISIBLE_FRACTION * peak]


# The small-flake limit (issue 4: the full model must approach the fast one as
# diameter x concentration -> 0): metal flakes below the grid's diameters.
LIMIT_DIAMETERS_UM = [0.5, 1.0, 2.0]
LIMIT_VOLUME_FRACTIONS = [0.04, 0.12]
LIMIT_SPREAD_DEG = 20.0


# Flakes in an absorbing film (the demo pearlescent's basecoat holds 1 %
# carbon black): absorption weights the reflections near the top of the film,
# where the full model's tilted flakes cannot reach (a flake's centre keeps
# r sin(tilt) from each face), so the full model is the darker
# (engine/src/model_validity.cpp, "surface depletion").
ABSORBING_KINDS = {"interference": 0.04, "mirror": 0.01}  # kind: volume fraction
ABSORBING_DIAMETERS_UM = [5.0, 20.0, 50.0]
ABSORPTIONS_PER_UM = [0.05, 0.15, 0.5]
ABSORBING_SPREAD_DEG = 10.0


def grid():
    for kind in TYPES:
        for spread in SPREADS_DEG:
            for vf in VOLUME_FRACTIONS:
                for d in DIAMETERS_UM:
                    yield "grid", kind, d, vf, spread, 0.0
    for vf in LIMIT_VOLUME_FRACTIONS:
        for d in LIMIT_DIAMETERS_UM:
            yield "limit", "mirror", d, vf, LIMIT_SPREAD_DEG, 0.0
    for kind, vf in ABSORBING_KINDS.items():
        for a in ABSORPTIONS_PER_UM:
            for d in ABSORBING_DIAMETERS_UM:
                yield "absorbing", kind, d, vf, ABSORBING_SPREAD_DEG, a


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cli", default=str(REPO / "build" / "release" / "cli" / "paintlab-cli"))
    parser.add_argument("--work", default="/tmp/paintlab-compare-report", help="recipes and raw JSON")
    parser.add_argument("--out", default=str(REPO / "docs"), help="where the CSV and PNG go")
    parser.add_argument("--samples", type=int, default=4000,
                        help="MC paths per band and incidence (x4 for weakly reflecting paints, see LOW_SIGNAL_FACTOR)")
    parser.add_argument("--preset", default="standard", help="fast-model preset (its bands are the MC's)")
    parser.add_argument("--quick", action="store_true", help="two points only (a smoke test)")
    parser.add_argument("--no-plot", action="store_true")
    parser.add_argument("--cached-only", action="store_true", help="summarise the runs already in --work, run none")
    args = parser.parse_args()

    work = Path(args.work)
    (work / "recipes").mkdir(parents=True, exist_ok=True)
    (work / "runs").mkdir(parents=True, exist_ok=True)
    points = list(grid())
    if args.quick:
        points = [("grid", "mirror", 5.0, 0.04, 20.0, 0.0), ("absorbing", "interference", 20.0, 0.04, 10.0, 0.15)]

    table = []
    t0 = time.monotonic()
    for n, (series, kind, d, vf, spread, absorption) in enumerate(points):
        a_tag = f"_a{absorption:g}" if absorption > 0.0 else ""
        tag = f"{kind}_d{d:g}_c{vf:g}_s{spread:g}{a_tag}"
        rp = work / "recipes" / f"{tag}.json"
        rp.write_text(json.dumps(recipe(kind, d, vf, spread, absorption), indent=1))
        samples = samples_for(kind, vf, args.samples)
        suffix = f"_n{samples}_{args.preset}"
        ctag = f"{kind}_c{vf:g}_s{spread:g}{a_tag}_continuum"
        if args.cached_only and not all(
                (work / "runs" / f"{t}{suffix}.json").exists() for t in (tag, ctag)):
            continue
        full = run_compare(args.cli, rp, work / "runs" / f"{tag}{suffix}.json", samples, args.preset, True)
        # The control does not depend on the diameter: run it once, at the smallest.
        crp = work / "recipes" / f"{kind}_d{DIAMETERS_UM[0]:g}_c{vf:g}_s{spread:g}{a_tag}.json"
        if not crp.exists():
            crp.write_text(json.dumps(recipe(kind, DIAMETERS_UM[0], vf, spread, absorption), indent=1))
        control = run_compare(args.cli, crp, work / "runs" / f"{ctag}{suffix}.json", samples, args.preset, False)
        geo = summarise(full)
        cgeo = summarise(control)
        worst = max(visible(geo), key=lambda g: abs(g["rel"]))
        cworst = max(visible(cgeo), key=lambda g: abs(g["rel"]))
        row = {
            "series": series,
            "flake_type": kind,
            "diameter_um": d,
            "volume_fraction": vf,
            "spread_deg": spread,
            "absorption_per_um": absorption,
            "coverage": round(coverage(kind, vf), 4),
            "diameter_over_free_path": round(d * vf / TYPES[kind]["thickness_um"], 4),
            "diameter_over_film": d / FILM_UM,
        }
        for g in geo:
            row[f"rel_45as{g['aspecular']:g}"] = round(g["rel"], 5)
        for g in geo:
            row[f"se_45as{g['aspecular']:g}"] = round(g["rel_se"], 5)
        # Signal-weighted over the six geometries: sum(mc - fast) / sum(fast),
        # dominated by the bright near-specular ones as the eye is.
        total = sum(g["fast"] for g in geo)
        row["weighted_rel"] = round(sum(g["mc"] - g["fast"] for g in geo) / total, 5)
        row["weighted_rel_se"] = round(math.sqrt(sum(g["se"] ** 2 for g in geo)) / total, 5)
        shown = visible(geo)
        row["visible_geometries"] = len(shown)
        row["mean_abs_rel"] = round(sum(abs(g["rel"]) for g in shown) / len(shown), 5)
        row["mean_rel_se"] = round(math.sqrt(sum(g["rel_se"] ** 2 for g in shown)) / len(shown), 5)
        row["worst_rel"] = round(worst["rel"], 5)
        row["worst_rel_se"] = round(worst["rel_se"], 5)
        row["worst_geometry"] = f"45as{worst['aspecular']:g}"
        row["worst_z"] = round(worst["rel"] / worst["rel_se"], 2) if worst["rel_se"] > 0 else float("nan")
        # The control (full model with the continuum's statistics) against the
        # fast model: the fast model's discretisation plus the estimator's
        # bias; and the explicit flakes against the control: the continuum
        # approximation alone, free of the fast model's discretisation.
        ctotal = sum(g["fast"] for g in cgeo)
        row["control_weighted_rel"] = round(sum(g["mc"] - g["fast"] for g in cgeo) / ctotal, 5)
        row["control_weighted_rel_se"] = round(math.sqrt(sum(g["se"] ** 2 for g in cgeo)) / ctotal, 5)
        mc_total = sum(g["mc"] for g in cgeo)
        ratio = sum(g["mc"] for g in geo) / mc_total
        row["explicit_vs_continuum"] = round(ratio - 1.0, 5)
        # Error propagation for a ratio of two independent sums.
        row["explicit_vs_continuum_se"] = round(
            math.sqrt(sum(g["se"] ** 2 for g in geo) + ratio**2 * sum(g["se"] ** 2 for g in cgeo)) / mc_total, 5)
        row["control_worst_rel"] = round(cworst["rel"], 5)
        row["control_worst_rel_se"] = round(cworst["rel_se"], 5)
        row["fast_seconds"] = round(full["fast_seconds"], 4)
        row["mc_seconds"] = round(full["mc_seconds"], 2)
        row["mc_paths"] = full["mc_settings"]["paths"]
        table.append(row)
        print(f"[{n + 1}/{len(points)} {time.monotonic() - t0:7.0f} s] {tag}: worst {row['worst_geometry']} "
              f"{100 * row['worst_rel']:+.1f} +- {100 * row['worst_rel_se']:.1f} %, mean |rel| "
              f"{100 * row['mean_abs_rel']:.1f} %, weighted {100 * row['weighted_rel']:+.1f} +- "
              f"{100 * row['weighted_rel_se']:.1f} %, control {100 * row['control_weighted_rel']:+.1f} %, "
              f"explicit vs continuum {100 * row['explicit_vs_continuum']:+.1f} %, "
              f"MC {row['mc_seconds']:.1f} s, fast {row['fast_seconds']:.3f} s", flush=True)

    out = Path(args.out)
    if args.quick:
        out = work
    out.mkdir(parents=True, exist_ok=True)
    csv_path = out / "fast_vs_full.csv"
    with open(csv_path, "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=list(table[0].keys()), lineterminator="\n")
        writer.writeheader()
        writer.writerows(table)
    print(f"wrote {csv_path}")
    if not args.no_plot:
        from plot import plot  # matplotlib only here, so the grid runs without it

        png = out / "fast_vs_full.png"
        plot(table, png)
        print(f"wrote {png}")


if __name__ == "__main__":
    main()
