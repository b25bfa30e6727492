# Which Blender API shape is in front of us: the few 3.x / 4.x / 5.x differences, in one place.
# SPDX-License-Identifier: GPL-3.0-or-later
"""Version differences, written against duck-typed objects so they test without Blender.

- 5.0 moved the compositor tree from `scene.node_tree` (with `scene.use_nodes`) to a node
  group assigned to `scene.compositing_node_group`; its final image goes to the group's Group
  Output (an `Image` output socket) instead of a Composite node, and the compositor's MixRGB
  became the shared `ShaderNodeMix` (sockets by identifier: Factor_Float, A_Color, B_Color).
- EEVEE's engine id is BLENDER_EEVEE in 3.x and 5.x, BLENDER_EEVEE_NEXT in 4.2-4.5.
- 4.0 removed `bgl`: the preview draws with the `gpu` module only (never import bgl).
- 4.0 dropped the dpi argument of `blf.size(font, size, dpi)`.
- Point/spot/area radius is `shadow_soft_size` in 3.x and 4.x (`radius` in the UI).
- 3.0+ objects carry `visible_shadow` / `visible_camera`; older files had `cycles_visibility`.
- Materials' EEVEE `shadow_method` went with EEVEE Next (4.2): from then on an object casts
  in both engines when its `visible_shadow` says so.
- 4.0 added light and shadow linking: a light object's `light_linking.receiver_collection` and
  `blocker_collection`, with each member's INCLUDE/EXCLUDE in `collection_objects[i]` and
  `collection_children[i]` (index-paired with `objects` and `children`); 3.x has none.
"""


def version_tuple(app):
    """(major, minor, patch) of a bpy.app-like object."""
    return tuple(getattr(app, "version", (0, 0, 0)))[:3]


def blf_size(blf, app, font, size):
    """Sets a font's size in every version (4.0 dropped the dpi argument)."""
    if version_tuple(app) >= (4, 0, 0):
        blf.size(font, size)
    else:
        blf.size(font, size, 72)


def compositor_tree(scene, create=False, bpy_data=None):
    """The scene's compositor node tree, or None. With create=True it is made when missing."""
    if hasattr(scene, "compositing_node_group"):  # 5.0+
        tree = scene.compositing_node_group
        if tree is None and create:
            if bpy_data is None:
                return None
            tree = bpy_data.node_groups.new("Compositor", "CompositorNodeTree")
            scene.compositing_node_group = tree
        return tree
    if create and hasattr(scene, "use_nodes") and not scene.use_nodes:
        scene.use_nodes = True
    return getattr(scene, "node_tree", None)


def _first(tree, bl_idname):
    return next((n for n in tree.nodes if n.bl_idname == bl_idname), None)


def compositor_output(tree, types):
    """(node, socket) that takes the compositor's final image: the Composite node before 5.0,
    the tree's Group Output after (its `Image` output socket made when missing). `types` is
    bpy.types. Returns (node, created)."""
    if hasattr(types, "CompositorNodeComposite"):
        node = _first(tree, "CompositorNodeComposite")
        created = node is None
        if created:
            node = tree.nodes.new("CompositorNodeComposite")
        return node, created
    if "Image" not in group_sockets(tree, "OUTPUT"):
        add_group_socket(tree, "OUTPUT", "NodeSocketColor", "Image")
    node = _first(tree, "NodeGroupOutput")
    created = node is None
    if created:
        node = tree.nodes.new("NodeGroupOutput")
    return node, created


def new_color_mix(nodes, types, blend_type):
    """A colour mix node in a compositor tree: (node, factor, a, b, result) sockets."""
    if hasattr(types, "CompositorNodeMixRGB"):
        node = nodes.new("CompositorNodeMixRGB")
        node.blend_type = blend_type
        return node, node.inputs[0], node.inputs[1], node.inputs[2], node.outputs[0]
    node = nodes.new("ShaderNodeMix")
    node.data_type = "RGBA"
    node.blend_type = blend_type

    def socket(sockets, identifier):
        return next(s for s in sockets if s.identifier == identifier)
    return (node, socket(node.inputs, "Factor_Float"), socket(node.inputs, "A_Color"),
            socket(node.inputs, "B_Color"), socket(node.outputs, "Result_Color"))


def eevee_engine_id(render):
    """The identifier of EEVEE among `render.engine`'s choices (scene.render)."""
    items = {item.identifier for item in render.bl_rna.properties["engine"].enum_items}
    return "BLENDER_EEVEE_NEXT" if "BLENDER_EEVEE_NEXT" in items else "BLENDER_EEVEE"


def has_bgl(app):
    return version_tuple(app) < (4, 0, 0)


def light_radius(light):
    """The sphere radius of a point/spot light (and the soft size of legacy area lights)."""
    for name in ("shadow_soft_size", "radius"):
        value = getattr(light, name, None)
        if value is not None:
            return float(value)
    return 0.0


def _ray_visibility(obj, ray):
    """One of the object's Cycles ray visibilities: `visible_<ray>` (3.0+), else the older
    `cycles_visibility.<ray>`; True where neither exists."""
    value = getattr(obj, "visible_" + ray, None)
    if value is not None:
        return bool(value)
    legacy = getattr(getattr(obj, "cycles_visibility", None), ray, None)
    return True if legacy is None else bool(legacy)


def object_casts_shadow(obj):
    """The object's own shadow visibility."""
    return _ray_visibility(obj, "shadow")


def object_camera_visible(obj):
    return _ray_visibility(obj, "camera")


def materials_cast_shadow(materials):
    """False only when every material says EEVEE `shadow_method == 'NONE'` (3.x-4.1)."""
    methods = [getattr(m, "shadow_method", None) for m in materials if m is not None]
    methods = [m for m in methods if m is not None]
    if not methods:
        return True
    return any(m != "NONE" for m in methods)


def material_shadow_alpha(material, engine):
    """How a material's alpha shadows under `engine` (scene.render.engine): "alpha" (Cycles, and
    EEVEE's hashed or transparent shadows), "clip" (EEVEE 3.x-4.1 shadow_method CLIP: alpha
    thresholded at alpha_threshold) or "opaque" (EEVEE's opaque shadows: the alpha is ignored)."""
    if "EEVEE" not in str(engine):
        return "alpha"
    transparent = getattr(material, "use_transparent_shadow", None)  # 4.2+
    if transparent is not None:
        return "alpha" if transparent else "opaque"
    method = getattr(material, "shadow_method", "OPAQUE")
    return {"CLIP": "clip", "HASHED": "alpha"}.get(method, "opaque")


def light_use_shadow(light):
    return bool(getattr(light, "use_shadow", True))


def extension_or_legacy_package(package_name):
    """The add-on's module name as preferences know it ('bl_ext.<repo>.softshadow' in 4.2+)."""
    return package_name


def group_sockets(group, in_out):
    """The names of a node group's inputs or outputs (4.0+ interface or 3.x inputs/outputs)."""
    interface = getattr(group, "interface", None)
    if interface is not None and hasattr(interface, "items_tree"):
        return [item.name for item in interface.items_tree
                if getattr(item, "item_type", "SOCKET") == "SOCKET" and item.in_out == in_out]
    return [s.name for s in (group.inputs if in_out == "INPUT" else group.outputs)]


def add_group_socket(group, in_out, socket_type, name):
    """Adds an input/output socket to a node group (4.0+ interface or 3.x inputs/outputs)."""
    interface = getattr(group, "interface", None)
    if interface is not None and hasattr(interface, "new_socket"):
        return interface.new_socket(name, in_out=in_out, socket_type=socket_type)
    sockets = group.inputs if in_out == "INPUT" else group.outputs
    return sockets.new(socket_type, name)


def _cycles_own_shadow(light, engine):
    cycles = getattr(light, "cycles", None)
    return engine == "CYCLES" and cycles is not None and hasattr(cycles, "cast_shadow")


def set_renderer_shadow(light, on, engine="CYCLES"):
    """Switches a render engine's own shadow of a light: Cycles' `cast_shadow` up to 3.6, else
    `use_shadow` (EEVEE's in every version; shared with Cycles from 4.0 on)."""
    if _cycles_own_shadow(light, engine):
        light.cycles.cast_shadow = on
    else:
        light.use_shadow = on


def renderer_shadow(light, engine="CYCLES"):
    if _cycles_own_shadow(light, engine):
        return bool(light.cycles.cast_shadow)
    return bool(light.use_shadow)


def lightgroup_pass(view_layer, obj, name):
    """Puts a light object in a Cycles light group of the view layer (3.2+), made when missing.
    Returns the Render Layers output that carries the group: "Combined_<name>"."""
    if name not in [group.name for group in view_layer.lightgroups]:
        view_layer.lightgroups.add(name=name)
    obj.lightgroup = name
    return "Combined_" + name


def supports_lightgroups(view_layer):
    return hasattr(view_layer, "lightgroups")


def _link_set(collection):
    """A linking collection as Blender resolves it for one light: None (every object: no
    collection, or one with no object in it), ("only", names, members) when some member is
    included (the included ones, minus those excluded), ("except", names, members) when all are
    excluded; `members` are every object the collection names, either way. A
    direct member's own state wins over the state of the child collection it is also reached
    through; an object in a child collection (at any depth) takes that first-level child's
    state, the later child winning."""
    if collection is None:
        return None
    states = {}
    children = list(getattr(collection, "children", ()))
    child_links = list(getattr(collection, "collection_children", ()))
    for child, link in zip(children, child_links):
        for obj in child.all_objects:
            states[obj.name] = link.light_linking.link_state
    for obj, link in zip(list(collection.objects), list(getattr(collection, "collection_objects", ()))):
        states[obj.name] = link.light_linking.link_state
    if not states:
        return None
    members = frozenset(states)
    included = frozenset(n for n, s in states.items() if s == "INCLUDE")
    if included:
        return ("only", included, members)
    return ("except", members, members)


def light_links(light_object):
    """(receivers, blockers) of a light object (the original, not the evaluated copy): each
    None (every object) or a _link_set() pair. (None, None) before 4.0."""
    linking = getattr(light_object, "light_linking", None)
    if linking is None:
        return None, None
    return (_link_set(getattr(linking, "receiver_collection", None)),
            _link_set(getattr(linking, "blocker_collection", None)))


def link_objects(meshes, link_sets):
    """The object each exported mesh answers to for one kind of link (receivers or blockers),
    given every light's link set of that kind: an instance takes its instancer's links when
    some collection of that kind names the instancer (as Cycles does), else its own object's."""
    named = set()
    for link_set in link_sets:
        if link_set is not None:
            named |= link_set[2]
    return [mesh["instancer"] if mesh.get("instancer") in named else mesh.get("object", mesh["name"])
            for mesh in meshes]


def linked_meshes(link_set, mesh_objects):
    """The indices of `mesh_objects` (object names, one per exported mesh) a link set holds,
    or None for every mesh."""
    if link_set is None:
        return None
    kind, names, _ = link_set
    if kind == "only":
        return [i for i, name in enumerate(mesh_objects) if name in names]
    return [i for i, name in enumerate(mesh_objects) if name not in names]
