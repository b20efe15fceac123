#!/usr/bin/env python3
"""`mc --json`'s "jobs" account against the rest of the same JSON (stdin).

Per (band, incidence) job: its paths add up to settings.paths, its seconds
to at most compute_seconds, its largest relative standard error and where it
is are those of the albedo and f estimates printed beside it, and behind
--rel-error that error is at or below the target (the stop rule's promise).
With --expect-rate-model every oblique job carries the rate model's account
(explicit flakes): non-negative costs and relative variances of the five
parts, the worst cone one of the job's geometries.
"""

import json
import sys


PARTS = {"walk", "next_event", "glints", "reverse_walks", "delta_walks"}


def check_rate_model(job, geometries):
    m = job["rate_model"]
    assert m["worst"] in geometries, m
    for key in ("cost_us_per_path", "rel_variance_per_path"):
        assert set(m[key]) == PARTS, m[key]
        assert all(v >= 0.0 for v in m[key].values()), m[key]
    assert sum(m["cost_us_per_path"].values()) > 0.0, m
    assert sum(m["rel_variance_per_path"].values()) > 0.0, m


def main():
    expect_rate_model = "--expect-rate-model" in sys.argv[1:]
    d = json.load(sys.stdin)
    jobs, s = d["jobs"], d["settings"]
    bands = d["wavelengths_nm"]
    incidences = [a["theta_i_deg"] for a in d["albedo"]]
    assert len(jobs) == len(bands) * len(incidences), f"{len(jobs)} jobs"
    assert sum(j["paths"] for j in jobs) == s["paths"], "paths do not add up"
    assert sum(j["seconds"] for j in jobs) <= s["compute_seconds"] * (1 + 1e-9), "seconds over the total"
    for n, j in enumerate(jobs):
        b, i = divmod(n, len(incidences))
        assert j["wavelength_nm"] == bands[b] and j["theta_i_deg"] == incidences[i], j
        albedo = d["albedo"][i]["albedo"]
        entries = [("albedo", albedo["mean"][b], albedo["std_error"][b])]
        if i > 0:  # the oblique incidence carries the six multi-angle f
            for g in d["geometries"]:
                name = f"{incidences[i]:g}as{g['aspecular_deg']:g}"
                entries.append((name, g["brdf_per_sr"]["mean"][b], g["brdf_per_sr"]["std_error"][b]))
        rel = [(se / abs(m), name) for name, m, se in entries if m != 0.0]
        largest, at = max(rel)
        assert abs(j["largest_rel_error"] - largest) <= 1e-12 * largest, (j, largest)
        assert j["at"] == at, (j, at)
        if s["target_rel_error"] > 0.0:
            assert largest <= s["target_rel_error"], f"job {n}: {largest} over the target"
        if "rate_model" in j:
            check_rate_model(j, [name for name, _, _ in entries[1:]])
        elif expect_rate_model and i > 0:
            raise AssertionError(f"job {n}: no rate_model")
    print(f"{len(jobs)} jobs, {s['paths']} paths: consistent")


if __name__ == "__main__":
    main()
