# What the user can set: per light (pass on/off, method, quality), per scene (output, layers).
# SPDX-License-Identifier: GPL-3.0-or-later
import bpy

from . import native

# The light's method menu: the library's methods (ss_method_name), in its order, after "auto".
# This table only labels them for the interface; when the library cannot be loaded its keys
# stand in for the list (test_method_list_comes_from_the_library checks they are the same list).
METHOD_LABELS = {
    "auto": ("Auto", "Render each fast method and keep the one with the least error on a sparse "
                     "ray-traced check (the report says which)"),
    "shadow_map": ("Shadow Map", "Hard shadow from the light centre (fast baseline)"),
    "pcss": ("PCSS", "Percentage-closer soft shadows"),
    "dbuffer": ("D-Buffer", "Umbra/penumbra volumes with a D-buffer (disk lights)"),
    "sweep": ("Sweep", "Geometric sweep line over light samples (planar receivers)"),
    "penumbra_map": ("Penumbra Map", "Shadow map with cones and sheets (sphere/disk lights)"),
    "occlusion_textures": ("Occlusion Textures", "Slices with pre-filtering (rectangle lights)"),
    "reference": ("Reference", "Ray traced with stratified light samples (slow, exact)"),
}

# Blender keeps no reference to the strings a dynamic enum returns: they must outlive the call.
_method_items = []


def method_items(self=None, context=None):
    """The menu's items; each item's number is its place in the list ("auto" 0), the numbers the
    saved files of the earlier fixed menu hold."""
    try:
        names = ("auto",) + native.method_names()
    except native.LibraryUnavailable:
        names = tuple(METHOD_LABELS)
    items = [(name, *METHOD_LABELS.get(name, (name.replace("_", " ").title(), "")), number)
             for number, name in enumerate(names)]
    if items != _method_items:
        _method_items[:] = items  # replaced only when the list changes (the library loaded)
    return _method_items


class SoftShadowLightSettings(bpy.types.PropertyGroup):
    enabled: bpy.props.BoolProperty(
        name="Soft Shadow Pass", default=True,
        description="Compute a soft-shadow visibility pass for this light")
    # A dynamic enum takes no string default; an unset value is item 0, "auto".
    method: bpy.props.EnumProperty(name="Method", items=method_items)
    samples: bpy.props.IntProperty(
        name="Samples", default=0, min=0, soft_max=1024,
        description="Light samples for sampling methods (0: the method's default)")
    settings: bpy.props.StringProperty(
        name="Method Settings", default="",
        description="Advanced method quality settings as key=value;key=value; the ? button beside "
                    "the field lists the valid keys of the light's method")
    refine_final: bpy.props.BoolProperty(
        name="Refine Final Renders", default=True,
        description="In final renders (F12, blender -b) ray trace the pixels the method cannot "
                    "decide, its penumbra and a margin, after checking the rest with a few rays "
                    "(Method Settings' refine_margin, refine_samples, ... tune it): shadows as close "
                    "to Cycles as EEVEE's best, in seconds. The viewport preview stays fast")
    replaces_shadow: bpy.props.BoolProperty(
        name="Pass Replaces the Shadow", default=False, options={"HIDDEN"},
        description="Set by the Replace composite: the renderer's shadow of this light is off "
                    "and the pass puts the shadow back")
    home_collections: bpy.props.StringProperty(
        name="Collections Before Replace", default="", options={"HIDDEN"},
        description="EEVEE Replace moves the light into a collection of its own; these are the "
                    "collections it goes back to (names joined by ';')")


FAILURE_ITEMS = [
    ("STOP", "Stop the Render",
     "In the background (blender -b) exit with code 3 before a frame whose passes failed is "
     "rendered; the interface reports the problem and goes on"),
    ("CONTINUE", "Report and Continue",
     "Report the problem and render the frame without its passes, also in the background"),
]


def _enabled_changed(self, context):
    # In the interface the render handlers run on the render thread; Blender's rule for handlers
    # that touch data there is a locked interface (bpy.app.handlers, "Note on Altering Data").
    if self.enabled:
        self.id_data.render.use_lock_interface = True


def _strength_changed(self, context):
    from . import compositor  # (properties register first: no import at module level)
    compositor.apply_strength(context.scene)


def _pass_items(self, context):
    from . import compositor
    return compositor.pass_enum_items(context.scene if context else None)


# The choice is kept by name (compositor_pass_name): a dynamic enum stores a number, which would
# silently point at another pass when the list changes.
def _pass_get(self):
    from . import compositor
    return compositor.pass_enum_number(self.compositor_pass_name)


def _pass_set(self, value):
    from . import compositor
    self.compositor_pass_name = compositor.pass_enum_name(value)
    compositor.relink_chosen(bpy.context.scene)


class SoftShadowSceneSettings(bpy.types.PropertyGroup):
    enabled: bpy.props.BoolProperty(
        name="Soft Shadow Passes", default=False, update=_enabled_changed,
        description="Compute the passes before each render of this scene and write them as a "
                    "multilayer EXR per frame and view layer (also locks the interface during "
                    "renders, as Blender requires of handlers that read and change data)")
    on_failure: bpy.props.EnumProperty(
        name="On Failure", items=FAILURE_ITEMS, default="STOP",
        description="What a render does when a frame's passes cannot be made")
    output_path: bpy.props.StringProperty(
        name="Pass Files", subtype="FILE_PATH", default="",
        description="Template of the pass files: {scene}, {view_layer} and # for the frame "
                    "(empty: a 'softshadow' folder beside the render output, following its # padding)")
    extra_layers: bpy.props.BoolProperty(
        name="Extra Layers", default=False,
        description="Also write umbra, penumbra, mask and the methods' debug layers")
    composite: bpy.props.EnumProperty(
        name="Composite", default="DARKEN", items=[
            ("DARKEN", "Darken", "Multiply the final image by one pass (a quick look: the renderer's "
             "own shadow stays, so that light's shadow is darkened twice)"),
            ("REPLACE", "Replace", "Each light's own shadow is switched off in the renderer, its "
             "contribution (Cycles: a light group; EEVEE: a view layer without it) is multiplied "
             "by its pass and summed back"),
        ], description="How Set Up Compositor uses the passes")
    compositor_pass_name: bpy.props.StringProperty(name="Darken By (name)", default="",
                                                   options={"HIDDEN"})
    compositor_pass: bpy.props.EnumProperty(
        name="Darken By", items=_pass_items, get=_pass_get, set=_pass_set,
        description="The pass the compositor's darken group multiplies by (the passes of the last "
                    "pass file)")
    strength: bpy.props.FloatProperty(name="Strength", default=1.0, min=0.0, max=1.0,
                                      update=_strength_changed,
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
    def render_passes(self, lights=None, methods=None, extra_layers=False, final=None, view_layer=None):
        """The passes of this scene's current frame: see api.render_passes."""
        from . import api
        return api.render_passes(self.id_data, lights=lights, methods=methods, extra_layers=extra_layers,
                                 final=final, view_layer=view_layer)

    def write_pass_files(self, frames, lights=None):
        """Only the pass files of `frames` ('1-12'), nothing rendered: see api.write_pass_files."""
        from . import api
        return api.write_pass_files(self.id_data, frames, lights=lights)

    def passes_problems(self):
        """What the last render_passes call left out, and why."""
        from . import api
        return list(api.render_passes.last_problems)


CLASSES = (SoftShadowLightSettings, SoftShadowSceneSettings)


_register_classes, _unregister_classes = bpy.utils.register_classes_factory(CLASSES)


def register():
    _register_classes()
    bpy.types.Light.softshadow = bpy.props.PointerProperty(type=SoftShadowLightSettings)
    bpy.types.Scene.softshadow = bpy.props.PointerProperty(type=SoftShadowSceneSettings)


def unregister():
    del bpy.types.Scene.softshadow
    del bpy.types.Light.softshadow
    _unregister_classes()
