#!/usr/bin/env python3
"""Where a model's CD-J2J comes from: each predicted joint's nearest reference joint and each
reference joint's nearest predicted joint, in % of the figure size, worst first.

Run `skelfit bench ../shared/refdata --rig game_engine --method anatomical --skeletons --out DIR`
first, then `python3 tools/chamfer_nearest.py DIR MODEL [MODEL ...]` (refdata at
../shared/refdata, or REFDATA=path). Deforming joints only, as the bench's chamfer; the J2J it
prints is the bench's. Standard library only.
"""
import json
import math
import os
import sys

REFDATA = os.environ.get("REFDATA", "../shared/refdata")


def reference_rig(model):
    for category in ("quadruped", "other", "humanoid", "robustness"):
        folder = os.path.join(REFDATA, category, model)
        if os.path.isdir(folder):
            rigs = sorted(f for f in os.listdir(folder) if f.startswith("rig_"))
            preferred = [f for f in rigs if f in ("rig_gltf.json", "rig_game_engine.json")]
            return os.path.join(folder, (preferred or rigs)[0])
    sys.exit(f"no refdata model {model} under {REFDATA}")


def deforming(path):
    return [j for j in json.load(open(path))["joints"] if j.get("deform", True)]


def nearest(joint, others, size):
    best = min(others, key=lambda o: math.dist(joint["position"], o["position"]))
    return 100.0 * math.dist(joint["position"], best["position"]) / size, best["name"]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    bench = sys.argv[1]
    rows = {m["model"]: m for m in json.load(open(os.path.join(bench, "bench.json")))}
    for model in sys.argv[2:]:
        size = rows[model]["evaluation"]["figure"]["size"]
        predicted = deforming(os.path.join(bench, "skeletons", f"{model}.json"))
        reference = deforming(reference_rig(model))
        p = [(j["name"],) + nearest(j, reference, size) for j in predicted]
        r = [(j["name"],) + nearest(j, predicted, size) for j in reference]
        mp = sum(x[1] for x in p) / len(p)
        mr = sum(x[1] for x in r) / len(r)
        print(f"== {model}: J2J {(mp + mr) / 2:.2f} % = ½ (predicted→reference {mp:.2f}, "
              f"n={len(p)}; reference→predicted {mr:.2f}, n={len(r)})")
        for label, pairs in (("predicted", p), ("reference", r)):
            worst = sorted(pairs, key=lambda x: -x[1])[:12]
            print(f"  {label} joints farthest from the other rig: "
                  + ", ".join(f"{n} {e:.1f} ({b})" for n, e, b in worst))


if __name__ == "__main__":
    main()
