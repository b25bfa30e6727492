# Where the settings show: light and output properties, and the add-on's preferences status.
# SPDX-License-Identifier: GPL-3.0-or-later
import bpy

from . import handlers, native
from .plain_text import plain


class SoftShadowPreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    def draw(self, context):
        draw_status(self.layout)


def draw_status(layout):
    """Library version, GL backend and renderer, or why the library could not load."""
    info = native.status()
    box = layout.box()
    if info["loaded"] and not info["error"]:
        box.label(text="Library: softshadow %s" % info["version"], icon="CHECKMARK")
        box.label(text="GL backend: %s" % (info["backend"] or "unknown"))
        box.label(text="Renderer: %s" % (info["renderer"] or "unknown"))
        if info.get("device"):
            box.label(text="EGL device used: %s (SOFTSHADOW_EGL_DEVICE chooses)" % info["device"])
        for device in info.get("egl_devices", []):
            box.label(text="  EGL %s" % device)
        if info.get("path"):
            box.label(text="Loaded from: %s" % info["path"])
        return
    box.label(text="Soft Shadow is not available", icon="ERROR")
    for line in _wrap(info["error"], 90):
        box.label(text=line)
    box.label(text="Looked in:")
    for path in info["looked"]:
        box.label(text="  " + path)
    box.label(text="Set SOFTSHADOW_LIB to the library's path, or reinstall the add-on zip.")


def _wrap(text, width):
    words, lines, line = text.split(), [], ""
    for word in words:
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = (line + " " + word).strip()
    return lines + ([line] if line else [])


def method_settings_text(method):
    """The settings the library lists for `method` (or "auto"), one line each: what the light's
    Method Settings field accepts."""
    try:
        listed = native.method_settings(method)
    except (native.LibraryUnavailable, native.SoftShadowError) as exc:
        return "The library cannot list the settings: %s" % exc
    lines = ["Settings of %s (key=value;key=value):" % method]
    for key, _type, default, allowed, doc in listed:
        facts = ", ".join(part for part in (("default " + default) if default else "", allowed) if part)
        lines.append("%s (%s): %s" % (key, facts, doc) if facts else "%s: %s" % (key, doc))
    return "\n".join(lines)


class SOFTSHADOW_OT_method_settings(bpy.types.Operator):
    """The valid Method Settings keys of the light's method"""
    bl_idname = "softshadow.method_settings"
    bl_label = "Method Settings Keys"
    bl_options = {"INTERNAL"}

    method: bpy.props.StringProperty(default="auto", options={"HIDDEN", "SKIP_SAVE"})

    @classmethod
    def description(cls, context, properties):
        return method_settings_text(properties.method)

    def execute(self, context):
        self.report({"INFO"}, method_settings_text(self.method))
        return {"FINISHED"}


class _SettingsPanel:
    """A Properties-editor panel over the `softshadow` settings of one ID (`owner`), with their
    on/off switch in its header."""
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"

    @staticmethod
    def owner(context):
        raise NotImplementedError

    @classmethod
    def poll(cls, context):
        owner = cls.owner(context)
        return owner is not None and hasattr(owner, "softshadow")

    def draw_header(self, context):
        self.layout.prop(self.owner(context).softshadow, "enabled", text="")


class SOFTSHADOW_PT_light(_SettingsPanel, bpy.types.Panel):
    bl_label = "Soft Shadow"
    bl_context = "data"
    COMPAT_ENGINES = {"CYCLES", "BLENDER_EEVEE", "BLENDER_WORKBENCH", "BLENDER_EEVEE_NEXT"}

    @staticmethod
    def owner(context):
        return context.light

    def draw(self, context):
        light = context.light
        props = light.softshadow
        layout = self.layout
        layout.use_property_split = True
        layout.active = props.enabled and light.use_shadow
        if not light.use_shadow:
            layout.label(text="Shadows are off for this light: no pass", icon="INFO")
        layout.prop(props, "method")
        layout.prop(props, "samples")
        row = layout.row(align=True)
        row.prop(props, "settings")
        row.operator(SOFTSHADOW_OT_method_settings.bl_idname, text="", icon="QUESTION").method = props.method
        layout.prop(props, "refine_final")
        chosen = handlers.last_report.get("chosen", {})
        obj = context.object
        if obj is not None and obj.name in chosen:
            layout.label(text="Last render used: %s" % chosen[obj.name])


class SOFTSHADOW_PT_output(_SettingsPanel, bpy.types.Panel):
    bl_label = "Soft Shadow Passes"
    bl_context = "output"

    @staticmethod
    def owner(context):
        return context.scene

    def draw(self, context):
        props = context.scene.softshadow
        layout = self.layout
        if not native.available():
            draw_status(layout)
            return
        layout.use_property_split = True
        col = layout.column()
        col.active = props.enabled
        col.prop(props, "output_path")
        col.prop(props, "on_failure")
        col.prop(props, "extra_layers")
        col.prop(props, "composite")
        sub = col.column()
        sub.active = props.composite == "DARKEN"
        sub.prop(props, "compositor_pass")
        col.prop(props, "strength")
        row = layout.row(align=True)
        row.operator("softshadow.render_passes", icon="RENDER_STILL", text="Render Passes")
        row.operator("softshadow.render_animation_passes", icon="RENDER_ANIMATION", text="All Frames")
        row = layout.row(align=True)
        row.operator("softshadow.setup_compositor", icon="NODETREE", text="Set Up Compositor")
        row.operator("softshadow.export_scene", icon="EXPORT", text="Export Scene")
        layout.prop(props, "preview")
        sub = layout.row()
        sub.active = props.preview
        sub.prop(props, "preview_scale")
        report = handlers.last_report
        if report.get("frame") is not None:
            written = bpy.path.basename(report["path"]) or "nothing written"
            layout.label(text=plain("Frame %d: %s" % (report["frame"], written)))
            for light, cause in list(report.get("failed", {}).items())[:5]:
                layout.label(text=plain("Light '%s' failed (not shadowed in the composite): %s" % (light, cause)),
                             icon="ERROR")
            for problem in [p for p in report["problems"] if p not in report.get("failed", {}).values()][:5]:
                layout.label(text=plain(problem), icon="ERROR")


CLASSES = (SoftShadowPreferences, SOFTSHADOW_OT_method_settings, SOFTSHADOW_PT_light, SOFTSHADOW_PT_output)

register, unregister = bpy.utils.register_classes_factory(CLASSES)
