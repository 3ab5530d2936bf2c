# Blender's automatic (bone heat, Baran & Popovic 2007) weights on the artists' skeletons, for
# the side-by-side comparison in reports/deformation (examples/deformation.rs reads them).
#
# For every MODEL_DIR/source.glb: import it (default glTF importer settings, as a user would),
# keep as deforming bones exactly the joints the artist's weights use (skelfit's
# `skin_skeleton` gets the same: `deform` is true iff some vertex weighs on the joint), drop the
# artist's vertex groups, re-parent every mesh object to the armature "With Automatic Weights"
# (Object > Parent > With Automatic Weights, `parent_set(type="ARMATURE_AUTO")`), and write
# the weights as JSON (where bone heat leaves vertices unweighted, "failed to find solution
# for one or more bones", the usual fix first: Merge by Distance, then again): every mesh
# vertex's rest position in the glTF frame (Y up, the file's units, world space) and its
# weights by bone name, limited to the four largest and renormalised as Blender's glTF
# exporter does, and the bones' rest heads in the same frame. Vertices bone heat leaves without weight are
# written with none (under an armature modifier they stay where they are).
#
# Usage:
#   blender -b --python tools/blender_autoweights.py -- OUT_DIR MODEL_DIR [MODEL_DIR...]
# writes OUT_DIR/<kind>/<model>.json (kind = the model folder's parent, e.g. humanoid).
# Every humanoid and quadruped of the reference data:
#   blender -b --python tools/blender_autoweights.py -- reports/deformation/blender \
#       ../shared/refdata/humanoid/* ../shared/refdata/quadruped/*
# (folders without source.glb are skipped). Not part of `cargo test`: Blender is too heavy
# for CI. Tested with Blender 3.4.1 (Debian bookworm).
import json
import os
import sys
import time

import numpy

if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Blender 3.4's glTF importer still uses np.bool (removed in numpy 1.24)

import bpy

MAX_INFLUENCES = 4


def autoweights(path, merge):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=path)
    objects = list(bpy.data.objects)
    armatures = [o for o in objects if o.type == "ARMATURE"]
    if not armatures:
        raise RuntimeError("no armature")
    armature = max(armatures, key=lambda o: len(o.data.bones))
    meshes = [o for o in objects if o.type == "MESH"]
    # The joints the artist's weights use deform; the others (IK and pole targets, roots,
    # end markers) do not, as in skelfit's `skin_skeleton`.
    used = set()
    for mesh in meshes:
        names = {g.index: g.name for g in mesh.vertex_groups}
        for v in mesh.data.vertices:
            for g in v.groups:
                if g.weight > 0.0 and g.group in names:
                    used.add(names[g.group])
    for bone in armature.data.bones:
        bone.use_deform = bone.name in used
    for mesh in meshes:
        for modifier in list(mesh.modifiers):
            if modifier.type == "ARMATURE":
                mesh.modifiers.remove(modifier)
        mesh.vertex_groups.clear()
    bpy.ops.object.select_all(action="DESELECT")
    for mesh in meshes:
        mesh.select_set(True)
        bpy.context.view_layer.objects.active = mesh
        bpy.ops.object.parent_clear(type="CLEAR_KEEP_TRANSFORM")
        if merge:
            # Mesh > Clean Up > Merge by Distance: the importer splits vertices along UV and
            # normal seams, and bone heat often finds no solution on the cut-up surface.
            bpy.ops.object.mode_set(mode="EDIT")
            bpy.ops.mesh.select_all(action="SELECT")
            bpy.ops.mesh.remove_doubles(threshold=1e-6)
            bpy.ops.object.mode_set(mode="OBJECT")
        mesh.select_set(False)
    for mesh in meshes:
        mesh.select_set(True)
    armature.select_set(True)
    bpy.context.view_layer.objects.active = armature
    started = time.time()
    bpy.ops.object.parent_set(type="ARMATURE_AUTO", keep_transform=True)
    seconds = time.time() - started

    bones = [b.name for b in armature.data.bones if b.use_deform]
    bone_index = {name: k for k, name in enumerate(bones)}
    positions, weights = [], []
    unweighted = 0
    for mesh in meshes:
        names = {g.index: g.name for g in mesh.vertex_groups}
        world = mesh.matrix_world
        for v in mesh.data.vertices:
            p = world @ v.co
            # Blender is Z up; glTF Y up: (x, y, z)_blender = (x, -z, y)_gltf.
            positions.append([round(p.x, 6), round(p.z, 6), round(-p.y, 6)])
            w = [
                (bone_index[names[g.group]], g.weight)
                for g in v.groups
                if g.weight > 0.0 and names.get(g.group) in bone_index
            ]
            w.sort(key=lambda e: -e[1])
            w = w[:MAX_INFLUENCES]
            total = sum(x for _, x in w)
            if total > 0.0:
                weights.append([[j, round(x / total, 5)] for j, x in w])
            else:
                weights.append([])
                unweighted += 1
    # The bones' rest heads in the same frame as the positions: the example maps these onto
    # the joints of the skeleton skelfit loads to bring both meshes into one frame.
    heads = {}
    for bone in armature.data.bones:
        h = armature.matrix_world @ bone.head_local
        heads[bone.name] = [round(h.x, 6), round(h.z, 6), round(-h.y, 6)]
    return {
        "source": os.path.basename(path),
        "heads": heads,
        "blender": bpy.app.version_string,
        "method": "parent_set(type='ARMATURE_AUTO') (bone heat)",
        "seconds": round(seconds, 3),
        "bones": bones,
        "unweighted_vertices": unweighted,
        "positions": positions,
        "weights": weights,
    }


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) < 2:
        sys.exit("usage: blender -b --python tools/blender_autoweights.py -- OUT_DIR MODEL_DIR...")
    out, models = args[0], args[1:]
    for model in models:
        source = os.path.join(model, "source.glb")
        if not os.path.isfile(source):
            continue
        model = os.path.normpath(model)
        kind, name = os.path.basename(os.path.dirname(model)), os.path.basename(model)
        # As a user would: the plain command first; where bone heat leaves vertices
        # unweighted ("failed to find solution for one or more bones"), the usual fix (merge
        # the split seams) and again.
        result = autoweights(source, merge=False)
        if result["unweighted_vertices"] > 0:
            first = result["unweighted_vertices"]
            result = autoweights(source, merge=True)
            result["unweighted_before_merge"] = first
            result["merged_by_distance"] = True
        folder = os.path.join(out, kind)
        os.makedirs(folder, exist_ok=True)
        target = os.path.join(folder, name + ".json")
        with open(target, "w") as f:
            json.dump(result, f, separators=(",", ":"))
        print(
            "blender_autoweights: %s/%s: %d vertices, %d unweighted, %d bones, %.2f s"
            % (kind, name, len(result["positions"]), result["unweighted_vertices"],
               len(result["bones"]), result["seconds"]),
            flush=True,
        )


main()
