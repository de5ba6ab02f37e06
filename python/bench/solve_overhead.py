#!/usr/bin/env python3
"""Overhead of a Python solve over the C++ one: wall time of ARAP.solve() against the time arap_solve takes
inside C++ (report["solve_ms"]), and the per-iteration time against `iarap bench` (a separate C++ process).

The scene is the bench scene of `iarap bench` (bottom 10% along y fixed, top 10% moved by 10% of the
bounding-box diagonal along +x); every solve runs exactly --iterations iterations (tolerance -1).

    PYTHONPATH=build/python /usr/bin/python3 python/bench/solve_overhead.py ../shared/meshes/beetle.off \\
        --cli build/iarap
"""
import argparse
import json
import statistics
import subprocess
import time

import numpy as np

import iarap


def bench_scene(V):
    y = V[:, 1]
    low, high = y.min(), y.max()
    bottom = np.flatnonzero(y <= low + 0.1 * (high - low))
    top = np.flatnonzero(y >= high - 0.1 * (high - low))
    fixed = np.concatenate([bottom, top])
    targets = V[fixed].copy()
    targets[len(bottom):, 0] += 0.1 * np.linalg.norm(V.max(axis=0) - V.min(axis=0))
    return fixed, targets


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh")
    parser.add_argument("--methods", default="iarap,spokes-rims,arap")
    parser.add_argument("--iterations", type=int, default=20, help="iterations per solve")
    parser.add_argument("--repeats", type=int, default=5, help="timed solves per method (after 1 warm-up)")
    parser.add_argument("--threads", type=int, default=0, help="0: all hardware threads")
    parser.add_argument("--cli", help="path of the iarap CLI, to compare with `iarap bench` as well")
    args = parser.parse_args()

    iarap.set_thread_count(args.threads)
    V, F = iarap.read_mesh(args.mesh)
    fixed, targets = bench_scene(V)
    print(f"{args.mesh}: {len(V)} vertices, {len(fixed)} constrained, {iarap.thread_count()} threads, "
          f"{args.iterations} iterations per solve, median of {args.repeats}")
    print(f"{'method':12s} {'python ms':>10s} {'c++ ms':>10s} {'overhead':>10s} {'py ms/it':>9s} {'bench ms/it':>11s}")
    for method in args.methods.split(","):
        solver = iarap.ARAP(V, F, fixed=fixed, method=method)
        solver.solve(targets, iterations=args.iterations, tolerance=-1)  # warm-up: caches, OpenMP pool
        wall, inside, per_iteration = [], [], []
        for _ in range(args.repeats):
            start = time.perf_counter()
            solver.solve(targets, iterations=args.iterations, tolerance=-1)
            wall.append(1e3 * (time.perf_counter() - start))
            report = solver.report
            inside.append(report["solve_ms"])
            # The first iteration is a warm-up in `iarap bench` too.
            iteration_ms = report["local_ms_per_iteration"] + report["global_ms_per_iteration"]
            per_iteration.append(statistics.median(iteration_ms[1:]))
        bench = ""
        if args.cli:
            run = subprocess.run([args.cli, "bench", args.mesh, "--methods", method, "--iterations",
                                  str(args.iterations), "--threads", str(args.threads), "--json"],
                                 capture_output=True, text=True, check=True)
            bench = f"{json.loads(run.stdout)['results'][0]['iteration_ms']:11.3f}"
        w, c = statistics.median(wall), statistics.median(inside)
        print(f"{method:12s} {w:10.3f} {c:10.3f} {100 * (w - c) / c:9.2f}% {statistics.median(per_iteration):9.3f} "
              f"{bench}")


if __name__ == "__main__":
    main()
