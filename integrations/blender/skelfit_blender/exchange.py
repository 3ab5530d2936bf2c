"""glTF round trips between the Blender scene and skelfit."""

import bpy

from . import compat


class Selection:
    """Selects exactly ``objects`` (making the first active) and restores the previous selection."""

    def __init__(self, context, objects):
        self.context = context
        self.objects = objects

    def __enter__(self):
        view_layer = self.context.view_layer
        self.previous = [o for o in view_layer.objects if o is not None and o.select_get()]
        self.active = view_layer.objects.active
        for obj in view_layer.objects:
            if obj is not None:
                obj.select_set(False)
        for obj in self.objects:
            obj.select_set(True)
        view_layer.objects.active = self.objects[0]
        return self

    def __exit__(self, *exc):
        view_layer = self.context.view_layer
        for obj in view_layer.objects:
            if obj is not None:
                obj.select_set(obj in self.previous)
        view_layer.objects.active = self.active if self.active in view_layer.objects[:] else None
        return False


def _export_gltf(path, **options):
    kwargs = compat.operator_kwargs(
        bpy.ops.export_scene.gltf,
        filepath=path,
        export_format="GLB",
        use_selection=True,
        export_yup=True,
        export_texcoord=True,
        export_normals=True,
        export_materials="EXPORT",
        export_animations=False,
        export_cameras=False,
        export_lights=False,
        check_existing=False,
        **options,
    )
    result = bpy.ops.export_scene.gltf(**kwargs)
    if "FINISHED" not in result:
        raise RuntimeError(f"the glTF export to {path} failed")


def export_mesh_for_rig(context, obj, path):
    """Writes ``obj`` as it looks (modifiers applied, world transform baked into the vertices,
    all its material slots, UVs) to ``path`` as a .glb without armature. Returns the number of
    vertices written."""
    depsgraph = context.evaluated_depsgraph_get()
    mesh = bpy.data.meshes.new_from_object(
        obj.evaluated_get(depsgraph), preserve_all_data_layers=True, depsgraph=depsgraph
    )
    temporary = None
    try:
        mesh.transform(obj.matrix_world)
        if obj.matrix_world.determinant() < 0:
            mesh.flip_normals()
        # Materials linked to the object instead of its data would be lost with the data copy.
        for index, slot in enumerate(obj.material_slots):
            if index < len(mesh.materials):
                mesh.materials[index] = slot.material
            else:
                mesh.materials.append(slot.material)
        temporary = bpy.data.objects.new("skelfit_export", mesh)
        context.scene.collection.objects.link(temporary)
        with Selection(context, [temporary]):
            _export_gltf(path, export_apply=True, export_skins=False)
        return len(mesh.vertices)
    finally:
        if temporary is not None:
            bpy.data.objects.remove(temporary)
        bpy.data.meshes.remove(mesh)


def export_rig_for_check(context, armature, meshes, path):
    """Writes the armature and its skinned meshes (rest pose) to ``path`` as a .glb."""
    pose = armature.data.pose_position
    armature.data.pose_position = "REST"
    try:
        with Selection(context, [armature, *meshes]):
            _export_gltf(path, export_apply=False, export_skins=True, export_def_bones=False)
    finally:
        armature.data.pose_position = pose


class Imported:
    """What one glTF import added to the file, so that the temporary parts can be removed."""

    KINDS = ("objects", "meshes", "materials", "images", "textures", "armatures", "actions")

    def __init__(self, context, path):
        before = {kind: set(getattr(bpy.data, kind)) for kind in self.KINDS}
        result = bpy.ops.import_scene.gltf(
            **compat.operator_kwargs(bpy.ops.import_scene.gltf, filepath=path)
        )
        if "FINISHED" not in result:
            raise RuntimeError(f"the glTF import of {path} failed")
        self.added = {
            kind: [d for d in getattr(bpy.data, kind) if d not in before[kind]] for kind in self.KINDS
        }
        self.objects = self.added["objects"]

    def remove_objects(self, objects):
        for obj in objects:
            bpy.data.objects.remove(obj)
        self.objects = [o for o in self.objects if o not in objects]

    def purge_unused(self):
        """Removes the data blocks the import added that nothing uses any more."""
        for kind in ("meshes", "materials", "textures", "images", "actions"):
            collection = getattr(bpy.data, kind)
            for block in self.added[kind]:
                try:
                    unused = block.users == 0
                except ReferenceError:  # already removed with its object
                    continue
                if unused:
                    collection.remove(block)
