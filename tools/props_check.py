#!/usr/bin/env python3
"""Props check: a body holding, wearing or growing what game characters do.

Real characters hold swords, staffs and guns, carry shields, wear hats and grow tails. For
every MakeHuman body under REFDATA/humanoid (a folder whose reference rig is
rig_game_engine.json) this tool writes copies of mesh.obj with one addition each, as a
separate closed piece:

  sword_down  a blade (1.0 x 0.05 x 0.012 m) hanging from the right hand beside the leg
  sword_fwd   the blade held forward, level
  sword_up    the blade raised straight up from the right hand
  staff       a staff (1.6 m, 3 cm across) held upright in the right hand
  gun         a gun-sized box (0.45 x 0.12 x 0.06 m) held forward in the right hand
  shield      a disc (0.56 m across, 3 cm thick) strapped to the outside of the left forearm
  hat         a wide-brimmed hat (brim 0.6 m across) on the head
  tail        a tail (5.5 to 2 cm thick) leaving the sacrum and curving down behind the legs
  hair        hair of 150 cards (open quads 6 cm wide) over the scalp, those at the back hanging
              10 to 30 cm down towards the shoulders

(sizes for a 1.75 m body, scaled with the height), rigs the body and every copy with `skelfit
rig --keep-frame --skeleton-json` and the default options, and prints the core error (pelvis,
neck, head, shoulders, elbows, wrists, hips, knees, ankles) against the reference's
`canonical` map, % of the height, with the joints more than 1.5 % off and the warnings'
codes. The reference is the body's: an addition should leave its joints where they are.

Standard-library Python only. Usage (from the repository, after `cargo build --release`):

    python3 tools/props_check.py [--refdata ../shared/refdata] [--skelfit target/release/skelfit]
                                 [--work /tmp/props_check] [--props sword_down,tail,...]
                                 [MODEL ...]
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pieces_check import body, body_check_args, rig_and_score  # noqa: E402

PROPS = "sword_down,sword_fwd,sword_up,staff,gun,shield,hat,tail,hair"


def norm(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def frame(d, hint):
    d = norm(d)
    if abs(sum(a * b for a, b in zip(d, hint))) > 0.99:
        hint = [0.0, 1.0, 0.0] if abs(d[1]) < 0.9 else [1.0, 0.0, 0.0]
    u = norm(cross(d, hint))
    return d, u, cross(d, u)


def box(V, F, start, direction, length, width, thick, hint=(1.0, 0.0, 0.0)):
    """A closed box from `start` along `direction`."""
    d, u, v = frame(direction, list(hint))
    base = len(V)
    for a in (0.0, length):
        for su in (-1, 1):
            for sv in (-1, 1):
                V.append(tuple(start[i] + d[i] * a + u[i] * su * width / 2 + v[i] * sv * thick / 2
                               for i in range(3)))
    for q in ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)):
        a, b, c, e = (base + i for i in q)
        F += [(a, b, c), (a, c, e)]


def tube(V, F, points, r0, r1, segments=12):
    """A closed tube through `points`, radius `r0` tapering to `r1`, capped by fans."""
    base, n = len(V), len(points)
    for i, p in enumerate(points):
        d, u, v = frame([b - a for a, b in zip(points[max(i - 1, 0)], points[min(i + 1, n - 1)])],
                        [1.0, 0.0, 0.0])
        r = r0 + (r1 - r0) * i / (n - 1)
        for k in range(segments):
            a = 2 * math.pi * k / segments
            V.append(tuple(p[j] + r * (math.cos(a) * u[j] + math.sin(a) * v[j]) for j in range(3)))
    for i in range(n - 1):
        for k in range(segments):
            a = base + i * segments + k
            b = base + i * segments + (k + 1) % segments
            F += [(a, b, b + segments), (a, b + segments, a + segments)]
    for end, first in ((0, True), (n - 1, False)):
        V.append(tuple(points[end]))
        c = len(V) - 1
        for k in range(segments):
            a = base + end * segments + k
            b = base + end * segments + (k + 1) % segments
            F.append((c, b, a) if first else (c, a, b))


def disc(V, F, centre, normal, radius, thick):
    """A closed flat cylinder (a shield, a hat's brim)."""
    n = norm(normal)
    tube(V, F, [[centre[i] - n[i] * thick / 2 for i in range(3)],
                [centre[i] + n[i] * thick / 2 for i in range(3)]], radius, radius, 24)


def cards(V, F, head, top, s, count=150):
    """Hair cards: open quads over the scalp on a golden-angle spiral out to 1.2 rad from the
    crown, facing out; those at the back hang 10 to 30 cm."""
    radius, width = 0.11 * s, 0.03 * s
    for k in range(count):
        theta = k * 2.399963
        phi = math.acos(1 - (k + 0.5) / count * (1 - math.cos(1.2)))
        sn, cs = math.sin(theta), math.cos(theta)
        root = [head[0] + radius * math.sin(phi) * cs, top - 0.02 * s - radius * (1 - math.cos(phi)),
                head[2] - 0.01 * s + radius * math.sin(phi) * sn]
        length = (0.1 + 0.2 * ((k * 7) % 10) / 10) * s if sn < 0 else 0.05 * s
        across = [-sn * width, 0.0, cs * width]
        down = [0.02 * s * cs, -length, 0.02 * s * sn]
        first = len(V)
        V += [tuple(root[i] + across[i] for i in range(3)),
              tuple(root[i] - across[i] for i in range(3)),
              tuple(root[i] + across[i] + down[i] for i in range(3)),
              tuple(root[i] - across[i] + down[i] for i in range(3))]
        F += [(first, first + 2, first + 1), (first + 1, first + 2, first + 3)]


def add(prop, V, F, joints, scale):
    j = joints
    s = scale
    hand = [(a + b) / 2 for a, b in zip(j["hand_r"], j["middle_03_r"])]
    top = max(p[1] for p in V)
    if prop == "sword_down":
        box(V, F, [hand[0], hand[1] + 0.1 * s, hand[2]], [0, -1, 0], 1.0 * s, 0.05 * s,
            0.012 * s, (0, 0, 1))
    elif prop == "sword_fwd":
        box(V, F, [hand[0], hand[1], hand[2] - 0.1 * s], [0, 0, 1], 1.0 * s, 0.05 * s, 0.012 * s)
    elif prop == "sword_up":
        box(V, F, [hand[0], hand[1] - 0.1 * s, hand[2]], [0, 1, 0.15], 1.0 * s, 0.05 * s,
            0.012 * s, (0, 0, 1))
    elif prop == "staff":
        tube(V, F, [[hand[0], 0.02 * s, hand[2]], [hand[0], 1.62 * s, hand[2]]],
             0.015 * s, 0.015 * s)
    elif prop == "gun":
        box(V, F, [hand[0], hand[1], hand[2] - 0.05 * s], [0, 0, 1], 0.45 * s, 0.12 * s,
            0.06 * s)
    elif prop == "shield":
        fore = [(a + b) / 2 for a, b in zip(j["lowerarm_l"], j["hand_l"])]
        d = norm([b - a for a, b in zip(j["lowerarm_l"], j["hand_l"])])
        out = norm(cross(d, [0, 0, 1]))
        if out[0] < 0:
            out = [-x for x in out]
        disc(V, F, [fore[i] + out[i] * 0.06 * s for i in range(3)], out, 0.28 * s, 0.03 * s)
    elif prop == "hat":
        x, z = j["head"][0], j["head"][2] + 0.01 * s
        disc(V, F, [x, top - 0.04 * s, z], [0, 1, 0], 0.30 * s, 0.02 * s)
        disc(V, F, [x, top + 0.02 * s, z], [0, 1, 0], 0.11 * s, 0.14 * s)
    elif prop == "tail":
        pelvis = j["pelvis"]
        points = []
        for i in range(13):
            t = i / 12
            points.append([0.0, pelvis[1] + 0.02 * s - 0.45 * s * t ** 1.3,
                           pelvis[2] - 0.06 * s - 0.7 * s * t])
        tube(V, F, points, 0.055 * s, 0.02 * s)
    elif prop == "hair":
        cards(V, F, j["head"], top, s)
    else:
        raise SystemExit(f"unknown prop {prop}")


def main():
    args, folders = body_check_args(__doc__, "/tmp/props_check", "--props", PROPS,
                                    models=["mh_neutral_default"])
    if folders is None:
        return 1
    print("core mean, % of height; joints over 1.5 % in brackets; warning codes")
    for folder in folders:
        model = os.path.basename(folder)
        reference, joints, positions, triangles, height = body(folder)
        print(model)
        for prop in ["none"] + args.props.split(","):
            V, F = list(positions), list(triangles)
            if prop != "none":
                add(prop, V, F, joints, height / 1.75)
            mesh = os.path.join(args.work, f"{model}_{prop}.obj")
            skeleton, text = rig_and_score(args.skelfit, mesh, V, F, reference, height)
            placed = skeleton["joints"] if skeleton else []
            tail = sum(1 for j in placed if j["name"].startswith("tail"))
            print(f"  {prop:11s} {text}" + (f"  tail joints {tail}" if tail else ""), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
