#!/usr/bin/env python3
"""Figure of the measured-paint fits (docs/measured_brdf_fits.png).

Reads measured_inplane.csv and measured_fits.csv written by the report run
report_measured_brdf_fits (tests/measured_brdf/report_measured_fits.cpp) and
draws, per paint, Y of pi*f in the plane of incidence at 45 deg incidence
(neural reconstruction of the measurement, the fitted recipe, ABC, SGD) on a
log axis, with the six multi-angle geometries marked and the log errors in
the title. Needs Debian's matplotlib (run with /usr/bin/python3).

    /usr/bin/python3 tools/measured_brdf/plot_fits.py REPORT_DIR docs/measured_brdf_fits.png
    python3 tools/measured_brdf/plot_fits.py --table REPORT_DIR   # the markdown table of VALIDATION.md
"""
import csv
import sys
from collections import defaultdict


STYLE = {
    "neural": dict(color="black", lw=2.0, label="measured (neural fit)"),
    "fit": dict(color="tab:red", lw=1.5, label="fitted recipe"),
    "abc": dict(color="tab:blue", lw=1.0, ls="--", label="ABC (Low 2012)"),
    "sgd": dict(color="tab:green", lw=1.0, ls=":", label="SGD (Bagher 2012)"),
}
# Detector angle of 45asX in the figure's signed view angle (negative: the
# specular side): -45 + X.
GEOMETRIES = [-15, 15, 25, 45, 75, 110]


def table(report_dir):
    """Per paint: log error (all samples / off the specular lobe) and ΔE00 at
    the six geometries of the fit, ABC and SGD against the neural fit."""
    print("| paint | template | model | log error | off specular | ΔE00 " + " / ".join(f"45as{g}" for g in GEOMETRIES) + " |")
    print("|---|---|---|---|---|---|")
    with open(f"{report_dir}/measured_fits.csv", newline="") as f:
        for row in csv.DictReader(f):
            for model in ("fit", "abc", "sgd"):
                if not row[f"{model}_log_error"]:
                    continue
                de = " / ".join(f"{float(row[f'{model}_de00_45as{g}']):.1f}" for g in GEOMETRIES)
                name = row["paint"] if model == "fit" else ""
                tmpl = row["template"] if model == "fit" else ""
                label = {"fit": "**fit**", "abc": "ABC", "sgd": "SGD"}[model]
                print(f"| {name} | {tmpl} | {label} | {float(row[f'{model}_log_error']):.3f} | "
                      f"{float(row[f'{model}_log_error_off_specular']):.3f} | {de} |")


def main(report_dir, out_png):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    curves = defaultdict(lambda: defaultdict(list))
    with open(f"{report_dir}/measured_inplane.csv", newline="") as f:
        for row in csv.DictReader(f):
            c = curves[row["paint"]][row["model"]]
            c.append((-float(row["view_deg"]), float(row["Y"])))
    errors = {}
    with open(f"{report_dir}/measured_fits.csv", newline="") as f:
        for row in csv.DictReader(f):
            errors[row["paint"]] = row
    paints = list(curves)
    cols = 4
    rows = (len(paints) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.3 * rows), squeeze=False)
    for ax, paint in zip(axes.flat, paints):
        for model, points in curves[paint].items():
            points.sort()
            ax.semilogy([p[0] for p in points], [max(p[1], 1e-5) for p in points], **STYLE[model])
        for g in GEOMETRIES:
            ax.axvline(-(-45 + g), color="grey", lw=0.5, alpha=0.5)
        e = errors.get(paint, {})
        title = paint.split("/", 1)[1]
        if e:
            title += f"\nlog err fit {float(e['fit_log_error']):.3f}"
            if e.get("abc_log_error"):
                title += f", ABC {float(e['abc_log_error']):.3f}, SGD {float(e['sgd_log_error']):.3f}"
        ax.set_title(title, fontsize=8)
        ax.set_xlim(-80, 80)
        ax.tick_params(labelsize=7)
        ax.set_xlabel("view angle (deg; + = specular side)", fontsize=7)
        ax.set_ylabel("Y of pi f", fontsize=7)
    for ax in list(axes.flat)[len(paints):]:
        ax.axis("off")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(out_png, dpi=110)


if __name__ == "__main__":
    if sys.argv[1] == "--table":
        table(sys.argv[2])
    else:
        main(sys.argv[1], sys.argv[2])
