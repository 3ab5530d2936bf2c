#!/usr/bin/env python3
"""Facing check: every humanoid turned about up, rigged with no orientation flags.

glTF says an asset's front faces +Z, but real files also face -Z or +-X. For every model folder
under REFDATA/humanoid this tool

1. writes copies of mesh.obj turned about +Y by 90, 180 and 270 degrees (forward +Z becomes
   +X, -Z, -X): (x, y, z) -> (x cos a + z sin a, y, -x sin a + z cos a);
2. rigs the original and every copy with `skelfit rig --keep-frame --skeleton-json` and NO
   --up/--forward (both automatic);
3. turns each rig's joints back and compares its core joints (pelvis, neck, head, shoulders,
   elbows, wrists, hips, knees, ankles) with the reference rig's `canonical` map, mean % of
   the figure's height (as tools/zup_check.py does).

A figure rigged facing the wrong way has its left and right swapped (about 20 % of height
off); one rigged sideways loses joints. It prints per model the core error of each turn and
the forward each run chose ("=" the file's +Z kept, "feet" found from the feet, "?" across the
paired limbs with no sign to go by), and lists the turns more than --limit % of height worse
than the unturned rig; the exit code is 1 when there is one.

Standard-library Python only. Usage (from the repository, after `cargo build --release`):

    python3 tools/facing_check.py [--refdata ../shared/refdata] [--skelfit target/release/skelfit]
                                  [--work /tmp/facing_check] [--limit 1.0] [--turns=90,180,270]
                                  [MODEL ...]

`--turns=-3,-1,1,3` measures figures a few degrees off the file's axes instead (forward snaps to
the axis; what changes is how the voxels fall on the figure).
"""
import argparse
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from zup_check import core_error, model_folders, reference_canonical  # noqa: E402

TURNS = "90,180,270"


def turn(p, degrees):
    """`p` turned about +Y by `degrees` (exact for quarter turns)."""
    a = math.radians(degrees)
    c, s = round(math.cos(a), 12), round(math.sin(a), 12)
    x, y, z = p
    return (x * c + z * s, y, -x * s + z * c)


def turned_obj(src, dst, degrees):
    """Write `src` turned by `degrees` to `dst`; returns the height (y extent)."""
    lo, hi = math.inf, -math.inf
    with open(src) as f, open(dst, "w") as out:
        for line in f:
            if line.startswith("v "):
                p = tuple(float(t) for t in line.split()[1:4])
                lo, hi = min(lo, p[1]), max(hi, p[1])
                out.write("v %r %r %r\n" % turn(p, degrees))
            else:
                out.write(line)
    return hi - lo


def rig(skelfit, mesh, json_path):
    glb = json_path[:-5] + ".glb"
    if os.path.exists(json_path):
        os.remove(json_path)
    cmd = [skelfit, "rig", mesh, "-o", glb, "--skeleton-json", json_path, "--keep-frame", "-q"]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0 or not os.path.exists(json_path):
        print(f"  skelfit failed ({done.returncode}): {done.stderr.strip()[:300]}")
        return None
    with open(json_path) as f:
        return json.load(f)


def how(skeleton):
    found = skeleton["run"].get("forward_found") or {}
    note = found.get("note", "")
    if note.startswith("kept"):
        return "="
    return "feet" if "feet point" in note else "?"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("models", nargs="*", metavar="MODEL")
    parser.add_argument("--refdata", default="../shared/refdata")
    parser.add_argument("--skelfit", default="target/release/skelfit")
    parser.add_argument("--work", default="/tmp/facing_check")
    parser.add_argument("--limit", type=float, default=1.0)
    parser.add_argument("--turns", default=TURNS,
                        help="comma-separated angles in degrees (default 90,180,270; e.g. "
                             "--turns=-3,-1,1,3 for figures a little off the file's axes)")
    args = parser.parse_args()
    turns = [0.0] + [float(t) for t in args.turns.split(",") if float(t) != 0.0]

    folders = model_folders(args.refdata, ("humanoid",), args.models)
    if not folders:
        print(f"no humanoid models under {args.refdata}")
        return 1
    os.makedirs(args.work, exist_ok=True)
    failing = []
    for folder in folders:
        model = os.path.basename(folder)
        reference = reference_canonical(folder)
        if not reference:
            continue
        cells, base = [], None
        for degrees in turns:
            mesh = os.path.join(args.work, f"{model}_{degrees:g}.obj")
            height = turned_obj(os.path.join(folder, "mesh.obj"), mesh, degrees)
            skeleton = rig(args.skelfit, mesh, mesh[:-4] + ".json")
            if skeleton is None:
                cells.append(f"{degrees:g}: failed")
                failing.append((model, degrees, "rig failed"))
                continue
            by_name = {j["name"]: turn(j["position"], -degrees) for j in skeleton["joints"]}
            found = {k: by_name[v] for k, v in skeleton.get("canonical", {}).items() if v in by_name}
            error, missing = core_error(found, reference, height)
            text = "-" if error is None else f"{error:.2f} %"
            cells.append(f"{degrees:g}: {text} {how(skeleton)}"
                         + (f" (missing {len(missing)})" if missing else ""))
            if degrees == 0:
                base = error
            elif error is None or (base is not None and error > base + args.limit):
                failing.append((model, degrees, text))
        print(f"{model:34s} " + " | ".join(cells), flush=True)
    print()
    if failing:
        print(f"{len(failing)} turns more than {args.limit} % of height worse than unturned:")
        for model, degrees, why in failing:
            print(f"  {model} turned {degrees:g}: {why}")
        return 1
    print(f"all {len(folders)} models: every turn within {args.limit} % of height of the unturned rig")
    return 0


if __name__ == "__main__":
    sys.exit(main())
