# What the user can run: passes for this frame, the compositor set-up, the scene file for the CLI.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Every operator body is wrapped: failures become self.report messages, never tracebacks."""
import os

import bpy

from . import api, compositor, native, replace, scene_export
from .plain_text import plain


def _library_ready(op):
    if native.available():
        return True
    op.report({"ERROR"}, plain("Soft Shadow: %s" % native.status()["error"]))
    return False


def _report_problems(op, problems):
    for problem in problems:
        op.report({"WARNING"}, plain("Soft Shadow: %s" % problem))


class SOFTSHADOW_OT_render_passes(bpy.types.Operator):
    """Compute the soft-shadow passes for the current frame and write them as a multilayer EXR"""
    bl_idname = "softshadow.render_passes"
    bl_label = "Render Soft Shadow Passes"
    bl_options = {"REGISTER"}

    def execute(self, context):
        if not _library_ready(self):
            return {"CANCELLED"}
        scene = context.scene
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            # No progress callback: it would run on the library's thread, where the window
            # manager must not be touched.
            path, problems, chosen = api.render_frame(scene, context.evaluated_depsgraph_get())
        except (native.SoftShadowError, native.LibraryUnavailable) as exc:
            self.report({"ERROR"}, plain("Soft Shadow: %s" % exc))
            return {"CANCELLED"}
        except Exception as exc:
            self.report({"ERROR"}, plain("Soft Shadow internal error: %s: %s" % (type(exc).__name__, exc)))
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        scene.softshadow.last_report = plain("; ".join(problems))
        if not path:
            # The popup's first line is the first report: the cause, not only the outcome.
            self.report({"ERROR"}, plain("Soft Shadow: no pass was produced: %s" % (
                problems[0] if problems else "no light casts a soft-shadow pass")))
            _report_problems(self, problems[1:])
            return {"CANCELLED"}
        _report_problems(self, problems)
        methods = ", ".join("%s: %s" % item for item in chosen.items())
        self.report({"INFO"}, plain("Soft Shadow: wrote %s (%s)" % (bpy.path.basename(path), methods)))
        return {"FINISHED"}


class SOFTSHADOW_OT_setup_compositor(bpy.types.Operator):
    """Insert a group that darkens the final image by a pass just before the compositor's output
(keeping the rest of the tree), and the Image node reading the passes"""
    bl_idname = "softshadow.setup_compositor"
    bl_label = "Set Up Soft Shadow Compositing"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        scene = context.scene
        view_layer = api.compositor_view_layer(scene)
        replacing = scene.softshadow.composite == "REPLACE"
        if replacing and replace.problem(scene, view_layer):
            self.report({"ERROR"}, plain("Soft Shadow: " + replace.problem(scene, view_layer)))
            return {"CANCELLED"}
        unframed = scene_export.frame_problem(scene)
        if unframed:  # nothing to wire: the render would get no pass
            self.report({"ERROR"}, plain("Soft Shadow: the compositor was not set up: " + unframed))
            return {"CANCELLED"}
        try:
            path = api.frame_exr_path(scene, view_layer=view_layer)
            if compositor.missing_sockets(scene, view_layer) or not os.path.exists(path):
                # The Image node gets its pass sockets from a pass file: make this frame's now,
                # so a render's first frame finds them (and a saved file carries them).
                if _library_ready(self):
                    path, problems, _ = api.render_frame(scene, view_layer=view_layer)
                    _report_problems(self, problems)
            path = path or api.frame_exr_path(scene, view_layer=view_layer)
            if replacing:
                node = compositor.image_node(scene, compositor.passes_image(path))
                changes = replace.setup(scene, view_layer, node)
            else:
                changes = replace.teardown(scene, view_layer)
                node, more = compositor.setup(scene, path)
                changes += more
        except Exception as exc:
            self.report({"ERROR"}, plain("Soft Shadow: compositor set-up failed: %s" % exc))
            return {"CANCELLED"}
        self.report({"INFO"}, plain("Soft Shadow: " + ("; ".join(changes) or "the compositor was already set up")))
        if not compositor.pass_sockets(node):
            self.report({"INFO"}, plain("Soft Shadow: nodes added; passes appear after the first render"))
        return {"FINISHED"}


class SOFTSHADOW_OT_export_scene(bpy.types.Operator):
    """Save the scene as a softshadow scene file for the command line tool"""
    bl_idname = "softshadow.export_scene"
    bl_label = "Export Soft Shadow Scene"
    bl_options = {"REGISTER"}

    filepath: bpy.props.StringProperty(subtype="FILE_PATH")
    filter_glob: bpy.props.StringProperty(default="*.json;*.ssc", options={"HIDDEN"})

    def invoke(self, context, event):
        if not self.filepath:
            self.filepath = bpy.path.ensure_ext(bpy.path.display_name_from_filepath(
                bpy.data.filepath) or "scene", ".json")
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        if not _library_ready(self):
            return {"CANCELLED"}
        try:
            problems = api.export_scene_file(context.scene, bpy.path.abspath(self.filepath),
                                             context.evaluated_depsgraph_get())
        except (native.SoftShadowError, native.LibraryUnavailable, OSError) as exc:
            self.report({"ERROR"}, plain("Soft Shadow: export failed: %s" % exc))
            return {"CANCELLED"}
        except Exception as exc:
            self.report({"ERROR"}, plain("Soft Shadow internal error: %s: %s" % (type(exc).__name__, exc)))
            return {"CANCELLED"}
        _report_problems(self, problems)
        self.report({"INFO"}, plain("Soft Shadow: exported %s" % self.filepath))
        return {"FINISHED"}


class SOFTSHADOW_OT_render_animation_passes(bpy.types.Operator):
    """Compute and write the passes for every frame of the scene's frame range (Esc cancels)"""
    bl_idname = "softshadow.render_animation_passes"
    bl_label = "Render Soft Shadow Passes for All Frames"
    bl_options = {"REGISTER"}

    _timer = None
    _frame = 0
    _problems = None

    def invoke(self, context, event):
        if not _library_ready(self):
            return {"CANCELLED"}
        scene = context.scene
        self._frame = scene.frame_start
        self._original = scene.frame_current
        self._problems = []
        self._written = 0
        wm = context.window_manager
        wm.progress_begin(scene.frame_start, scene.frame_end + 1)
        self._timer = wm.event_timer_add(0.01, window=context.window)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def _finish(self, context, cancelled):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.scene.frame_set(self._original)
        _report_problems(self, self._problems[:20])
        self.report({"INFO"}, "Soft Shadow: wrote %d frame(s)%s" % (
            self._written, " (cancelled)" if cancelled else ""))
        return {"CANCELLED"} if cancelled else {"FINISHED"}

    def modal(self, context, event):
        if event.type == "ESC":
            return self._finish(context, True)
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        scene = context.scene
        if self._frame > scene.frame_end:
            return self._finish(context, False)
        try:
            scene.frame_set(self._frame)
            path, problems, _ = api.render_frame(scene, context.evaluated_depsgraph_get())
            self._written += 1 if path else 0
            self._problems.extend("frame %d: %s" % (self._frame, p) for p in problems)
        except Exception as exc:
            self._problems.append("frame %d: %s" % (self._frame, exc))
        context.window_manager.progress_update(self._frame)
        self._frame += 1
        return {"RUNNING_MODAL"}


CLASSES = (SOFTSHADOW_OT_render_passes, SOFTSHADOW_OT_setup_compositor, SOFTSHADOW_OT_export_scene,
           SOFTSHADOW_OT_render_animation_passes)

register, unregister = bpy.utils.register_classes_factory(CLASSES)
