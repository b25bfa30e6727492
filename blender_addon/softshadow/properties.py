# What the user can set: per light (pass on/off, method, quality), per scene (output, layers).
# SPDX-License-Identifier: GPL-3.0-or-later
import bpy

METHOD_ITEMS = [
    ("auto", "Auto", "Pick a method for this light's shape and the scene (the report says which)"),
    ("shadow_map", "Shadow Map", "Hard shadow from the light centre (fast baseline)"),
    ("pcss", "PCSS", "Percentage-closer soft shadows"),
    ("dbuffer", "D-Buffer", "Umbra/penumbra volumes with a D-buffer (disk lights)"),
    ("sweep", "Sweep", "Geometric sweep line over light samples (planar receivers)"),
    ("penumbra_map", "Penumbra Map", "Shadow map with cones and sheets (sphere/disk lights)"),
    ("occlusion_textures", "Occlusion Textures", "Slices with pre-filtering (rectangle lights)"),
    ("reference", "Reference", "Ray traced with stratified light samples (slow, exact)"),
]


class SoftShadowLightSettings(bpy.types.PropertyGroup):
    enabled: bpy.props.BoolProperty(
        name="Soft Shadow Pass", default=True,
        description="Compute a soft-shadow visibility pass for this light")
    method: bpy.props.EnumProperty(name="Method", items=METHOD_ITEMS, default="auto")
    samples: bpy.props.IntProperty(
        name="Samples", default=0, min=0, soft_max=1024,
        description="Light samples for sampling methods (0: the method's default)")
    settings: bpy.props.StringProperty(
        name="Method Settings", default="",
        description="Advanced method quality settings as key=value;key=value")


class SoftShadowSceneSettings(bpy.types.PropertyGroup):
    enabled: bpy.props.BoolProperty(
        name="Soft Shadow Passes", default=True,
        description="Compute the passes before each render and write them as a multilayer EXR")
    output_dir: bpy.props.StringProperty(
        name="Output Folder", subtype="DIR_PATH", default="",
        description="Where the per-frame EXR goes (empty: next to the render output)")
    extra_layers: bpy.props.BoolProperty(
        name="Extra Layers", default=False,
        description="Also write umbra, penumbra, mask and the methods' debug layers")
    compositor_pass: bpy.props.StringProperty(
        name="Darken By", default="",
        description="The pass the compositor's darken group multiplies by (empty: the first)")
    strength: bpy.props.FloatProperty(name="Strength", default=1.0, min=0.0, max=1.0,
                                      description="How strongly the darken group applies the pass")
    preview: bpy.props.BoolProperty(
        name="Viewport Preview", default=False,
        description="Draw a live soft-shadow preview over the 3D viewport")
    preview_scale: bpy.props.IntProperty(
        name="Preview Resolution", default=25, min=5, max=100, subtype="PERCENTAGE",
        description="Resolution of the viewport preview relative to the viewport")
    last_report: bpy.props.StringProperty(name="Last Report", default="")

    # Pipeline scripts reach the add-on through the scene in every Blender and both install modes:
    # as an extension its package is `bl_ext.<repository>.softshadow`, a name the studio chooses,
    # and an extension may not add a top-level module of its own.
    def render_passes(self, lights=None, methods=None, extra_layers=False):
        """The passes of this scene's current frame: see api.render_passes."""
        from . import api
        return api.render_passes(self.id_data, lights=lights, methods=methods, extra_layers=extra_layers)

    def passes_problems(self):
        """What the last render_passes call left out, and why."""
        from . import api
        return list(api.render_passes.last_problems)


CLASSES = (SoftShadowLightSettings, SoftShadowSceneSettings)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Light.softshadow = bpy.props.PointerProperty(type=SoftShadowLightSettings)
    bpy.types.Scene.softshadow = bpy.props.PointerProperty(type=SoftShadowSceneSettings)


def unregister():
    del bpy.types.Scene.softshadow
    del bpy.types.Light.softshadow
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
