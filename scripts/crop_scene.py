#!/usr/bin/env python3
"""Crop a particle scene (docs/SCENE_FORMAT.md) to the particles whose centres lie in an x-z box
and give it a new camera; writes the ground-truth bench's cloudscape patch:

  ./build/cloudlut render --luts LUTS --dump-particles /tmp/all.json --out /tmp/all.png
  scripts/crop_scene.py /tmp/all.json data/bench_scenes/cloudscape-patch.json \\
      --x 4000 8000 --z -12000 -8500 --eye 8800 5000 -14650 --target 6000 1700 -10250 --fov 38
"""
import argparse
import json

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("src")
ap.add_argument("dst")
ap.add_argument("--x", nargs=2, type=float, required=True, metavar=("MIN", "MAX"), help="centre x range (m)")
ap.add_argument("--z", nargs=2, type=float, required=True, metavar=("MIN", "MAX"), help="centre z range (m)")
ap.add_argument("--eye", nargs=3, type=float, required=True)
ap.add_argument("--target", nargs=3, type=float, required=True)
ap.add_argument("--fov", type=float, required=True, help="vertical field of view (degrees)")
a = ap.parse_args()

with open(a.src) as f:
    scene = json.load(f)
kept = [p for p in scene["particles"]
        if a.x[0] <= p["center"][0] <= a.x[1] and a.z[0] <= p["center"][2] <= a.z[1]]
out = {
    "description": "Ground-truth bench: a patch of %d particles of %s (%s), centres in x [%g, %g] m, "
                   "z [%g, %g] m, seen from above on the sun's side" %
                   (len(kept), scene.get("description", a.src), "cloudlut render --dump-particles",
                    a.x[0], a.x[1], a.z[0], a.z[1]),
    "camera": {"eye": a.eye, "target": a.target, "fov_deg": a.fov},
    "sun": scene["sun"],
    "sky": scene["sky"],
    "particles": kept,
}
with open(a.dst, "w") as f:  # one particle per line
    head = json.dumps({k: v for k, v in out.items() if k != "particles"}, indent=1)[:-2]
    f.write(head + ',\n "particles": [\n')
    f.write(",\n".join("  " + json.dumps(p) for p in kept) + "\n ]\n}\n")
print("wrote %s: %d particles" % (a.dst, len(kept)))
