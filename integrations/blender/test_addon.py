"""Headless test of the skelfit add-on.

    blender -b --factory-startup --python integrations/blender/test_addon.py -- SKELFIT_BIN MESH...

Enables the add-on from this folder (or, when $BLENDER_USER_SCRIPTS points at a scratch folder,
installs the zip make_zip.py builds, as a user would), then for each mesh: imports it (OBJ,
glTF/GLB; a multi-part or skinned file is joined into one plain mesh object first), runs
bpy.ops.skelfit.rig() and checks the result: an armature of >= 20 bones parenting the object,
an Armature modifier pointing at it, every vertex in a vertex group with weight > 0, the
material count unchanged, nothing left of the import, the rest pose deforming nothing; then
bpy.ops.skelfit.check(). Exits non-zero on the first failure.
"""

import importlib.util
import os
import sys
import tempfile
import time
import traceback

import bpy

sys.dont_write_bytecode = True

HERE = os.path.dirname(os.path.abspath(__file__))


def enable_addon():
    user_scripts = os.environ.get("BLENDER_USER_SCRIPTS")
    if user_scripts:
        # This folder stays off sys.path, so that the add-on can only come from the zip.
        spec = importlib.util.spec_from_file_location("make_zip", os.path.join(HERE, "make_zip.py"))
        make_zip = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(make_zip)
        zip_path = make_zip.build(os.path.join(tempfile.mkdtemp(prefix="skelfit_zip_"), "skelfit_blender.zip"))
        bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
        how = f"installed from {zip_path}"
        home = os.path.realpath(user_scripts)
    else:
        sys.path.insert(0, HERE)
        how = f"enabled from {HERE}"
        home = os.path.realpath(HERE)
    bpy.ops.preferences.addon_enable(module="skelfit_blender")
    import skelfit_blender

    where = os.path.realpath(skelfit_blender.__file__)
    assert where.startswith(home + os.sep), f"the add-on was loaded from {where}, not from {home}"
    assert hasattr(bpy.ops.skelfit, "rig"), "the add-on did not register skelfit.rig"
    print(f"add-on {how} ({where})")


def import_mesh(path):
    """Imports ``path`` into an empty scene and returns one plain mesh object made of it."""
    bpy.ops.wm.read_homefile(use_empty=True)
    extension = os.path.splitext(path)[1].lower()
    if extension == ".obj":
        if hasattr(bpy.ops.wm, "obj_import"):
            bpy.ops.wm.obj_import(filepath=path)
        else:
            bpy.ops.import_scene.obj(filepath=path)
    elif extension in (".glb", ".gltf"):
        bpy.ops.import_scene.gltf(filepath=path)
    else:
        raise ValueError(f"unsupported test mesh {path}")
    meshes = [o for o in bpy.data.objects if o.type == "MESH"]
    assert meshes, f"{path}: no mesh objects imported"
    # A file's own skinning goes: the add-on rigs plain meshes.
    for obj in meshes:
        world = obj.matrix_world.copy()
        obj.parent = None
        obj.matrix_world = world
        for modifier in [m for m in obj.modifiers if m.type == "ARMATURE"]:
            obj.modifiers.remove(modifier)
        obj.vertex_groups.clear()
    for obj in [o for o in bpy.data.objects if o.type != "MESH"]:
        bpy.data.objects.remove(obj)
    view_layer = bpy.context.view_layer
    view_layer.update()
    for obj in bpy.context.scene.objects:
        obj.select_set(obj.type == "MESH")
    target = max(meshes, key=lambda o: len(o.data.vertices))
    view_layer.objects.active = target
    if len(meshes) > 1:
        bpy.ops.object.join()
    return view_layer.objects.active, len(meshes)


def rest_displacement(obj):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = obj.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    try:
        return max((a.co - b.co).length for a, b in zip(obj.data.vertices, mesh.vertices))
    finally:
        evaluated.to_mesh_clear()


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def test_mesh(path):
    started = time.time()
    obj, parts = import_mesh(path)
    name = obj.name
    materials = len(obj.material_slots)
    material_names = [s.material.name if s.material else None for s in obj.material_slots]
    vertices = len(obj.data.vertices)
    objects_before = set(bpy.data.objects)
    result = bpy.ops.skelfit.rig()
    check(result == {"FINISHED"}, f"skelfit.rig returned {result}")
    obj = bpy.data.objects[name]

    armature = obj.parent
    check(armature is not None and armature.type == "ARMATURE", f"{name} is not parented to an armature")
    bones = len(armature.data.bones)
    check(bones >= 20, f"{bones} bones (< 20)")
    modifiers = [m for m in obj.modifiers if m.type == "ARMATURE"]
    check(len(modifiers) == 1 and modifiers[0].object == armature, "no Armature modifier on the armature")
    check(len(obj.data.vertices) == vertices, "the object's vertices changed")
    check(len(obj.material_slots) == materials, f"{len(obj.material_slots)} materials, had {materials}")
    check(
        [s.material.name if s.material else None for s in obj.material_slots] == material_names,
        "the object's materials changed",
    )
    bone_names = {b.name for b in armature.data.bones}
    groups = {g.index: g.name for g in obj.vertex_groups}
    bare = [
        v.index
        for v in obj.data.vertices
        if not any(g.weight > 0 and groups.get(g.group) in bone_names for g in v.groups)
    ]
    check(not bare, f"{len(bare)} of {vertices} vertices in no bone's vertex group (first {bare[:5]})")
    new = set(bpy.data.objects) - objects_before
    check(new == {armature}, f"objects left besides the armature: {sorted(o.name for o in new - {armature})}")
    moved = rest_displacement(obj)
    check(moved < 1e-4 * max(obj.dimensions), f"the rest pose moves vertices by {moved}")

    result = bpy.ops.skelfit.check()
    check(result == {"FINISHED"}, f"skelfit.check returned {result}")
    summary = bpy.context.scene.skelfit.last_check.splitlines()
    check(any(line.startswith("all poses") for line in summary), f"no check summary: {summary}")
    print(
        f"PASS {path}: {parts} part(s) -> {vertices} vertices, {materials} materials, {bones} bones, "
        f"{len(obj.vertex_groups)} vertex groups; check: {summary[-1].split()}; {time.time() - started:.1f} s"
    )


def main():
    arguments = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(arguments) < 2:
        print("usage: blender -b --factory-startup --python test_addon.py -- SKELFIT_BIN MESH...")
        return 2
    os.environ["SKELFIT_BIN"] = os.path.abspath(arguments[0])
    print(f"Blender {bpy.app.version_string}")
    enable_addon()
    failed = 0
    for path in arguments[1:]:
        try:
            test_mesh(os.path.abspath(path))
        except Exception:
            failed += 1
            print(f"FAIL {path}")
            traceback.print_exc()
    return 1 if failed else 0


if __name__ == "__main__":
    try:
        code = main()
    except Exception:
        traceback.print_exc()
        code = 1
    sys.stdout.flush()
    os._exit(code)
