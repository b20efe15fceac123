#!/usr/bin/env python3
"""Writes measurements/blue-pearl-panel.json: a made-up multi-angle reading of
a blue pearl panel for the workstation's Match tab and the fit examples.

Not a real measurement: the demo blue pearl with 7.2 % flakes (not 6 %) and a
13 µm basecoat (not 15 µm), its reflectance factors at the six standard
geometries from `paintlab-cli multiangle --json` (standard preset), resampled
to 400-700 nm in 10 nm steps as multi-angle spectrophotometers export them,
with 0.5 % multiplicative Gaussian noise (seed 7). CIELAB is left out: the
import computes it from the spectra. Run from the repository root after a
build: python3 packaging/demo/make_demo_measurement.py
"""
import json
import random
import subprocess
import tempfile

RECIPE = "packaging/demo/recipes/pearlescent-two-layer.json"
CLI = "build/release/cli/paintlab-cli"


def main():
    recipe = json.load(open(RECIPE))
    recipe["layers"][1]["thickness_um"] = 13
    recipe["layers"][1]["components"][0]["volume_fraction"] = 0.072
    with tempfile.NamedTemporaryFile("w", suffix=".json") as f:
        json.dump(recipe, f)
        f.flush()
        out = subprocess.run([CLI, "multiangle", f.name, "--json"], check=True, capture_output=True, text=True)
    report = json.loads(out.stdout)
    random.seed(7)
    model_nm = [380 + 5 * i for i in range(81)]
    wavelengths = list(range(400, 701, 10))
    readings = []
    for g in report["geometries"]:
        r = g["reflectance_factor"]
        assert len(r) == len(model_nm)
        values = [r[model_nm.index(w)] * (1 + 0.005 * random.gauss(0, 1)) for w in wavelengths]
        readings.append({"illumination_deg": 45, "aspecular_deg": g["aspecular_deg"],
                         "reflectance": [round(max(v, 0.0), 6) for v in values]})
    measurement = {"format": "paintlab-measurement", "format_version": 1,
                   "name": "Blue pearl panel 7 (made-up reading)", "kind": "multiangle",
                   "instrument": "simulated multi-angle spectrophotometer",
                   "geometry": "45as-15,15,25,45,75,110", "sample": "demo: blue pearl, 7.2 % flakes, 13 um basecoat",
                   "measured_at": "2026-12-05", "source": "packaging/demo/make_demo_measurement.py",
                   "illuminant": "D65", "observer": "10deg", "wavelengths_nm": wavelengths, "readings": readings}
    with open("packaging/demo/measurements/blue-pearl-panel.json", "w") as f:
        json.dump(measurement, f, indent=2)
        f.write("\n")


if __name__ == "__main__":
    main()
