#!/usr/bin/env python3
"""Draw the figures of docs/PERFORMANCE.md from Google Benchmark JSON output.

  build/bench/bench_accuracy --benchmark_min_time=0.05 --benchmark_out=acc.json --benchmark_out_format=json
  build/bench/bench_chain --benchmark_filter='chain/' --benchmark_out=chain.json --benchmark_out_format=json
  bench/plot.py --accuracy acc.json --chain chain.json --out docs/figures

Writes accuracy-vs-time.{png,svg} (time per solve against the relative error
of the velocities, one series per scene, one point per precision; the rows
.../general-path, the general solve path where n <= 8 takes the fixed-size
one, as one more series of open squares) and
chain-scaling.{png,svg} (time per solve against n, log-log, with the slope of
a least-squares line through n >= 1000), each with its .dat and .gp beside
it.  Needs gnuplot.  Prints the fitted slope.
"""
import argparse
import json
import math
import os
import subprocess
import sys

# An exact answer has error 0; it is drawn on this floor (the plot says so).
ERROR_FLOOR = 1e-130


def load(path):
    """The runs of a benchmark JSON file, one per benchmark: with repetitions,
    its median (named as the benchmark, without the "_median" suffix);
    without, its one run."""
    with open(path, encoding="utf-8") as f:
        runs = json.load(f)["benchmarks"]
    medians = [dict(r, name=r.get("run_name", r["name"])) for r in runs if r.get("aggregate_name") == "median"]
    return medians if medians else [r for r in runs if r.get("run_type", "iteration") == "iteration"]


def nanoseconds(run):
    scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[run["time_unit"]]
    return run["cpu_time"] * scale


def gnuplot(script, out_stem):
    for terminal, ext in (("pngcairo size 900,600 font 'DejaVu Sans,11'", "png"), ("svg size 900,600 font 'DejaVu Sans,11'", "svg")):
        text = f"set terminal {terminal}\nset output '{os.path.basename(out_stem)}.{ext}'\n" + script
        subprocess.run(["gnuplot"], input=text, text=True, check=True, cwd=os.path.dirname(out_stem) or ".")
    with open(out_stem + ".gp", "w", encoding="utf-8") as f:
        f.write(script)


def accuracy(path, out):
    # One series per scene (the path numeric::solve takes: fixed-size for
    # n <= 8 in double and long double); the rows .../general-path (the
    # runtime-sized path on the same problems, the same answers bit for bit)
    # form one more series, drawn as open squares at their own times.
    series = {}
    general = "general path (n <= 8)"
    for r in load(path):
        parts = r["name"].split("/")
        scene, precision = parts[1], parts[2]
        if len(parts) > 3 and parts[3] == "general-path":
            series.setdefault(general, []).append((f"{scene} {precision}", nanoseconds(r), r["rel_error"], r["case_ok"] >= 1))
            continue
        series.setdefault(scene, []).append((precision, nanoseconds(r), r["rel_error"], r["case_ok"] >= 1))
    if general in series:  # last, so that the scenes keep their colours
        series[general] = series.pop(general)
    dat = out + "/accuracy-vs-time.dat"
    with open(dat, "w", encoding="utf-8") as f:
        for scene, points in series.items():
            f.write(f"# {scene}: precision, CPU ns per solve, relative error (floor {ERROR_FLOOR:g} = exact), case right\n")
            for precision, ns, err, ok in points:
                f.write(f'"{precision}" {ns:.6g} {max(err, ERROR_FLOOR):.6g} {1 if ok else 0}\n')
            f.write("\n\n")
    plots = []
    for k, scene in enumerate(series):
        source = "'accuracy-vs-time.dat'" if k == 0 else "''"
        if scene == general:
            plots.append(f"{source} index {k} using 2:3 with points pt 4 ps 1.6 lw 2 lc rgb 'gray40' title '{scene}'")
            plots.append(f"'' index {k} using 2:($4 == 0 ? $3 : 1/0) with points pt 6 ps 3 lw 2 lc rgb 'black' notitle")
            continue
        plots.append(f"{source} index {k} using 2:3 with linespoints pt 7 ps 1.2 title '{scene}'")
        plots.append(f"'' index {k} using 2:($4 == 0 ? $3 : 1/0) with points pt 6 ps 3 lw 2 lc rgb 'black' notitle")
        plots.append(f"'' index {k} using 2:3:1 with labels offset 0.6,0.6 left font ',8' notitle")
    script = (
        "set logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\nset xlabel 'CPU time per solve (ns)'\n"
        "set ylabel 'relative error of the velocities against the exact solution'\n"
        f"set yrange [{ERROR_FLOOR / 10:g}:100]\nset grid\nset key top right\n"
        "set title 'What accuracy costs (bench\\_accuracy; black circle: wrong case; exact = 0 drawn at 10^{-130})'\n"
        "plot " + ", \\\n     ".join(plots) + "\n"
    )
    gnuplot(script, out + "/accuracy-vs-time")


def chain(path, out):
    points = []
    for r in load(path):
        if not r["name"].startswith("chain/"):
            continue
        points.append((int(r["name"].split("/")[-1]), nanoseconds(r) / 1e6))
    points.sort()
    fit = [(math.log10(n), math.log10(t)) for n, t in points if n >= 1000]
    if len(fit) < 2:
        sys.exit("plot.py: the chain benchmark has fewer than two sizes >= 1000")
    mx = sum(x for x, _ in fit) / len(fit)
    my = sum(y for _, y in fit) / len(fit)
    slope = sum((x - mx) * (y - my) for x, y in fit) / sum((x - mx) ** 2 for x, _ in fit)
    with open(out + "/chain-scaling.dat", "w", encoding="utf-8") as f:
        f.write("# n, CPU ms per solve (ChainSolver<double>)\n")
        for n, t in points:
            f.write(f"{n} {t:.6g}\n")
    script = (
        "set logscale xy\nset format x '10^{%L}'\nset xlabel 'bodies n'\nset ylabel 'CPU time per solve (ms)'\nset grid\n"
        f"set key top left\nset title 'Long chains: time per solve, log-log slope {slope:.2f} for n >= 1000 (bench\\_chain)'\n"
        f"plot 'chain-scaling.dat' using 1:2 with linespoints pt 7 ps 1.2 title 'ChainSolver, double', \\\n"
        f"     10**({my - slope * mx:.6g}) * x**{slope:.6g} with lines dt 2 title 'fit: slope {slope:.2f}'\n"
    )
    gnuplot(script, out + "/chain-scaling")
    print(f"chain: log-log slope {slope:.3f} over n >= 1000")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--accuracy", help="JSON output of bench_accuracy")
    p.add_argument("--chain", help="JSON output of bench_chain")
    p.add_argument("--out", default="docs/figures", help="folder of the figures (default docs/figures)")
    a = p.parse_args()
    if not a.accuracy and not a.chain:
        p.error("give --accuracy and/or --chain")
    os.makedirs(a.out, exist_ok=True)
    if a.accuracy:
        accuracy(a.accuracy, a.out)
    if a.chain:
        chain(a.chain, a.out)


if __name__ == "__main__":
    main()
