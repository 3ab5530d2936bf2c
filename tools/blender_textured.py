# Imports a rigged .glb into Blender headless and checks that it came in textured and skinned:
# one mesh with the expected vertex count, a UV layer, a material whose base colour is an image
# texture with pixels, an armature with bones, the mesh weighted to it by an Armature modifier.
# Prints "PASS <file>" or "FAIL <file>: <reason>" per file and exits 1 on any failure.
#
# Usage: blender -b --factory-startup --python tools/blender_textured.py -- FILE.glb VERTICES [FILE.glb VERTICES ...]
import sys

import numpy

if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Blender 3.4's glTF importer still uses np.bool (removed in numpy 1.24)

import bpy


def check(path, vertices):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=path)
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    armatures = [o for o in bpy.data.objects if o.type == "ARMATURE"]
    if not armatures or len(armatures[0].data.bones) < 2:
        return "no armature with bones"
    if not meshes:
        return "no mesh"
    count = sum(len(m.data.vertices) for m in meshes)
    if count != vertices:
        return f"{count} vertices, expected {vertices}"
    for mesh in meshes:
        if not mesh.data.uv_layers:
            return f"{mesh.name}: no UV layer"
        if not any(m.type == "ARMATURE" for m in mesh.modifiers):
            return f"{mesh.name}: no Armature modifier"
        if not mesh.vertex_groups:
            return f"{mesh.name}: no vertex groups"
        images = [
            node.image
            for slot in mesh.material_slots
            if slot.material and slot.material.use_nodes
            for node in slot.material.node_tree.nodes
            if node.type == "TEX_IMAGE" and node.image is not None
        ]
        if not images:
            return f"{mesh.name}: no image texture in its materials"
        if not any(image.size[0] > 0 and image.size[1] > 0 for image in images):
            return f"{mesh.name}: its texture images have no pixels"
    return None


args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
failed = False
for path, vertices in zip(args[0::2], args[1::2]):
    problem = check(path, int(vertices))
    if problem:
        failed = True
        print(f"FAIL {path}: {problem}")
    else:
        print(f"PASS {path}")
sys.exit(1 if failed or not args else 0)
