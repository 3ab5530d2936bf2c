#!/usr/bin/env python3
"""Z-up check: every humanoid rigged turned Z-up with no orientation flags, against its Y-up rig.

Issue 21 asks for "a Z-up copy of every humanoid, rigged with no orientation flags, within the
same bounds". For every model folder under REFDATA/humanoid and REFDATA/robustness this tool

1. writes a Z-up copy of mesh.obj, turned as Blender turns a Y-up file to Z-up (up +Y to +Z,
   forward +Z to -Y): (x, y, z) -> (x, -z, y);
2. rigs the original and the copy with `skelfit rig --keep-frame --skeleton-json`, the copy with
   NO --up/--forward (both automatic), the original with skelfit's defaults too;
3. turns the copy's joints back ((x, y, z) -> (x, z, -y)) and compares every joint the two rigs
   share by name with the Y-up rig's, in % of the figure's height (its extent along y);
4. if the folder holds a reference rig with a `canonical` map (rig_game_engine.json, else its
   only rig_*.json), compares the core joints (pelvis, neck, head, shoulders, elbows, wrists,
   hips, knees, ankles) of both rigs with the reference, mean % of height (as the bench's core
   error, but with this tool's height).

It prints per model: the automatic up the Z-up run chose and its confidence, joints matched
(and joints only one rig has), mean and max deviation Z-up vs Y-up in % of height, the worst
joints, and the core error of the Y-up and the Z-up rig against the reference. The last lines
list the models whose Z-up run did not choose +Z or deviates by more than --limit % (default
2.0) at some joint; the exit code is 1 when there is one.

Standard-library Python only. Usage (from the repository, after `cargo build --release`):

    python3 tools/zup_check.py [--refdata ../shared/refdata] [--skelfit target/release/skelfit]
                               [--work /tmp/zup_check] [--limit 2.0] [--worst 3] [MODEL ...]

MODEL names (folder names, e.g. quaternius_knight) restrict the run to those models.
"""
import argparse
import json
import math
import os
import subprocess
import sys

CORE = [
    "pelvis", "neck", "head",
    "shoulder_L", "shoulder_R", "elbow_L", "elbow_R", "wrist_L", "wrist_R",
    "hip_L", "hip_R", "knee_L", "knee_R", "ankle_L", "ankle_R",
]


def z_up_obj(src, dst):
    """Write `src` turned Z-up ((x, y, z) -> (x, -z, y)) to `dst`; returns the y extent."""
    lo, hi = math.inf, -math.inf
    with open(src) as f, open(dst, "w") as out:
        for line in f:
            if line.startswith("v "):
                x, y, z = (float(t) for t in line.split()[1:4])
                lo, hi = min(lo, y), max(hi, y)
                out.write(f"v {x!r} {-z!r} {y!r}\n")
            else:
                out.write(line)
    return hi - lo


def rig(skelfit, mesh, json_path):
    """Rig `mesh` with default orientation; returns the skeleton JSON or None (error printed)."""
    glb = json_path[:-5] + ".glb"
    cmd = [skelfit, "rig", mesh, "-o", glb, "--skeleton-json", json_path, "--keep-frame", "-q"]
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0 or not os.path.exists(json_path):
        print(f"  skelfit failed ({done.returncode}): {done.stderr.strip()[:300]}")
        return None
    with open(json_path) as f:
        return json.load(f)


def positions(skeleton, turn_back=False):
    out = {}
    for j in skeleton["joints"]:
        x, y, z = j["position"]
        out[j["name"]] = (x, z, -y) if turn_back else (x, y, z)
    return out


def canonical_positions(skeleton, turn_back=False):
    by_name = positions(skeleton, turn_back)
    return {k: by_name[v] for k, v in skeleton.get("canonical", {}).items() if v in by_name}


def reference_canonical(folder):
    names = sorted(n for n in os.listdir(folder) if n.startswith("rig_") and n.endswith(".json"))
    pick = "rig_game_engine.json" if "rig_game_engine.json" in names else (
        names[0] if len(names) == 1 else None)
    if pick is None:
        return None
    with open(os.path.join(folder, pick)) as f:
        ref = json.load(f)
    by_name = {j["name"]: tuple(j["position"]) for j in ref["joints"]}
    return {k: by_name[v] for k, v in ref.get("canonical", {}).items() if v in by_name}


def core_error(found, reference, height):
    """Mean core-joint distance, % of height, and the core keys the reference maps but `found` lacks."""
    keys = [k for k in CORE if k in reference]
    have = [k for k in keys if k in found]
    if not have:
        return None, keys
    mean = sum(math.dist(found[k], reference[k]) for k in have) / len(have)
    return 100.0 * mean / height, [k for k in keys if k not in found]


def model_folders(refdata, kinds, models):
    """The model folders (with a mesh.obj) under REFDATA/KIND for each of `kinds`, sorted; only
    those named in `models` when it is not empty."""
    folders = []
    for kind in kinds:
        root = os.path.join(refdata, kind)
        if os.path.isdir(root):
            folders += [os.path.join(root, m) for m in sorted(os.listdir(root))
                        if os.path.exists(os.path.join(root, m, "mesh.obj"))]
    return [f for f in folders if not models or os.path.basename(f) in models]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("models", nargs="*", metavar="MODEL")
    parser.add_argument("--refdata", default="../shared/refdata")
    parser.add_argument("--skelfit", default="target/release/skelfit")
    parser.add_argument("--work", default="/tmp/zup_check")
    parser.add_argument("--limit", type=float, default=2.0)
    parser.add_argument("--worst", type=int, default=3)
    args = parser.parse_args()

    folders = model_folders(args.refdata, ("humanoid", "robustness"), args.models)
    if not folders:
        print(f"no humanoid models under {args.refdata}")
        return 1
    os.makedirs(args.work, exist_ok=True)

    failing = []
    for folder in folders:
        model = os.path.basename(folder)
        print(model)
        z_mesh = os.path.join(args.work, model + "_zup.obj")
        height = z_up_obj(os.path.join(folder, "mesh.obj"), z_mesh)
        y_rig = rig(args.skelfit, os.path.join(folder, "mesh.obj"),
                    os.path.join(args.work, model + "_yup.json"))
        z_rig = rig(args.skelfit, z_mesh, os.path.join(args.work, model + "_zup.json"))
        if y_rig is None or z_rig is None:
            failing.append((model, "rig failed"))
            continue
        found = z_rig["run"].get("up_found", {})
        up = found.get("up", z_rig["run"].get("up"))
        up_name = next((s["name"] for s in found.get("scores", []) if s.get("up") == up), str(up))
        print(f"  auto up      {up_name} (confidence {found.get('confidence', float('nan')):.2f})")
        y_at, z_at = positions(y_rig), positions(z_rig, turn_back=True)
        shared = [n for n in y_at if n in z_at]
        only = sorted(set(y_at) ^ set(z_at))
        offs = sorted(((100.0 * math.dist(y_at[n], z_at[n]) / height, n) for n in shared),
                      reverse=True)
        mean = sum(o for o, _ in offs) / len(offs) if offs else float("nan")
        worst = ", ".join(f"{n} {o:.2f}" for o, n in offs[: args.worst])
        print(f"  joints       {len(shared)} matched, {len(only)} in one rig only"
              + (f" ({', '.join(only[:6])}{', ...' if len(only) > 6 else ''})" if only else ""))
        print(f"  Z-up vs Y-up mean {mean:.2f} %, max {offs[0][0] if offs else float('nan'):.2f} %"
              f" of height; worst: {worst}")
        reference = reference_canonical(folder)
        if reference:
            y_core, y_missing = core_error(canonical_positions(y_rig), reference, height)
            z_core, z_missing = core_error(canonical_positions(z_rig, True), reference, height)
            fmt = lambda e, m: (f"{e:.2f} %" if e is not None else "-") + (
                f" (missing {', '.join(m)})" if m else "")
            print(f"  core vs ref  Y-up {fmt(y_core, y_missing)}, Z-up {fmt(z_core, z_missing)}")
        if up != [0.0, 0.0, 1.0]:
            failing.append((model, f"auto up {up_name}"))
        elif offs and offs[0][0] > args.limit:
            failing.append((model, f"{offs[0][1]} {offs[0][0]:.2f} % > {args.limit} %"))
        elif only:
            failing.append((model, f"{len(only)} joints in one rig only"))
    print()
    if failing:
        print(f"{len(failing)} of {len(folders)} models off:")
        for model, why in failing:
            print(f"  {model}: {why}")
        return 1
    print(f"all {len(folders)} models: auto up +Z, every joint within {args.limit} % of height")
    return 0


if __name__ == "__main__":
    sys.exit(main())
