#!/usr/bin/env python3
"""Garments check: a body dressed as game characters are, in open single-sided clothing.

Game characters wear clothes modelled as open sheets over the body (or instead of the body
under them), and robes, coats and capes that stand away from it. For every MakeHuman body
under REFDATA/humanoid (a folder whose reference rig is rig_game_engine.json) this tool writes
copies of mesh.obj with one garment each and rigs them with `skelfit rig --keep-frame
--skeleton-json` and the default options:

  jacket          the trunk's and upper arms' faces copied 2 cm out along the vertex normals:
                  an open shell over the body, open at the neck, waist and sleeves
  jacket_only     the jacket with the body's faces under it deleted (the body hidden under
                  clothing removed, as game assets do)
  sleeves_only    the same down to the wrists, 1.5 cm out
  pants_only      the same over the legs and the trunk below the waist, 1.5 cm out
  skirt           an open bell (a flaring tube, wound outwards) from the waist to the knees
  robe            the bell down to mid-shin
  coat            the jacket and the skirt
  cape            an open double-sided sheet from the shoulders down the back to the knees

Every part of a vertex is its nearest reference bone; sizes are for a 1.75 m body, scaled
with the height. It prints the core error (pelvis, neck, head, shoulders, elbows, wrists,
hips, knees, ankles) against the reference's `canonical` map, % of the height, with the
joints more than 1.5 % off and the warnings' codes. The reference is the undressed body's:
the garment should leave its joints where they are.

Standard-library Python only. Usage (from the repository, after `cargo build --release`):

    python3 tools/garments_check.py [--refdata ../shared/refdata] [--skelfit target/release/skelfit]
                                    [--work /tmp/garments_check] [--garments jacket,robe,...]
                                    [MODEL ...]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pieces_check import body, body_check_args, bones, rig_and_score  # noqa: E402

GARMENTS = "jacket,jacket_only,sleeves_only,pants_only,skirt,robe,coat,cape"


def segment_distance(p, a, b):
    ab = [b[i] - a[i] for i in range(3)]
    ap = [p[i] - a[i] for i in range(3)]
    t = sum(x * y for x, y in zip(ab, ap)) / max(1e-12, sum(x * x for x in ab))
    t = max(0.0, min(1.0, t))
    return math.dist(p, [a[i] + t * ab[i] for i in range(3)])


def parts(positions, joints):
    """The piece (pieces_check's bones) of every vertex."""
    segments = bones(joints)
    return [min(segments, key=lambda s: segment_distance(p, s[1], s[2]))[0] for p in positions]


def normals(positions, triangles):
    n = [[0.0, 0.0, 0.0] for _ in positions]
    for a, b, c in triangles:
        u = [positions[b][i] - positions[a][i] for i in range(3)]
        v = [positions[c][i] - positions[a][i] for i in range(3)]
        f = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        for k in (a, b, c):
            for i in range(3):
                n[k][i] += f[i]
    out = []
    for x in n:
        length = math.sqrt(sum(c * c for c in x))
        out.append([c / length for c in x] if length > 0 else [0.0, 1.0, 0.0])
    return out


def shell(positions, triangles, keep, offset, delete):
    """The faces whose three vertices `keep` accepts, copied `offset` out along the vertex
    normals; with `delete`, the body's own faces there are removed."""
    n = normals(positions, triangles)
    chosen = [t for t in triangles if all(keep(v) for v in t)]
    V = list(positions)
    index = {}
    for t in chosen:
        for v in t:
            if v not in index:
                index[v] = len(V)
                V.append(tuple(positions[v][i] + n[v][i] * offset for i in range(3)))
    kept = set(chosen) if delete else set()
    F = [t for t in triangles if t not in kept]
    F += [tuple(index[v] for v in t) for t in chosen]
    return V, F


def bell(V, F, joints, bottom, s):
    """An open flaring tube from just above the pelvis down to height `bottom`, wound
    outwards."""
    pelvis = joints["pelvis"]
    top = pelvis[1] + 0.05 * s
    rows, segments, r0 = 10, 32, 0.19 * s
    first = len(V)
    for r in range(rows + 1):
        t = r / rows
        radius = r0 * (1 + 0.6 * t)
        for k in range(segments):
            a = 2 * math.pi * k / segments
            V.append((pelvis[0] + 1.15 * radius * math.cos(a), top + (bottom - top) * t,
                      pelvis[2] + 0.9 * radius * math.sin(a)))
    for r in range(rows):
        for k in range(segments):
            a = first + r * segments + k
            b = first + r * segments + (k + 1) % segments
            F += [(a, b, a + segments), (b, b + segments, a + segments)]


def cape(V, F, joints, s):
    """A double-sided sheet behind the back from the shoulders to the knees."""
    j = joints
    neck = [(a + b) / 2 for a, b in zip(j["clavicle_l"], j["clavicle_r"])]
    back = min(p[2] for p in V) - 0.03 * s
    top, bottom = neck[1], (j["calf_l"][1] + j["calf_r"][1]) / 2
    rows, cols = 16, 12
    first = len(V)
    for r in range(rows + 1):
        t = r / rows
        half = (0.22 + 0.15 * t) * s
        for c in range(cols + 1):
            u = c / cols * 2 - 1
            V.append((neck[0] + u * half, top + (bottom - top) * t, back - 0.05 * s * t))
    for r in range(rows):
        for c in range(cols):
            a = first + r * (cols + 1) + c
            b, d = a + 1, a + cols + 1
            F += [(a, d, b), (b, d, d + 1), (a, b, d), (b, d + 1, d)]


def dressed(garment, positions, triangles, joints, s):
    part = parts(positions, joints)
    upper = {"trunk", "upper arm l", "upper arm r"}
    under = joints["spine_01"][1]
    jacket = (lambda v: part[v] in upper)
    if garment in ("jacket", "jacket_only", "coat"):
        V, F = shell(positions, triangles, jacket, 0.02 * s, garment == "jacket_only")
    elif garment == "sleeves_only":
        V, F = shell(positions, triangles,
                     lambda v: part[v] in upper or part[v].startswith("forearm"), 0.015 * s, True)
    elif garment == "pants_only":
        V, F = shell(positions, triangles,
                     lambda v: part[v].startswith(("thigh", "shin"))
                     or (part[v] == "trunk" and positions[v][1] < under), 0.015 * s, True)
    else:
        V, F = list(positions), list(triangles)
    knees = (joints["calf_l"][1] + joints["calf_r"][1]) / 2
    ankles = (joints["foot_l"][1] + joints["foot_r"][1]) / 2
    if garment in ("skirt", "coat"):
        bell(V, F, joints, knees, s)
    elif garment == "robe":
        bell(V, F, joints, (knees + ankles) / 2, s)
    elif garment == "cape":
        cape(V, F, joints, s)
    elif garment not in ("jacket", "jacket_only", "sleeves_only", "pants_only"):
        raise SystemExit(f"unknown garment {garment}")
    return V, F


def main():
    args, folders = body_check_args(__doc__, "/tmp/garments_check", "--garments", GARMENTS)
    if folders is None:
        return 1
    print("core mean, % of height; joints over 1.5 % in brackets; warning codes")
    for folder in folders:
        model = os.path.basename(folder)
        reference, joints, positions, triangles, height = body(folder)
        print(model)
        for garment in ["none"] + args.garments.split(","):
            if garment == "none":
                V, F = positions, triangles
            else:
                V, F = dressed(garment, positions, triangles, joints, height / 1.75)
            mesh = os.path.join(args.work, f"{model}_{garment}.obj")
            _, text = rig_and_score(args.skelfit, mesh, V, F, reference, height)
            print(f"  {garment:13s} {text}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
