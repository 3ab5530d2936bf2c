# Imports skinned glTF files into Blender and prints what came in: the armature and its bones,
# the mesh with its vertex groups and armature modifier, how far the rest pose moves the mesh
# (should be ~0: inverse bind matrices agree with the joint nodes) and how many vertices a
# rotated bone moves.
#
# Usage: blender -b --python tools/blender_check.py -- FILE.glb [FILE...]
import sys

import numpy

if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Blender 3.4's glTF importer still uses np.bool (removed in numpy 1.24)

import bpy

files = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
for path in files:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=path)
    objects = list(bpy.data.objects)
    print("FILE", path, [(o.name, o.type, o.parent.name if o.parent else None) for o in objects])
    armature = next(o for o in objects if o.type == "ARMATURE")
    # The skinned mesh (with `--bones` the bone meshes are parented to joints, unskinned).
    mesh = max((o for o in objects if o.type == "MESH"), key=lambda o: len(o.vertex_groups))
    print("  bones", len(armature.data.bones))
    used = {g.group for v in mesh.data.vertices for g in v.groups if g.weight > 0}
    print("  vertices", len(mesh.data.vertices), "vertex groups", len(mesh.vertex_groups),
          "with weights", len(used), "modifiers", [m.type for m in mesh.modifiers])
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = mesh.evaluated_get(depsgraph).to_mesh()
    rest = max((a.co - b.co).length for a, b in zip(mesh.data.vertices, evaluated.vertices))
    print("  rest-pose max displacement", rest)
    bone = armature.pose.bones[min(1, len(armature.pose.bones) - 1)]
    bone.rotation_mode = "XYZ"
    bone.rotation_euler = (1.0, 0.0, 0.0)
    depsgraph.update()
    evaluated = mesh.evaluated_get(depsgraph).to_mesh()
    moved = sum(1 for a, b in zip(mesh.data.vertices, evaluated.vertices) if (a.co - b.co).length > 1e-4)
    print("  rotating bone", bone.name, "moves", moved, "of", len(evaluated.vertices), "vertices")
