#!/usr/bin/env python3
"""Run one Google Benchmark of bench_montecarlo over a range of seeds.

The stop-rule time of the full model (issue 4's speed target) depends on the
seed by up to 2x and on the machine's momentary speed by ~5 %, so a single
run says little (docs/PERFORMANCE.md). This runs the benchmark once per seed
(PAINTLAB_BENCH_SEED) and prints each run's wall time and paths, then the
mean, standard deviation and range. With --baseline, a second binary runs
each seed right after the first, and the per-seed ratios (this / baseline)
are summarised with their standard error: the machine's drift then cancels.

    tools/bench_seeds/bench_seeds.py --seeds 1-20
    tools/bench_seeds/bench_seeds.py --seeds 1-14 --baseline /tmp/old/bench_montecarlo
    tools/bench_seeds/bench_seeds.py --seeds 1-12 --baseline-benchmark BM_McPearlescentOnePercent/8/5/6
"""

import argparse
import os
import re
import statistics
import subprocess
import sys

DEFAULT_BINARY = "build/release/tests/bench/bench_montecarlo"
DEFAULT_FILTER = "BM_McPearlescentOnePercent/8/1/6"


def seed_range(text):
    seeds = []
    for part in text.split(","):
        if "-" in part:
            lo, hi = part.split("-")
            seeds.extend(range(int(lo), int(hi) + 1))
        else:
            seeds.append(int(part))
    return seeds


def run(binary, benchmark, seed):
    """Wall seconds and the 'paths' counter of one run."""
    env = dict(os.environ, PAINTLAB_BENCH_SEED=str(seed))
    out = subprocess.run([binary, f"--benchmark_filter={benchmark}"], env=env, capture_output=True,
                         text=True, check=True).stdout
    for line in out.splitlines():
        if line.startswith(benchmark.split("/")[0]):
            fields = line.split()
            seconds = float(fields[1]) * {"s": 1.0, "ms": 1e-3}[fields[2]]
            paths = re.search(r"paths=([\d.]+)([kM]?)", line)
            scale = {"": 1.0, "k": 1e3, "M": 1e6}[paths.group(2)] if paths else 0.0
            return seconds, float(paths.group(1)) * scale if paths else 0.0
    raise RuntimeError(f"no result line for {benchmark} in:\n{out}")


def summary(name, values):
    sd = statistics.stdev(values) if len(values) > 1 else 0.0
    print(f"{name}: mean {statistics.mean(values):.3f}, sd {sd:.3f}, range {min(values):.3f}-{max(values):.3f}"
          f" ({len(values)} runs)")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", default="1-20", help="e.g. 1-20 or 1,3,5-8")
    parser.add_argument("--binary", default=DEFAULT_BINARY)
    parser.add_argument("--baseline", help="a second bench_montecarlo to pair each seed with")
    parser.add_argument("--benchmark", default=DEFAULT_FILTER, help="one benchmark's full name")
    parser.add_argument("--baseline-benchmark",
                        help="pair with this benchmark (of --baseline, or of the same binary) instead")
    args = parser.parse_args()
    baseline = args.baseline or (args.binary if args.baseline_benchmark else None)
    baseline_benchmark = args.baseline_benchmark or args.benchmark
    times, ratios = [], []
    for seed in seed_range(args.seeds):
        seconds, paths = run(args.binary, args.benchmark, seed)
        times.append(seconds)
        line = f"seed {seed:3d}: {seconds:7.2f} s, {paths:10.0f} paths"
        if baseline:
            base_seconds, base_paths = run(baseline, baseline_benchmark, seed)
            ratios.append(seconds / base_seconds)
            same = "same paths" if base_paths == paths else f"baseline {base_paths:.0f} paths"
            line += f"; baseline {base_seconds:7.2f} s ({same}), ratio {ratios[-1]:.3f}"
        print(line, flush=True)
    summary("seconds", times)
    if ratios:
        summary("ratio to baseline", ratios)
        if len(ratios) > 1:
            print(f"ratio's standard error: {statistics.stdev(ratios) / len(ratios) ** 0.5:.3f}")
    print(f"runs over 10 s: {sum(t > 10.0 for t in times)}")


if __name__ == "__main__":
    sys.exit(main())
