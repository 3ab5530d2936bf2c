"""The operators: skelfit.rig and skelfit.check."""

import os
import tempfile

import bpy

from . import compat, exchange, runner, weights


def _report_run(operator, run):
    for warning in run.warnings:
        operator.report({"WARNING"}, "skelfit: " + warning)


def _skinned_by(context, armature):
    """Mesh objects of the scene deformed by ``armature`` through an Armature modifier."""
    return [
        o
        for o in context.scene.objects
        if o.type == "MESH" and any(m.type == "ARMATURE" and m.object == armature for m in o.modifiers)
    ]


class SKELFIT_OT_rig(bpy.types.Operator):
    """Fit an anatomical skeleton into the active mesh with skelfit and skin the mesh to it"""

    bl_idname = "skelfit.rig"
    bl_label = "Rig with skelfit"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == "MESH" and context.mode == "OBJECT"

    def execute(self, context):
        obj = context.active_object
        binary, where = runner.find_binary(context)
        if binary is None:
            self.report({"ERROR"}, where)
            return {"CANCELLED"}
        if not obj.data.vertices:
            self.report({"ERROR"}, f"{obj.name} has no vertices")
            return {"CANCELLED"}
        settings = context.scene.skelfit
        try:
            arguments = settings.rig_arguments()
        except ValueError as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}

        # An earlier rig's Armature modifiers would pose the exported mesh: off while exporting,
        # removed once the new rig is in place, restored when it fails.
        old = [m for m in obj.modifiers if m.type == "ARMATURE"]
        shown = [m.show_viewport for m in old]
        for modifier in old:
            modifier.show_viewport = False
        try:
            with tempfile.TemporaryDirectory(prefix="skelfit_") as folder:
                source = os.path.join(folder, "mesh.glb")
                output = os.path.join(folder, "rig.glb")
                exchange.export_mesh_for_rig(context, obj, source)
                run = runner.run(context, binary, ["rig", source, "-o", output, *arguments])
                _report_run(self, run)
                if not run.ok:
                    raise RuntimeError(run.failure())
                armature, bones, farthest = self._adopt(context, obj, output)
        except RuntimeError as error:
            for modifier, show in zip(old, shown):
                modifier.show_viewport = show
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        earlier = {m.object.name for m in old if m.object is not None}
        for modifier in old:
            obj.modifiers.remove(modifier)
        if earlier:
            self.report({"INFO"}, f"skelfit: replaced the Armature modifier of {', '.join(sorted(earlier))} (left in the scene)")
        size = max(obj.dimensions) or 1.0
        if farthest > 0.01 * size:
            self.report(
                {"WARNING"},
                f"skelfit: vertices of {obj.name} lie up to {farthest:.4g} from the rigged mesh "
                "(modifiers that move vertices?); their weights are those of the nearest rigged vertex",
            )
        self.report({"INFO"}, f"skelfit: rigged {obj.name} with {armature.name} ({bones} bones)")
        return {"FINISHED"}

    def _adopt(self, context, obj, path):
        """Imports skelfit's .glb and moves its armature and weights onto ``obj``."""
        imported = exchange.Imported(context, path)
        armatures = [o for o in imported.objects if o.type == "ARMATURE"]
        if len(armatures) != 1:
            imported.remove_objects(list(imported.objects))
            imported.purge_unused()
            raise RuntimeError(f"expected one armature in skelfit's output, found {len(armatures)}")
        armature = armatures[0]
        skinned = [
            o for o in imported.objects if o.type == "MESH" and any(m.type == "ARMATURE" for m in o.modifiers)
        ]
        # Bone meshes (--bones) hang from bones and stay; anything else imported is temporary.
        keep = {armature} | {o for o in imported.objects if o.parent == armature and o.parent_type == "BONE"}
        try:
            farthest = weights.transfer(skinned, obj)
        finally:
            imported.remove_objects([o for o in imported.objects if o not in keep])
            imported.purge_unused()

        self._place_armature(context, obj, armature, [o for o in keep if o != armature])
        world = obj.matrix_world.copy()
        obj.parent = armature
        obj.parent_type = "OBJECT"
        obj.matrix_parent_inverse.identity()
        obj.matrix_world = world
        modifier = obj.modifiers.new(name="skelfit", type="ARMATURE")
        modifier.object = armature
        modifier.use_vertex_groups = True
        compat.move_modifier_first(obj, modifier)
        context.view_layer.update()
        for other in context.view_layer.objects:
            if other is not None:
                other.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        return armature, len(armature.data.bones), farthest

    @staticmethod
    def _place_armature(context, obj, armature, bone_meshes):
        """The armature takes the object's frame and place in the hierarchy and collections;
        bones and bone meshes stay where skelfit put them in the world."""
        kept = {o: o.matrix_world.copy() for o in bone_meshes}
        current = armature.matrix_world.copy()
        armature.parent = None
        frame = obj.matrix_world.copy()
        armature.data.transform(frame.inverted() @ current)
        # Re-rigging: the object hangs from its earlier rig; the new rig takes that one's place.
        anchor = obj.parent
        if anchor is not None and anchor.type == "ARMATURE":
            anchor = anchor.parent
        if anchor is not None:
            armature.parent = anchor
            armature.parent_type = "OBJECT"
            armature.matrix_parent_inverse.identity()
        armature.matrix_world = frame
        armature.name = f"{obj.name}_rig"
        armature.data.name = armature.name
        context.view_layer.update()
        for child, world in kept.items():
            child.matrix_world = world
        for item in (armature, *bone_meshes):
            for collection in list(item.users_collection):
                collection.objects.unlink(item)
            for collection in obj.users_collection:
                collection.objects.link(item)


class SKELFIT_OT_check(bpy.types.Operator):
    """Pose the active rig through skelfit's standard sweep and count the edges its skin tears"""

    bl_idname = "skelfit.check"
    bl_label = "Check deformation with skelfit"

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type in {"ARMATURE", "MESH"} and context.mode == "OBJECT"

    def execute(self, context):
        armature, meshes = self._rig(context)
        if armature is None or not meshes:
            self.report({"ERROR"}, "skelfit check: select an armature or a mesh with an Armature modifier")
            return {"CANCELLED"}
        binary, where = runner.find_binary(context)
        if binary is None:
            self.report({"ERROR"}, where)
            return {"CANCELLED"}
        try:
            arguments = context.scene.skelfit.check_arguments()
            with tempfile.TemporaryDirectory(prefix="skelfit_") as folder:
                path = os.path.join(folder, "rig.glb")
                exchange.export_rig_for_check(context, armature, meshes, path)
                run = runner.run(context, binary, ["check", path, *arguments])
        except (RuntimeError, ValueError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        _report_run(self, run)
        if not run.ok:
            self.report({"ERROR"}, run.failure())
            return {"CANCELLED"}
        context.scene.skelfit.last_check = "\n".join(run.stdout)
        for line in run.stdout:
            self.report({"INFO"}, line)
        if not bpy.app.background:
            lines = run.stdout

            def draw(menu, _context):
                column = menu.layout.column(align=True)
                for line in lines:
                    column.label(text=line)

            context.window_manager.popup_menu(draw, title=f"skelfit check: {armature.name}", icon="INFO")
        return {"FINISHED"}

    @staticmethod
    def _rig(context):
        obj = context.active_object
        if obj.type == "ARMATURE":
            return obj, _skinned_by(context, obj)
        armature = next((m.object for m in obj.modifiers if m.type == "ARMATURE" and m.object), None)
        if armature is None:
            return None, []
        return armature, _skinned_by(context, armature)
