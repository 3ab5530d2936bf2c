"""Differences between the Blender versions the add-on supports (3.4 to 4.x)."""

import warnings

import bpy


def patch_numpy():
    """Blender 3.4's glTF importer still uses ``np.bool`` (removed in numpy 1.24)."""
    import numpy

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if not hasattr(numpy, "bool"):
            numpy.bool = bool


def operator_kwargs(operator, **kwargs):
    """Keeps the keyword arguments ``operator`` knows (glTF options were renamed across versions)."""
    known = operator.get_rna_type().properties.keys()
    return {key: value for key, value in kwargs.items() if key in known}


def move_modifier_first(obj, modifier):
    """Puts ``modifier`` at the top of ``obj``'s stack."""
    index = list(obj.modifiers).index(modifier)
    if index == 0:
        return
    if hasattr(obj.modifiers, "move"):  # Blender 3.5+
        obj.modifiers.move(index, 0)
        return
    with bpy.context.temp_override(object=obj, active_object=obj):
        bpy.ops.object.modifier_move_to_index(modifier=modifier.name, index=0)
