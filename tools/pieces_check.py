#!/usr/bin/env python3
"""Pieces check: bodies cut into separate rigid pieces with gaps at the joints, like a robot.

Robots and mannequins (Mixamo's bots among them) are built of closed pieces, one per limb
segment, with a gap at each joint. For every MakeHuman body under REFDATA/humanoid (a folder
whose reference rig is rig_game_engine.json) this tool

1. cuts the body into 14 closed pieces: head with neck, trunk (pelvis, chest and clavicles),
   and per side upper arm, forearm, hand, thigh, shin and foot. Each vertex goes to its
   nearest reference bone; the vertices within GAP/2 of a joint shared by two pieces, measured
   along the bone, are taken out with their triangles, and each hole left is closed by a fan
   about its centroid. GAP is a fraction of the height (default 0.35, 0.6, 0.9, 1.2 and 1.7 %:
   6 to 30 mm on a 1.75 m body);
2. rigs the whole body and every pieced copy with `skelfit rig --keep-frame --skeleton-json`
   and the default options;
3. compares the core joints (pelvis, neck, head, shoulders, elbows, wrists, hips, knees,
   ankles) with the reference's `canonical` map, mean % of the height, and prints per gap the
   mean and the joints more than 2 % of the height off.

Standard-library Python only. Usage (from the repository, after `cargo build --release`):

    python3 tools/pieces_check.py [--refdata ../shared/refdata] [--skelfit target/release/skelfit]
                                  [--work /tmp/pieces_check] [--gaps=0.35,0.6,0.9,1.2,1.7]
                                  [MODEL ...]
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from facing_check import rig  # noqa: E402
from zup_check import CORE, core_error, model_folders, reference_canonical  # noqa: E402

GAPS = "0.35,0.6,0.9,1.2,1.7"


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def read_obj(path):
    positions, triangles = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                positions.append(tuple(float(t) for t in line.split()[1:4]))
            elif line.startswith("f "):
                idx = [int(t.split("/")[0]) - 1 for t in line.split()[1:]]
                triangles += [(idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1)]
    return positions, triangles


def bones(joints):
    """(piece, bone start, bone end) for every bone a vertex may go to."""
    up = (0.0, 1.0, 0.0)
    j = joints
    head_top = tuple(a + 0.1 * (j["head"][1] - j["pelvis"][1]) * u for a, u in zip(j["head"], up))
    out = [("head", j["neck_01"], head_top), ("trunk", j["pelvis"], j["neck_01"]),
           ("trunk", j["thigh_l"], j["thigh_r"])]
    for s in "lr":
        foot, ball = j[f"foot_{s}"], j[f"ball_{s}"]
        toe = tuple(b + 0.5 * (b - f) for f, b in zip(foot, ball))
        out += [("trunk", j[f"clavicle_{s}"], j[f"upperarm_{s}"]),
                (f"upper arm {s}", j[f"upperarm_{s}"], j[f"lowerarm_{s}"]),
                (f"forearm {s}", j[f"lowerarm_{s}"], j[f"hand_{s}"]),
                (f"hand {s}", j[f"hand_{s}"], j[f"middle_03_{s}"]),
                (f"thigh {s}", j[f"thigh_{s}"], j[f"calf_{s}"]),
                (f"shin {s}", j[f"calf_{s}"], foot),
                (f"foot {s}", foot, toe)]
    return out


def pieced(positions, triangles, joints, gap):
    """The body cut into closed pieces with `gap` (mesh units) at the joints between them."""
    segs = bones(joints)
    along, nearest = [], []
    for p in positions:
        best = None
        for k, (_, a, b) in enumerate(segs):
            ab = sub(b, a)
            length = math.sqrt(dot(ab, ab))
            t = max(0.0, min(1.0, dot(sub(p, a), ab) / (length * length)))
            d = math.dist(p, tuple(x + t * y for x, y in zip(a, ab)))
            if best is None or d < best[0]:
                best = (d, k, t * length, length)
        nearest.append(best[1])
        along.append((best[2], best[3]))
    # A bone's end is a cut when another piece's bone starts or ends there.
    cut = []
    for piece, a, b in segs:
        cut.append(tuple(any(q != piece and (e == a2 or e == b2) for q, a2, b2 in segs)
                         for e in (a, b)))
    keep = []
    for v, k in enumerate(nearest):
        t, length = along[v]
        keep.append(not ((cut[k][0] and t < gap / 2) or (cut[k][1] and t > length - gap / 2)))
    piece_of = [segs[k][0] for k in nearest]
    out_positions = list(positions)
    out_triangles = []
    for piece in sorted(set(piece_of)):
        own = [t for t in triangles if all(keep[v] and piece_of[v] == piece for v in t)]
        edges = {}
        for a, b, c in own:
            for e in ((a, b), (b, c), (c, a)):
                edges[e] = edges.get(e, 0) + 1
        # Boundary edges: no twin; the cap runs the other way round.
        following = {b: a for (a, b) in edges if (b, a) not in edges}
        seen = set()
        for start in list(following):
            if start in seen:
                continue
            loop, v = [start], following[start]
            seen.add(start)
            while v != start and v in following and v not in seen:
                loop.append(v)
                seen.add(v)
                v = following[v]
            if v != start or len(loop) < 3:
                continue
            centre = tuple(sum(positions[i][c] for i in loop) / len(loop) for c in range(3))
            out_positions.append(centre)
            ci = len(out_positions) - 1
            own += [(loop[i], loop[(i + 1) % len(loop)], ci) for i in range(len(loop))]
        out_triangles += own
    return out_positions, out_triangles


def write_obj(path, positions, triangles):
    with open(path, "w") as f:
        for p in positions:
            f.write("v %r %r %r\n" % p)
        for t in triangles:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def body_folders(refdata, models):
    """The MakeHuman body folders under REFDATA/humanoid with a rig_game_engine.json."""
    return [f for f in model_folders(refdata, ("humanoid",), models)
            if os.path.exists(os.path.join(f, "rig_game_engine.json"))
            and os.path.basename(f).startswith("mh_")]


def body(folder):
    """A body's reference canonical joints, all its reference joints by name, its mesh and its
    height."""
    with open(os.path.join(folder, "rig_game_engine.json")) as f:
        joints = {j["name"]: tuple(j["position"]) for j in json.load(f)["joints"]}
    positions, triangles = read_obj(os.path.join(folder, "mesh.obj"))
    ys = [p[1] for p in positions]
    return reference_canonical(folder), joints, positions, triangles, max(ys) - min(ys)


def scored(skeleton, reference, height, limit):
    """The text for one rig: its core error against `reference` (% of `height`), the core joints
    more than `limit` % off in brackets, and the core joints missing."""
    by_name = {j["name"]: tuple(j["position"]) for j in skeleton["joints"]}
    found = {k: by_name[v] for k, v in skeleton.get("canonical", {}).items() if v in by_name}
    error, missing = core_error(found, reference, height)
    worst = [f"{k} {100 * math.dist(found[k], reference[k]) / height:.1f}"
             for k in CORE if k in found and k in reference
             and math.dist(found[k], reference[k]) > limit / 100 * height]
    return ("-" if error is None else f"{error:.2f}") \
        + (f" [{', '.join(worst)}]" if worst else "") \
        + (f" (missing {', '.join(missing)})" if missing else "")


def rig_and_score(skelfit, mesh, positions, triangles, reference, height, limit=1.5):
    """Writes the mesh to `mesh` (.obj), rigs it with the defaults and returns the skeleton
    (None when the rig failed) and a line: `scored` against `reference` with the joints more
    than `limit` % off, and the warnings' codes."""
    write_obj(mesh, positions, triangles)
    skeleton = rig(skelfit, mesh, mesh[:-4] + ".json")
    if skeleton is None:
        return None, "failed"
    warnings = skeleton.get("run", {}).get("warnings", [])
    codes = sorted({w.get("code", "?") for w in warnings if isinstance(w, dict)})
    return skeleton, scored(skeleton, reference, height, limit) \
        + (f"  {' '.join(codes)}" if codes else "")


def body_check_args(doc, work, option, default, help=None, models=None):
    """The command line shared by the body checks (pieces, props, garments): MODEL names,
    --refdata, --skelfit, --work (default `work`) and the check's own `option`. Returns the
    arguments and the MakeHuman body folders to run on (`models` when none are named; all
    when that is None too), or None after saying why there are none; creates the work folder.
    """
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("models", nargs="*", metavar="MODEL")
    parser.add_argument("--refdata", default="../shared/refdata")
    parser.add_argument("--skelfit", default="target/release/skelfit")
    parser.add_argument("--work", default=work)
    parser.add_argument(option, default=default, help=help)
    args = parser.parse_args()
    folders = body_folders(args.refdata, args.models or models)
    if not folders:
        print(f"no MakeHuman bodies with rig_game_engine.json under {args.refdata}/humanoid")
        return args, None
    os.makedirs(args.work, exist_ok=True)
    return args, folders


def main():
    args, folders = body_check_args(__doc__, "/tmp/pieces_check", "--gaps", GAPS,
                                    "gaps, %% of the height (comma-separated)")
    if folders is None:
        return 1
    gaps = [0.0] + [float(g) for g in args.gaps.split(",")]
    print("core mean, % of height, per gap (% of height); joints over 2 % in brackets")
    for folder in folders:
        model = os.path.basename(folder)
        reference, joints, positions, triangles, height = body(folder)
        cells = []
        for gap in gaps:
            mesh = os.path.join(args.work, f"{model}_gap{gap:g}.obj")
            if gap == 0:
                write_obj(mesh, positions, triangles)
            else:
                write_obj(mesh, *pieced(positions, triangles, joints, gap / 100 * height))
            skeleton = rig(args.skelfit, mesh, mesh[:-4] + ".json")
            text = "failed" if skeleton is None else scored(skeleton, reference, height, 2.0)
            cells.append(f"{gap:g}: {text}")
        print(f"{model}\n  " + "\n  ".join(cells), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
