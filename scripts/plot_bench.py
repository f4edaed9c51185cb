#!/usr/bin/python3
"""Draws the speed/accuracy chart of the bakers from `cloudlut bench`: error against time, one
panel per suite (optical-depth, scattering), one series per method, table and orders.
The renderers' chart is plot_render_bench.py. Usage: plot_bench.py BENCH.csv OUT.png"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    if len(sys.argv) != 3:
        print("usage: plot_bench.py BENCH.csv OUT.png", file=sys.stderr)
        return 2
    rows = [r for r in csv.DictReader(open(sys.argv[1]))
            if r["suite"] in ("optical-depth", "scattering") and r["error_mean"] and float(r["seconds"] or 0) > 0]
    if not rows:
        print("plot_bench.py: no rows with both time and error", file=sys.stderr)
        return 1
    panels = defaultdict(lambda: defaultdict(list))
    for r in rows:
        if r["suite"] == "scattering":
            key = f'{r["method"]} {r["table"]} orders {r["orders"]}, {r["threads"]} thr'
        else:
            key = f'{r["method"]} {r["table"]} {r["variant"]}'.strip()
        panels[r["suite"]][key].append(r)
    fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels), 4.8), squeeze=False)
    for ax, (suite, series) in zip(axes[0], sorted(panels.items())):
        for name, pts in sorted(series.items()):
            pts.sort(key=lambda r: float(r["seconds"]))
            xs = [float(r["seconds"]) for r in pts]
            ys = [float(r["error_mean"]) for r in pts]
            ax.plot(xs, ys, marker="o", label=name)
            for r, x, y in zip(pts, xs, ys):
                label = r["steps"] if r["steps"] not in ("", "0") else r["resolution"]
                if label:
                    ax.annotate(label, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("seconds (wall)")
        ax.set_ylabel("mean abs. error vs 4096 samples" if suite == "optical-depth"
                      else "mean rel. error vs Monte Carlo")
        ax.set_title(suite)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
