#!/usr/bin/python3
"""Draws the ground-truth chart of `cloudlut bench --suite ground-truth`: RMSE against the
path-traced reference versus render time, one panel per scene, one series per method (ray
marching at its step counts, fixed and adaptive; the LUT particle renderer), the reference's
noise floor as a dashed line. With FRAMES.png, also the steady-state frame times at 1280×720
(bench/FrameTime.h rows): the ray marcher at 32 steps and the LUT renderer at full, 1/2 and 1/4
particle resolution, its light-space volumes built every frame (cold), kept from the frame before
(hatched) and under a sun turning 1° a frame (dotted: the sun volume built again, the diffusion
solve warm-started), and with the seed's lighting model (cross-hatched), per scene.
Usage: plot_render_bench.py BENCH.csv OUT.png [FRAMES.png]"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENES = ["one", "two", "three", "cluster", "cloudscape"]


def number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        return float("nan")


def plot_frames(rows, out):
    """Bars of steady-state frame time per scene: ray marcher, LUT at 1/1, 1/2, 1/4 resolution."""
    scenes = [s for s in SCENES if any(r["table"] == s for r in rows)]
    scenes += sorted({r["table"] for r in rows} - set(scenes))
    kinds = [("frame-raymarch", "32", "ray march, 32 steps"), ("frame-lut-volume", "1", "LUT, full resolution"),
             ("frame-lut-volume", "2", "LUT, particles at 1/2"), ("frame-lut-volume", "4", "LUT, particles at 1/4"),
             ("frame-lut-volume-kept", "1", "LUT, full, lighting kept"),
             ("frame-lut-volume-kept", "2", "LUT, 1/2, lighting kept"),
             ("frame-lut-volume-kept", "4", "LUT, 1/4, lighting kept"),
             ("frame-lut-volume-sun", "1", "LUT, full, sun turning"),
             ("frame-lut-volume-sun", "2", "LUT, 1/2, sun turning"),
             ("frame-lut-volume-sun", "4", "LUT, 1/4, sun turning"),
             ("frame-lut-volume-seed", "1", "LUT, full, seed's model"),
             ("frame-lut-volume-seed", "2", "LUT, 1/2, seed's model"),
             ("frame-lut-volume-seed", "4", "LUT, 1/4, seed's model")]
    kinds = [k for k in kinds if any(r["method"] == k[0] and r["steps"] == k[1] for r in rows)]
    fig, ax = plt.subplots(figsize=(max(6.0, 1.3 * len(scenes)), 4.2))
    width = 0.8 / len(kinds)
    for k, (method, steps, label) in enumerate(kinds):
        xs, ys = [], []
        for i, scene in enumerate(scenes):
            match = [r for r in rows if r["table"] == scene and r["method"] == method and r["steps"] == steps]
            if match:
                xs.append(i + (k - 0.5 * (len(kinds) - 1)) * width)
                ys.append(1e3 * number(match[0]["seconds"]))
        kept, sun, seed = method.endswith("-kept"), method.endswith("-sun"), method.endswith("-seed")
        ax.bar(xs, ys, width, label=label, hatch="//" if kept else ".." if sun else "xx" if seed else None,
               color="C%d" % (int(steps).bit_length() if kept or sun or seed else k),
               alpha=0.55 if kept else 0.35 if sun else 0.2 if seed else 1.0)
    ax.set_xticks(range(len(scenes)))
    ax.set_xticklabels(scenes, rotation=30, ha="right", fontsize=8)
    ax.set_yscale("log")
    ax.set_ylabel("steady-state frame, ms (llvmpipe)")
    resolution = rows[0]["resolution"] if rows else ""
    ax.set_title("frame time at %s: LUT renderer against the ray marcher" % resolution)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))  # beside the bars, not over them
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main() -> int:
    if len(sys.argv) not in (3, 4):
        print("usage: plot_render_bench.py BENCH.csv OUT.png [FRAMES.png]", file=sys.stderr)
        return 2
    rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["suite"] == "ground-truth"]
    if len(sys.argv) == 4:
        # the timed frames (frame-lut-volume-accuracy rows carry no time: their error is against the
        # reference at its own size)
        plot_frames([r for r in rows if r["method"] in ("frame-raymarch", "frame-lut-volume", "frame-lut-volume-kept",
                                                        "frame-lut-volume-sun", "frame-lut-volume-seed")],
                    sys.argv[3])
    # the frame rows' error is the upscale's, against the full-resolution frame, not the reference's
    measured = [r for r in rows if r["table"] and number(r["seconds"]) > 0 and number(r["error_mean"]) >= 0
                and not r["method"].startswith("frame-")]
    if not measured:
        print("plot_render_bench.py: no ground-truth rows with time and error", file=sys.stderr)
        return 1
    scenes = [s for s in SCENES if any(r["table"] == s for r in measured)]
    scenes += sorted({r["table"] for r in measured} - set(scenes))
    cols = min(4, len(scenes))
    rows_n = (len(scenes) + cols - 1) // cols
    fig, axes = plt.subplots(rows_n, cols, figsize=(4.6 * cols, 4.0 * rows_n), squeeze=False)
    flat = [ax for row in axes for ax in row]
    for ax in flat[len(scenes):]:
        ax.axis("off")
    for k, (ax, scene) in enumerate(zip(flat, scenes)):
        series = defaultdict(list)
        noise = None
        for r in measured:
            if r["table"] != scene:
                continue
            if r["method"] == "path-traced":
                noise = number(r["error_mean"])
                continue
            if r["method"].startswith("path-traced"):
                continue  # the path tracer's own speed rows (BVH against brute force)
            series[r["method"]].append(r)
        for method, pts in sorted(series.items()):
            pts.sort(key=lambda r: number(r["seconds"]))
            xs = [1e3 * number(r["seconds"]) for r in pts]
            ys = [number(r["error_mean"]) for r in pts]
            ax.plot(xs, ys, marker="o" if len(pts) > 1 else "s", label=method)
            for r, x, y in zip(pts, xs, ys):
                if r["steps"] not in ("", "0"):
                    ax.annotate(r["steps"], (x, y), textcoords="offset points", xytext=(3, 3), fontsize=7)
        if noise:
            ax.axhline(noise, linestyle="--", color="grey", linewidth=1, label="reference noise (RMS s.e.)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("render time, ms (llvmpipe)")
        ax.set_ylabel("RMSE vs path-traced ground truth")
        ax.set_title(scene)
        ax.grid(True, which="both", alpha=0.3)
        if k == 0:
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
