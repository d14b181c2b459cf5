# Blender's own glTF importer reads a brdfrig .glb; this script reports what it made of the
# material and renders the file's sphere with Cycles for the comparison in blender_test.cc.
#   blender -b --factory-startup --python blender_check.py -- MODEL.glb OUT.json OUT.exr \
#       WIDTH HEIGHT DISTANCE FOV_DEG LX LY LZ SAMPLES
# The scene matches three_render.mjs and brdfrig's renderer: the sphere scaled to radius 1 at
# the origin, a pinhole camera on +z looking at the origin with +y up, one sun lamp towards
# (LX, LY, LZ) of irradiance 1, a black world, no tone mapping (the EXR is linear radiance).
import json
import math
import sys

import bpy
import numpy
from mathutils import Vector

# Blender 3.4's importer asks numpy for np.bool, which numpy 1.24 (Debian 12's) removed; the
# builtin bool is what that alias always was.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

args = sys.argv[sys.argv.index("--") + 1:]
model, out_json, out_exr = args[0], args[1], args[2]
width, height = int(args[3]), int(args[4])
distance, fov_deg = float(args[5]), float(args[6])
light = Vector((float(args[7]), float(args[8]), float(args[9]))).normalized()
samples = int(args[10])

for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
bpy.ops.import_scene.gltf(filepath=model)

sphere = next((o for o in bpy.data.objects if o.type == "MESH" and "sphere" in o.name), None)
if sphere is None:
    raise SystemExit("no mesh object with sphere in its name in " + model)

report = {"blender": bpy.app.version_string, "materials": {}}
for slot in sphere.material_slots:
    material = slot.material
    values = {}
    for node in material.node_tree.nodes:
        if node.type != "BSDF_PRINCIPLED":
            continue
        for name in ("Base Color", "Metallic", "Roughness", "Specular", "Specular Tint", "IOR",
                     "Clearcoat", "Sheen"):
            socket = node.inputs[name]
            value = socket.default_value
            values[name] = list(value) if hasattr(value, "__len__") else value
            if socket.is_linked:
                values[name + " (linked)"] = socket.links[0].from_node.type
        values["distribution"] = node.distribution
        values["subsurface_method"] = node.subsurface_method
    report["materials"][material.name] = values

# The comparison scene: only the sphere, radius 1, at the origin.
for obj in list(bpy.data.objects):
    if obj != sphere:
        bpy.data.objects.remove(obj)
sphere.parent = None
sphere.location = (0, 0, 0)
sphere.rotation_mode = "XYZ"
sphere.rotation_euler = (0, 0, 0)
radius = max(abs(v.co.length) for v in sphere.data.vertices)
sphere.scale = (1 / radius, 1 / radius, 1 / radius)

scene = bpy.context.scene
camera_data = bpy.data.cameras.new("camera")
camera_data.sensor_fit = "VERTICAL"
camera_data.angle_y = math.radians(fov_deg)
camera_data.clip_start, camera_data.clip_end = 0.1, 100
camera = bpy.data.objects.new("camera", camera_data)
camera.location = (0, 0, distance)  # rotation 0: looks down -z with +y up
scene.collection.objects.link(camera)
scene.camera = camera

sun_data = bpy.data.lights.new("sun", "SUN")
sun_data.energy = 1.0  # irradiance, W/m², on a surface facing it
sun_data.angle = 0.0
sun = bpy.data.objects.new("sun", sun_data)
sun.rotation_mode = "QUATERNION"
sun.rotation_quaternion = light.to_track_quat("Z", "Y")  # the sun shines along its -z
scene.collection.objects.link(sun)

world = bpy.data.worlds.new("black")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
scene.world = world

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = samples
scene.cycles.use_denoising = False
scene.cycles.use_adaptive_sampling = False
scene.cycles.pixel_filter_type = "BOX"
scene.cycles.filter_width = 1.0
scene.cycles.max_bounces = 0  # direct light only, like the other renderers
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
scene.render.film_transparent = True
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.color_mode = "RGBA"
scene.render.filepath = out_exr
bpy.ops.render.render(write_still=True)

with open(out_json, "w") as f:
    json.dump(report, f, indent=1)
