"""The figure of the comparison report: relative difference of the full model
(explicit flakes) from the fast model against diameter x concentration /
thickness (the diameter over the mean free path between flakes), one panel per
flake type, with 2-standard-error bars from the Monte Carlo and the fitted
validity rule (fit_boundary.py, engine/src/model_validity.cpp) as lines."""

import matplotlib

matplotlib.use("Agg")  # no display: a docs tool run from a shell
import matplotlib.pyplot as plt  # noqa: E402

from compare_report import TYPES  # noqa: E402
from fit_boundary import fit, predict  # noqa: E402

TYPE_TITLES = {
    "mirror": "mirror flakes (aluminium, 0.3 µm)",
    "interference": "interference flakes (TiO2/mica, 0.59 µm)",
    "dielectric": "transparent dielectric (n 2.0, 0.25 µm)",
}
COLOURS = {0.01: "tab:blue", 0.04: "tab:green", 0.12: "tab:orange", 0.3: "tab:red"}
MARKERS = {5.0: "o", 20.0: "^", 10.0: "D"}  # 10°: the absorbing-film series


def plot(table, path):
    constants = fit([{k: str(v) for k, v in r.items()} for r in table])
    kinds = [k for k in TYPE_TITLES if any(r["flake_type"] == k for r in table)]
    fig, axes = plt.subplots(2, len(kinds), figsize=(4.8 * len(kinds), 8.0), squeeze=False, sharex="col")
    for col, kind in enumerate(kinds):
        rows = [r for r in table if r["flake_type"] == kind]
        t_um = TYPES[kind]["thickness_um"]
        for line, (key, err, label) in enumerate(
            [("weighted_rel", "weighted_rel_se", "signal-weighted over 6 geometries"),
             ("worst_rel", "worst_rel_se", "worst visible geometry")]
        ):
            ax = axes[line][col]
            for r in rows:
                limit = r["series"] == "limit"
                ax.errorbar(
                    r["diameter_over_free_path"],
                    100 * r[key],
                    yerr=200 * r[err],
                    marker=MARKERS.get(r["spread_deg"], "o"),
                    color=COLOURS.get(r["volume_fraction"], "k"),
                    mfc="none" if limit else COLOURS.get(r["volume_fraction"], "k"),
                    linestyle="none",
                    markersize=5,
                    capsize=2,
                    alpha=0.85,
                )
            if line == 0:
                for vf, colour in COLOURS.items():
                    ds = [0.3 * 1.1**i for i in range(60) if 0.3 * 1.1**i <= 60]
                    ax.plot([d * vf / t_um for d in ds],
                            [100 * predict(constants, kind, d, vf, 5.0) for d in ds],
                            color=colour, lw=0.9, alpha=0.7)
                ax.set_title(TYPE_TITLES[kind], fontsize=10)
            else:
                ax.set_xlabel("diameter × volume fraction / flake thickness")
            ax.set_xscale("log")
            ax.axhline(0, color="0.5", lw=0.8)
            for level in (10, -10):
                ax.axhline(level, color="0.6", lw=0.6, ls="--")
            ax.grid(True, which="major", alpha=0.3)
            if col == 0:
                ax.set_ylabel(f"(full − fast) / fast, %\n{label}")
    handles = [plt.Line2D([], [], marker="s", color=c, linestyle="none", label=f"c = {vf:g}")
               for vf, c in COLOURS.items()]
    handles += [plt.Line2D([], [], marker=m, color="0.3", linestyle="none", label=f"spread {s:g}°")
                for s, m in MARKERS.items() if s != 10.0]
    handles += [plt.Line2D([], [], marker="D", color="0.3", linestyle="none",
                           label="spread 10°, absorbing film (0.05-0.5 /µm)")]
    handles += [plt.Line2D([], [], marker="^", color="0.3", mfc="none", linestyle="none",
                           label="d < 5 µm (limit series)"),
                plt.Line2D([], [], color="0.3", lw=0.9, label="validity rule (fit), clear film, 5°")]
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=8, frameon=False)
    fig.suptitle(
        "Full model (explicit flakes) vs fast model (continuum): 20 µm film over black, 45° incidence, "
        "5° cone, band mean 400–700 nm; bars ±2 MC std errors; d = 5, 10, 20, 50 µm along each colour",
        fontsize=9,
    )
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    fig.savefig(path, dpi=110)
    plt.close(fig)
