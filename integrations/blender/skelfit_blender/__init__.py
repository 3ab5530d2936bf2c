"""skelfit for Blender: rig the active mesh object with the skelfit command-line tool.

Object > Rig with skelfit exports the active mesh (modifiers applied, world transform baked in)
as a temporary .glb, runs ``skelfit rig`` on it with the options of the "skelfit" sidebar panel,
imports the skinned result and moves its armature and weights onto the original object (whose
mesh, materials and UVs stay as they are). ``skelfit.check`` runs ``skelfit check`` on the
active rig. The binary is found through the add-on preference, ``$SKELFIT_BIN`` or ``PATH``.
"""

bl_info = {
    "name": "skelfit",
    "author": "skelfit developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Object > Rig with skelfit; View3D > Sidebar > skelfit",
    "description": "Fit an anatomical skeleton into a mesh and skin it with the skelfit tool",
    "category": "Rigging",
}

if "bpy" in locals():
    import importlib

    for _module in (compat, runner, exchange, weights, operators, ui):  # noqa: F821
        importlib.reload(_module)

import bpy  # noqa: E402

from . import compat, exchange, operators, runner, ui, weights  # noqa: E402,F401

_classes = (
    runner.SkelfitPreferences,
    ui.SkelfitSettings,
    operators.SKELFIT_OT_rig,
    operators.SKELFIT_OT_check,
    ui.SKELFIT_PT_panel,
)


def register():
    compat.patch_numpy()
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.Scene.skelfit = bpy.props.PointerProperty(type=ui.SkelfitSettings)
    bpy.types.VIEW3D_MT_object.append(ui.draw_object_menu)


def unregister():
    bpy.types.VIEW3D_MT_object.remove(ui.draw_object_menu)
    del bpy.types.Scene.skelfit
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
