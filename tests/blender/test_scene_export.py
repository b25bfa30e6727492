# Does the depsgraph export see what the render sees: instances, modifiers, hidden objects, flags?
# SPDX-License-Identifier: GPL-3.0-or-later
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sstest  # noqa: E402
import bpy  # noqa: E402

ss = sstest.addon()
se = ss.scene_export


def _export(scene, mode="RENDER"):
    return se.export(bpy.context.evaluated_depsgraph_get(), scene, mode=mode)


def _mesh(exported, name):
    found = [m for m in exported.meshes if m["name"] == name]
    sstest.check(len(found) == 1, "one mesh named %r in %s" % (name, [m["name"] for m in exported.meshes]))
    return found[0]


def test_world_space_and_modifiers():
    scene = sstest.standard_scene()
    box = sstest.add_box("Twisted", 1.0, (2, 3, 1))
    box.rotation_euler = (0, 0, math.pi / 4)
    box.modifiers.new("Sub", "SUBSURF").levels = 1
    exported = _export(scene)
    mesh = _mesh(exported, "Twisted")
    # One subdivision level of a cube: 6 faces x 4 quads x 2 triangles.
    sstest.check(mesh["triangles"].shape == (48, 3), "modifier applied: %s" % (mesh["triangles"].shape,))
    centre = sstest.world_vertices(mesh).mean(axis=0)
    sstest.check(np.allclose(centre, (2, 3, 1), atol=1e-5), "world space: centre %s" % centre)
    sstest.check(sstest.world_vertices(mesh).dtype == np.float32 and mesh["local"].dtype == np.float32
                 and mesh["triangles"].dtype == np.uint32, "dtypes")


def test_hidden_and_disabled_left_out():
    scene = sstest.standard_scene()
    sstest.add_box("NoRender", 0.5, (2, 2, 1)).hide_render = True
    hidden_view = sstest.add_box("HiddenInViewport", 0.5, (2, -2, 1))
    hidden_view.hide_set(True)
    coll = bpy.data.collections.new("Off")
    scene.collection.children.link(coll)
    inside = sstest.add_box("InOffCollection", 0.5, (-2, 2, 1))
    scene.collection.objects.unlink(inside)
    coll.objects.link(inside)
    coll.hide_render = True
    render = {m["name"] for m in _export(scene, "RENDER").meshes}
    sstest.check("NoRender" not in render and "InOffCollection" not in render, "render: %s" % render)
    sstest.check("HiddenInViewport" in render, "hidden in the viewport still renders: %s" % render)
    viewport = {m["name"] for m in _export(scene, "VIEWPORT").meshes}
    sstest.check("HiddenInViewport" not in viewport, "viewport leaves out hidden: %s" % viewport)
    sstest.check("NoRender" in viewport, "hide_render does not hide in the viewport: %s" % viewport)


def test_cast_and_receive_flags():
    scene = sstest.standard_scene()
    ghost = sstest.add_box("NoShadow", 0.5, (2, 2, 1))
    ghost.visible_shadow = False
    unseen = sstest.add_box("NotSeen", 0.5, (-2, 2, 1))
    unseen.visible_camera = False
    exported = _export(scene)
    native = ss.native
    sstest.check(_mesh(exported, "Ground")["flags"] == native.MESH_CAST | native.MESH_RECEIVE, "default flags")
    sstest.check(_mesh(exported, "NoShadow")["flags"] == native.MESH_RECEIVE, "visible_shadow off: no cast")
    sstest.check(_mesh(exported, "NotSeen")["flags"] == native.MESH_CAST | native.MESH_CAMERA_HIDDEN,
                 "camera-invisible: casts, the camera sees past it")


def test_collection_and_geometry_nodes_instances():
    scene = sstest.standard_scene()
    coll = bpy.data.collections.new("Props")
    prop = sstest.add_box("Prop", 0.4, (0, 0, 0))
    scene.collection.objects.unlink(prop)
    coll.objects.link(prop)
    for i, x in enumerate((-3.0, 3.0)):
        empty = bpy.data.objects.new("Set%d" % i, None)
        empty.instance_type = "COLLECTION"
        empty.instance_collection = coll
        empty.location = (x, 3, 1)
        scene.collection.objects.link(empty)
    # Geometry nodes: a cube instanced on the 3 points of a mesh line (not realized).
    group = bpy.data.node_groups.new("Scatter", "GeometryNodeTree")
    ss.compat.add_group_socket(group, "INPUT", "NodeSocketGeometry", "Geometry")
    ss.compat.add_group_socket(group, "OUTPUT", "NodeSocketGeometry", "Geometry")
    out = group.nodes.new("NodeGroupOutput")
    line = group.nodes.new("GeometryNodeMeshLine")
    line.inputs["Count"].default_value = 3
    line.inputs["Offset"].default_value = (1.0, 0.0, 0.0)
    cube = group.nodes.new("GeometryNodeMeshCube")
    cube.inputs["Size"].default_value = (0.3, 0.3, 0.3)
    on_points = group.nodes.new("GeometryNodeInstanceOnPoints")
    group.links.new(line.outputs["Mesh"], on_points.inputs["Points"])
    group.links.new(cube.outputs["Mesh"], on_points.inputs["Instance"])
    group.links.new(on_points.outputs["Instances"], out.inputs["Geometry"])
    holder = sstest.add_plane("Scatterer", 1.0, (0, -3, 1))
    holder.modifiers.new("GN", "NODES").node_group = group
    exported = _export(scene)
    names = [m["name"] for m in exported.meshes]
    sets = [n for n in names if n.startswith("Set")]
    sstest.check(len(sets) == 2, "two collection instances: %s" % names)
    xs = sorted(float(sstest.world_vertices(m)[:, 0].mean()) for m in exported.meshes if m["name"] in sets)
    sstest.check(np.allclose(xs, [-3, 3], atol=1e-5), "instances placed by their empties: %s" % xs)
    gn = [m for m in exported.meshes if m["name"].startswith("Scatterer")
          and len(m["triangles"]) == 12]
    sstest.check(len(gn) == 3, "three geometry-nodes cube instances: %s" % names)
    gx = sorted(float(sstest.world_vertices(m)[:, 0].mean()) for m in gn)
    sstest.check(np.allclose(gx, [0, 1, 2], atol=1e-5), "instances along the line: %s" % gx)


def test_lights_and_camera():
    scene = sstest.standard_scene(64, 48)
    spot = sstest.add_light("Spot", "SPOT", (1, 1, 4))
    spot.data.spot_size = 0.8
    spot.data.spot_blend = 0.3
    spot.data.shadow_soft_size = 0.2
    sun = sstest.add_light("Sun", "SUN", (0, 0, 9))
    sun.data.angle = 0.05
    rect = sstest.add_light("Rect", "AREA", (2, 0, 4), shape="RECTANGLE", size=1.0)
    rect.data.size_y = 0.25
    exported = _export(scene)
    lights = {l["name"]: l for l in exported.lights}
    sstest.check(lights["Spot"]["type"] == "SPOT" and abs(lights["Spot"]["radius"] - 0.2) < 1e-6, "spot")
    sstest.check(abs(lights["Spot"]["spot_size"] - 0.8) < 1e-6 and abs(lights["Spot"]["spot_blend"] - 0.3) < 1e-6,
                 "spot cone")
    sstest.check(lights["Sun"]["type"] == "SUN" and abs(lights["Sun"]["angle"] - 0.05) < 1e-6, "sun angle")
    sstest.check(lights["Rect"]["type"] == "RECTANGLE" and lights["Rect"]["size_y"] == 0.25, "rectangle")
    sstest.check(np.allclose(lights["Rect"]["light_to_world"][12:15], (2, 0, 4)), "light position (column-major)")
    cam = exported.camera
    sstest.check((cam["width"], cam["height"]) == (64, 48), "camera resolution")
    # The camera at (0, 0, 10) looking down: the view matrix moves the world by -10 in z.
    sstest.check(abs(cam["world_to_camera"][14] + 10.0) < 1e-5, "view translation: %s" % cam["world_to_camera"])


if __name__ == "__main__":
    sstest.run(dict(globals()))
