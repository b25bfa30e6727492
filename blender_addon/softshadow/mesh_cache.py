# Which meshes can an export take from its last read instead of reading Blender again?
# SPDX-License-Identifier: GPL-3.0-or-later
"""A MeshCache keeps the object-space arrays an export read from one depsgraph, per object, and
drops an object's arrays when that depsgraph reports its geometry changed (depsgraph.updates in
depsgraph_update_post and frame_change_post: a modifier, shape key, driver or edit that changes
the evaluated mesh flags the object's geometry). A moved object keeps its arrays: its matrix is
read every export.

Whatever the updates cannot vouch for empties the cache, so the next export reads everything:
another depsgraph, a file load, undo/redo, and a frame change while other frame_change_post
handlers are registered (Blender evaluates what those change after the handlers ran, without
reporting it)."""
import bpy

from . import app_handlers


class MeshCache:
    def __init__(self):
        self.graph = None     # (depsgraph pointer, scene name, view layer name) the arrays came from
        self.entries = {}     # object name -> (identity, local vertices, triangles)

    def clear(self):
        self.graph, self.entries = None, {}

    def bind(self, depsgraph):
        """Keeps the arrays when `depsgraph` is the one they were read from, else drops them."""
        graph = (depsgraph.as_pointer(), depsgraph.scene.name, depsgraph.view_layer.name)
        if graph != self.graph:
            self.clear()
            self.graph = graph

    @staticmethod
    def identity(obj):
        """What must be unchanged besides the updates: the object and its data block."""
        original = obj.original
        data = original.data
        return (obj.type, original.as_pointer(), data.as_pointer() if data is not None else 0)

    def get(self, obj):
        entry = self.entries.get(obj.original.name)
        if entry is None or entry[0] != self.identity(obj):
            return None
        return entry[1], entry[2]

    def put(self, obj, local, triangles):
        self.entries[obj.original.name] = (self.identity(obj), local, triangles)

    def note(self, depsgraph, updates):
        """Drops the arrays of the objects whose geometry `updates` (of `depsgraph`) changed."""
        if self.graph is None or depsgraph.as_pointer() != self.graph[0]:
            return
        for update in updates:
            block = getattr(update.id, "original", update.id)
            if isinstance(block, bpy.types.Object):
                # anything but a pure move may have changed the evaluated mesh
                if update.is_updated_geometry or not update.is_updated_transform:
                    self.entries.pop(block.name, None)
            elif update.is_updated_geometry:
                # a data block (mesh, curve, shape keys): its users' objects report too; this
                # also covers an object whose own update Blender might fold into its data's
                for name, entry in list(self.entries.items()):
                    if entry[0][2] == block.as_pointer():
                        del self.entries[name]


# The cache of render_passes' kept scene (passes._render_scene).
render_meshes = MeshCache()
_CACHES = (render_meshes,)


def unreported_frame_edits():
    """Whether a frame change may change data without depsgraph.updates saying so: a
    frame_change_post handler not of this add-on is registered (Blender evaluates its edits
    after the handlers ran, without reporting them)."""
    package = __name__.rpartition(".")[0]

    def ours(fn):
        module = getattr(fn, "__module__", None) or ""
        return module == package or module.startswith(package + ".")
    return not all(ours(fn) for fn in bpy.app.handlers.frame_change_post)


@bpy.app.handlers.persistent
def _on_depsgraph_update(scene, depsgraph=None, *_args):
    for cache in _CACHES:
        if depsgraph is None:
            cache.clear()
        else:
            cache.note(depsgraph, depsgraph.updates)


@bpy.app.handlers.persistent
def _on_frame_change(scene, depsgraph=None, *_args):
    foreign = unreported_frame_edits()
    for cache in _CACHES:
        if depsgraph is None or foreign:
            cache.clear()
        else:
            cache.note(depsgraph, depsgraph.updates)


@bpy.app.handlers.persistent
def _on_anything(*_args):
    for cache in _CACHES:
        cache.clear()


_HANDLERS = (("depsgraph_update_post", _on_depsgraph_update), ("frame_change_post", _on_frame_change),
             ("load_pre", _on_anything), ("load_post", _on_anything), ("undo_post", _on_anything),
             ("redo_post", _on_anything))


def register():
    app_handlers.attach(_HANDLERS)


def unregister():
    app_handlers.detach(_HANDLERS)
    for cache in _CACHES:
        cache.clear()
