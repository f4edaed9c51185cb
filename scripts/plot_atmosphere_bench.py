#!/usr/bin/env python3
"""The atmosphere's accuracy chart from `cloudlut bench --suite atmosphere` rows of bench.csv:
relative error of the sky from the tables against the brute-force reference at each check
(single scattering, all orders, and Hillaire 2020's series on the same axes), with the goals.
Usage: plot_atmosphere_bench.py BENCH.csv OUT.png
The bench writes check names with a comma ("sun +30 deg, zenith"), so rows are matched by
pattern rather than split as CSV."""
import re
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = {"single": {}, "all orders": {}, "Hillaire series": {}}
pattern = re.compile(r"^atmosphere,sky,(single|all orders),( Hillaire series,)?(sun [^,]+ deg), ?([^,]+),,,\d+,\d+,\d+,([0-9.eE+-]+),")
for line in open(sys.argv[1]):
    m = pattern.match(line)
    if not m:
        continue
    kind = "Hillaire series" if m.group(2) else m.group(1)
    rows[kind][f"{m.group(3)}\n{m.group(4)}"] = 100.0 * float(m.group(5))
checks = list(rows["all orders"].keys())
if not checks:
    sys.exit("no atmosphere sky rows in " + sys.argv[1])
x = range(len(checks))
fig, ax = plt.subplots(figsize=(14, 4.8), dpi=110)
ax.plot(x, [rows["Hillaire series"].get(c, float("nan")) for c in checks], "s", color="0.6", label="all orders, Hillaire 2020 series")
ax.plot(x, [rows["all orders"][c] for c in checks], "o", color="tab:blue", label="all orders (tables)")
ax.plot(x, [rows["single"].get(c, float("nan")) for c in checks], "^", color="tab:orange", label="single scattering (tables)")
ax.axhline(5, color="tab:blue", ls="--", lw=1, label="goal, all orders (5%)")
ax.axhline(2, color="tab:orange", ls="--", lw=1, label="goal, single (2%)")
ax.set_yscale("log")
ax.set_ylabel("largest relative error over R, G, B (%)")
ax.set_xticks(list(x))
ax.set_xticklabels(checks, rotation=90, fontsize=7)
ax.set_title("the sky from the atmosphere tables against the brute-force reference")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8, loc="upper left")
fig.tight_layout()
fig.savefig(sys.argv[2])
