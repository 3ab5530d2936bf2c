"""The options (one set per scene), the sidebar panel and the Object menu entry."""

import os

import bpy

# Blender is Z-up with figures facing -Y; the exported glTF is Y-up, so Blender (x, y, z) is
# glTF (x, z, -y). The panel speaks Blender's axes, skelfit is given glTF's.
_TO_GLTF = {"+X": "+X", "-X": "-X", "+Y": "-Z", "-Y": "+Z", "+Z": "+Y", "-Z": "-Y"}
_AXES = [(axis, axis, f"The figure's {{}} is Blender's {axis} axis") for axis in _TO_GLTF]


def _axis_items(what):
    auto = ("AUTO", "Auto", f"skelfit finds the figure's {what}")
    return [auto] + [(key, name, text.format(what)) for key, name, text in _AXES]


class SkelfitSettings(bpy.types.PropertyGroup):
    template: bpy.props.EnumProperty(
        name="Template",
        items=[
            ("auto", "Auto", "From the labelled figure: humanoid, quadruped or winged"),
            ("humanoid", "Humanoid", "Upright two-legged figure with arms"),
            ("quadruped", "Quadruped", "Four-legged animal"),
            ("winged", "Winged", "Bird or other winged figure"),
            ("FILE", "File", "A template .toml file"),
        ],
        default="auto",
    )
    template_file: bpy.props.StringProperty(name="Template file", subtype="FILE_PATH", default="")
    preset: bpy.props.EnumProperty(
        name="Names",
        description="Naming preset of the bones",
        items=[
            ("anatomical", "Anatomical", "skelfit's anatomical names (pelvis, spine_01, shoulder_L, ...)"),
            ("mixamo", "Mixamo", "Adobe Mixamo (mixamorig:Hips, ...)"),
            ("unity", "Unity", "Unity Humanoid (HumanBodyBones names)"),
            ("makehuman", "MakeHuman", "MakeHuman / MPFB2 game_engine (pelvis, upperarm_l, ...)"),
            ("unreal", "Unreal", "Unreal Engine 5 Mannequin (root, pelvis, spine_01, upperarm_l, ...)"),
        ],
        default="anatomical",
    )
    up: bpy.props.EnumProperty(name="Up", items=_axis_items("up direction"), default="AUTO")
    forward: bpy.props.EnumProperty(name="Forward", items=_axis_items("facing direction"), default="-Y")
    bones: bpy.props.BoolProperty(
        name="Bone meshes", description="Add skeleton bone meshes parented to the bones", default=False
    )
    strict: bpy.props.BoolProperty(
        name="Strict",
        description="Fail when the figure lacks a body part the template expects, or no template fits",
        default=False,
    )
    last_check: bpy.props.StringProperty(name="Last check", default="")

    def rig_arguments(self):
        """skelfit rig options for these settings (the output stays in the exported frame)."""
        if self.template == "FILE":
            path = bpy.path.abspath(self.template_file)
            if not os.path.isfile(path):
                raise ValueError(f"template file not found: {path or '(none set)'}")
            template = path
        else:
            template = self.template
        arguments = ["--template", template, "--preset", self.preset, "--keep-frame"]
        arguments += ["--up", "auto" if self.up == "AUTO" else _TO_GLTF[self.up]]
        arguments += ["--forward", "auto" if self.forward == "AUTO" else _TO_GLTF[self.forward]]
        if self.bones:
            arguments.append("--bones")
        if self.strict:
            arguments.append("--strict")
        return arguments

    def check_arguments(self):
        """skelfit check options: the figure's axes when the panel names them."""
        arguments = []
        if self.up != "AUTO":
            arguments += ["--up", _TO_GLTF[self.up]]
        if self.forward != "AUTO":
            arguments += ["--forward", _TO_GLTF[self.forward]]
        return arguments


class SKELFIT_PT_panel(bpy.types.Panel):
    bl_label = "skelfit"
    bl_idname = "SKELFIT_PT_panel"
    bl_space_type = "VIEW_3D"
    bl_region_type = "UI"
    bl_category = "skelfit"

    def draw(self, context):
        settings = context.scene.skelfit
        layout = self.layout
        layout.use_property_split = True
        layout.use_property_decorate = False
        layout.prop(settings, "template")
        if settings.template == "FILE":
            layout.prop(settings, "template_file")
        layout.prop(settings, "preset")
        layout.prop(settings, "up")
        layout.prop(settings, "forward")
        layout.prop(settings, "bones")
        layout.prop(settings, "strict")
        layout.operator("skelfit.rig", icon="ARMATURE_DATA")
        layout.operator("skelfit.check", icon="CHECKMARK")
        if settings.last_check:
            box = layout.box()
            for line in settings.last_check.splitlines():
                box.label(text=line)


def draw_object_menu(menu, _context):
    menu.layout.separator()
    menu.layout.operator("skelfit.rig", icon="ARMATURE_DATA")
