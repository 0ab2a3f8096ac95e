#!/usr/bin/env python3
"""The Python module beside the C++ library, in one run (issue 14; docs/PERFORMANCE.md).

    /usr/bin/python3 bench/python_side_by_side.py BUILD_DIR

BUILD_DIR is a build configured with -DSUPERBALL_BUILD_PYTHON=ON and
-DSUPERBALL_BUILD_BENCH=ON: the module is imported from BUILD_DIR/python and
BUILD_DIR/bench/bench_python_baseline gives the C++ figures of the same calls.

- sweep: the paper scene (§4.4, alpha_2 reading), K34 over 10^5 exact values
  from 0 to 20 in double, on 1 and 2 threads: numeric::sweep in C++,
  superball.sweep(scene, "K.3-4", superball.linspace(0, 20, 100000)) in
  Python (its NumPy arrays and case names included); the median of
  REPEATS runs each, the C++ and Python runs interleaved.
- solve: present::solve_scene in C++, superball.solve(scene, precision) in
  Python, per call (median of REPEATS timeit batches); the difference is the
  Python call's overhead.
"""
import json
import os
import statistics
import subprocess
import sys
import time
import timeit

REPEATS = int(os.environ.get("REPEATS", "5"))


def cpp(build, bench_filter, min_time=None):
    args = [os.path.join(build, "bench", "bench_python_baseline"), f"--benchmark_filter={bench_filter}", "--benchmark_format=json"]
    if min_time:
        args.append(f"--benchmark_min_time={min_time}")
    out = json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)
    return {b["name"]: b["real_time"] * {"ms": 1e-3, "us": 1e-6, "ns": 1e-9}[b["time_unit"]] for b in out["benchmarks"]}


def main():
    build = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else "build")
    sys.path.insert(0, os.path.join(build, "python"))
    import superball

    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    scene = superball.Scene.load(os.path.join(root, "cases", "scenes", "paper-4.4-alpha2.toml"))
    values = superball.linspace(0, 20, 100000)
    print(f"module {superball.__file__}\npython {sys.version.split()[0]} ({sys.executable}), {os.cpu_count()} cores, {REPEATS} repeats\n")
    print(f"{'sweep of 10^5 values (s)':28} {'C++':>9} {'Python':>9} {'ratio':>7}")
    for threads in (1, 2):
        c, p = [], []
        for _ in range(REPEATS):
            c.append(cpp(build, f"sweep/1e5/{threads}/", "0.1")[f"sweep/1e5/{threads}/real_time"])
            start = time.perf_counter()
            s = superball.sweep(scene, "K.3-4", values, threads=threads)
            p.append(time.perf_counter() - start)
            assert s.ok and s.velocities.shape == (100000, 4)
        c_med, p_med = statistics.median(c), statistics.median(p)
        print(f"{f'{threads} thread' + ('s' if threads > 1 else ''):28} {c_med:9.3f} {p_med:9.3f} {p_med / c_med:7.3f}")
    print(f"\n{'solve, per call (µs)':28} {'C++':>9} {'Python':>9} {'overhead':>9}")
    for precision in ("double", "exact"):
        c = statistics.median(cpp(build, f"solve/{precision}$")[f"solve/{precision}"] for _ in range(REPEATS))
        timer = timeit.Timer(lambda: superball.solve(scene, precision))
        number, _ = timer.autorange()
        p = statistics.median(t / number for t in timer.repeat(REPEATS, number))
        print(f"{precision:28} {c * 1e6:9.2f} {p * 1e6:9.2f} {(p - c) * 1e6:9.2f}")


if __name__ == "__main__":
    main()
