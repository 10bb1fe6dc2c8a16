"""neuv for Blender: neural UV unwrapping, packing and saved models on the
selected meshes, through neuv's Python package (python/neuv).

The package is found from this add-on's preference "neuv Python path" or
the environment variable NEUV_PYTHONPATH (package.py). The operators write
one UV map and never change the geometry (operators.py); loop_uvs.py turns
neuv's per-triangle atlas into Blender's per-loop UVs."""

bl_info = {
    "name": "neuv: Neural UV Unwrap",
    "author": "neuv",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D View > Edit Mode > UV; Object > right-click menu",
    "description": "Unwrap with neuv's neural charts and maps, pack UV maps, apply saved neuv models",
    "category": "UV",
}

if "operators" in locals():  # F8 / re-enabling: take the edited modules
    import importlib
    loop_uvs = importlib.reload(loop_uvs)  # noqa: F821
    package = importlib.reload(package)  # noqa: F821
    operators = importlib.reload(operators)  # noqa: F821
else:
    from . import loop_uvs, operators, package

import bpy
from bpy.props import StringProperty


class NEUV_AddonPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    python_path: StringProperty(
        name="neuv Python path", subtype='DIR_PATH',
        description="The folder holding the neuv package: the repository's python/ folder (with "
                    "build/libneuv.so built) or .venv/lib/python3.11/site-packages after `make python`. "
                    "Empty: $NEUV_PYTHONPATH")

    def draw(self, context):
        layout = self.layout
        layout.prop(self, "python_path")
        try:
            neuv = package.load(self.python_path)
        except package.Missing as e:
            layout.label(text=str(e).split("; looked")[0], icon='ERROR')
        else:
            layout.label(text=f"neuv {neuv.__version__}: {neuv.library_path}", icon='CHECKMARK')


def menu_uv(self, context):
    layout = self.layout
    layout.separator()
    layout.operator(operators.NEUV_OT_unwrap.bl_idname)
    layout.operator(operators.NEUV_OT_pack.bl_idname)
    layout.operator(operators.NEUV_OT_apply_model.bl_idname, text="Apply neuv Model...")


class NEUV_MT_object(bpy.types.Menu):
    bl_idname = "NEUV_MT_object"
    bl_label = "UV (neuv)"

    def draw(self, context):
        menu_uv(self, context)


def menu_object(self, context):
    if any(o.type == 'MESH' for o in context.selected_objects):
        self.layout.menu(NEUV_MT_object.bl_idname)


classes = (NEUV_AddonPreferences, NEUV_MT_object) + operators.classes


def register():
    for c in classes:
        bpy.utils.register_class(c)
    bpy.types.VIEW3D_MT_uv_map.append(menu_uv)
    bpy.types.VIEW3D_MT_object_context_menu.append(menu_object)


def unregister():
    bpy.types.VIEW3D_MT_object_context_menu.remove(menu_object)
    bpy.types.VIEW3D_MT_uv_map.remove(menu_uv)
    for c in reversed(classes):
        bpy.utils.unregister_class(c)
