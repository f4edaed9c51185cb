#!/usr/bin/python3
"""Draws the scattering-table layout chart from the "tables" suite of `cloudlut bench`: the
95th-percentile single-scattering error on the density slices and between them against the
bytes of one table (half precision), one point per layout (phi_v full or folded, slices per
octave, interpolation in log2 rho or in rho). Usage: plot_table_layout.py BENCH.csv OUT.png"""
import csv
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    if len(sys.argv) != 3:
        print("usage: plot_table_layout.py BENCH.csv OUT.png", file=sys.stderr)
        return 2
    rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["suite"] == "tables"]
    if not rows:
        print("plot_table_layout.py: no rows of the tables suite", file=sys.stderr)
        return 1
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    for r in rows:
        note = r["note"]
        kib = int(r["steps"]) / 1024.0
        on = float(re.search(r"on-slice p95 ([0-9.]+)", note).group(1))
        between = float(re.search(r"between p95 ([0-9.]+)", note).group(1))
        per_octave = re.search(r"(\d+) per octave", note).group(1)
        interp = "lin ρ" if r["variant"] == "linear-rho" else "lin log ρ"
        color = "tab:blue" if r["variant"] == "linear-rho" else "tab:red"
        marker = "o" if r["method"] == "folded" else "s"
        ax.plot([kib, kib], [on * 100, between * 100], color=color, alpha=0.4)
        ax.scatter([kib], [between * 100], color=color, marker=marker)
        ax.scatter([kib], [on * 100], color=color, marker=marker, facecolors="none")
        ax.annotate(f'{r["method"]} φv, {per_octave}/oct, {interp}', (kib, between * 100),
                    textcoords="offset points", xytext=(5, 3), fontsize=7)
    ax.axhline(3.0, color="gray", linestyle="--", linewidth=0.8)
    ax.axvline(512.0, color="gray", linestyle=":", linewidth=0.8)
    ax.text(514, ax.get_ylim()[1] * 0.9, "seed's 32×64×16×8", fontsize=7, color="gray")
    ax.set_xlabel("bytes of one scattering table, KiB (half)")
    ax.set_ylabel("single scattering p95 rel. error, %")
    ax.text(0.02, 0.02, "filled: between slices; open: on slices; blue: linear in ρ, red: in log2 ρ", transform=ax.transAxes, fontsize=7)
    ax.set_yscale("log")
    ax.set_title("Scattering-table layout: error against bytes (Monte Carlo reference)")
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
