#!/usr/bin/env python3
"""Writes an engine's rest frames (its bone-axis convention) into a naming preset.

Usage: python3 tools/preset_rest_frames.py RIG.json PRESET.json

RIG.json is a refdata rig with Blender-style bones (`position` = head, `tail`, `roll` in
radians in Blender's Z-up convention; the rig itself +Y up, facing +Z, left +X), e.g.
../shared/refdata/humanoid/mh_neutral_default/rig_mixamo.json. For every bone the script
computes Blender's rest matrix (the shortest rotation taking +Y onto the bone, then the roll
about it: Blender's vec_roll_to_mat3) and turns it into the Y-up frame that Blender's glTF
exporter writes (local +Y along the bone). It stores, in the figure's body axes (left, up,
forward), the frame's x and y axes and the direction to the child the bone points at (the
child whose head lies nearest the bone's line, if any) under the preset's "rest_frames"
key; skelfit carries each frame onto its fitted bone by the shortest rotation
(src/template/rest_frames.rs).
"""
import json
import math
import sys


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(a):
    n = math.sqrt(dot(a, a))
    return [v / n for v in a]


def rotate(v, axis, angle):
    """Rodrigues: v turned by angle about the unit axis."""
    c, s = math.cos(angle), math.sin(angle)
    k = cross(axis, v)
    d = dot(axis, v)
    return [v[i] * c + k[i] * s + axis[i] * d * (1 - c) for i in range(3)]


def arc(a, b, v):
    """v turned by the shortest rotation taking unit a onto unit b."""
    axis = cross(a, b)
    s = math.sqrt(dot(axis, axis))
    c = dot(a, b)
    if s < 1e-12:
        return v if c > 0 else [-v[0], v[1], -v[2]]
    return rotate(v, [x / s for x in axis], math.atan2(s, c))


def to_blender(v):  # Y-up (x, y, z) -> Blender Z-up
    return [v[0], -v[2], v[1]]


def from_blender(v):  # Blender Z-up -> Y-up
    return [v[0], v[2], -v[1]]


def frame(joint):
    """The bone's x and y axes in the rig's Y-up frame."""
    y = unit(to_blender(sub(joint["tail"], joint["position"])))
    axes = []
    for e in ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]):
        a = arc([0.0, 1.0, 0.0], y, e)
        axes.append(from_blender(rotate(a, y, joint["roll"])))
    return axes


def rounded(v):
    return [round(x, 5) for x in v]


def main(rig_path, preset_path):
    rig = json.load(open(rig_path))
    assert (rig["up"], rig["forward"], rig["left"]) == ("+Y", "+Z", "+X"), "rig frame"
    out = {}
    for j in rig["joints"]:
        if "tail" not in j:
            continue
        x, y = frame(j)
        entry = {"x": rounded(x), "y": rounded(y)}
        bone = sub(j["tail"], j["position"])
        children = [c for c in rig["joints"] if c["parent"] == j["name"]]
        best = None
        for c in children:
            d = sub(c["position"], j["position"])
            if dot(d, d) < 1e-12:
                continue
            cosine = dot(unit(d), unit(bone))
            if best is None or cosine > best[0]:
                best = (cosine, c["name"], unit(d))
        if best is not None and best[0] > math.cos(math.radians(45)):
            entry["child"] = best[1]
            entry["to_child"] = rounded(best[2])
        out[j["name"]] = entry
    preset = json.load(open(preset_path))
    preset["rest_frames"] = {
        "source": "tools/preset_rest_frames.py on " + rig_path.split("refdata/")[-1]
        + " (" + rig.get("source", "") + "): Blender bones (head, tail, roll) as Blender's glTF"
        " exporter writes them, local +Y along the bone; axes in the figure's body axes"
        " (left, up, forward)",
        "joints": out,
    }
    with open(preset_path, "w") as f:
        json.dump(preset, f, indent=2, ensure_ascii=False)
        f.write("\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
