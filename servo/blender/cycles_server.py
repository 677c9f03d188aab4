# SPDX-License-Identifier: GPL-2.0-or-later
"""icgp's render server inside Blender: the servo simulator's camera, path traced by Cycles.

Run by CyclesSceneBackend (servo/src/cycles_scene_backend.cpp) as
    blender -b --factory-startup -noaudio --python cycles_server.py -- REPLY_FD
It reads one JSON request per line on standard input and answers each with one line on
REPLY_FD: "ok", or "error <message>". Blender's own messages go to standard output, which
the backend keeps in a log for its error messages. Images travel as files in the backend's
temporary folder, named in the requests.

Conventions are icgp's: poses are 4x4 row-major matrices, metres; a camera looks along its
+z with x right and y down; pixel (j, i) has its centre at image coordinates (u, v) = (j, i).
"""
import json
import math
import os
import sys
import traceback

import bpy
import numpy as np
from mathutils import Matrix, Vector

# icgp's camera frame (x right, y down, z forward) to Blender's (x right, y up, looking down -z).
ICGP_TO_BLENDER_CAMERA = Matrix.Diagonal((1.0, -1.0, -1.0, 1.0))


def matrix(values):
    return Matrix([values[0:4], values[4:8], values[8:12], values[12:16]])


class Server:
    def __init__(self):
        scene = bpy.context.scene
        for obj in list(bpy.data.objects):
            bpy.data.objects.remove(obj)
        scene.render.engine = 'CYCLES'
        scene.cycles.device = 'CPU'
        scene.cycles.use_denoising = False
        scene.cycles.use_adaptive_sampling = False
        scene.cycles.use_animated_seed = False
        scene.render.resolution_percentage = 100
        scene.render.image_settings.file_format = 'PNG'
        scene.render.image_settings.color_mode = 'RGB'
        scene.render.image_settings.color_depth = '8'
        # What a camera's image pipeline gives: sRGB, no tone-mapping curve.
        scene.view_settings.view_transform = 'Standard'
        scene.view_settings.look = 'None'
        scene.frame_current = 1
        self.scene = scene
        self.bodies = {}  # handle -> [Blender objects, one per mesh part]
        self.camera = bpy.data.objects.new('camera', bpy.data.cameras.new('camera'))
        scene.collection.objects.link(self.camera)
        scene.camera = self.camera
        self.camera.data.sensor_fit = 'HORIZONTAL'
        self.camera.rotation_mode = 'QUATERNION'
        self.camera.data.clip_start = 0.01
        self.camera.data.clip_end = 1000.0
        self.lamps = []  # sun lamps, made as the requests' lamps need them
        self.geometry_output = None

    # ---- requests --------------------------------------------------------------------------

    def setup(self, r):
        """Sampling, and the scene's light: sun lamps and ambient light, whose strengths and
        directions each colour request gives."""
        cycles = self.scene.cycles
        cycles.samples = int(r['samples'])
        cycles.max_bounces = int(r['light_bounces'])
        cycles.diffuse_bounces = min(cycles.max_bounces, cycles.diffuse_bounces)
        cycles.glossy_bounces = min(cycles.max_bounces, cycles.glossy_bounces)
        cycles.transparent_max_bounces = max(cycles.max_bounces, 1)
        cycles.caustics_reflective = False
        cycles.caustics_refractive = False
        if int(r['threads']) > 0:
            self.scene.render.threads_mode = 'FIXED'
            self.scene.render.threads = int(r['threads'])
        self.samples = cycles.samples
        self.lamp_angle = math.radians(float(r['lamp_angle_deg']))
        self.set_world()
        self.set_geometry_output(r['geometry_folder'])

    def set_light(self, r, world_T_blender_camera):
        ambient = float(r['ambient'])
        self.ambient.inputs['Color'].default_value = (ambient, ambient, ambient, 1.0)
        while len(self.lamps) < len(r['lamps']):
            lamp = bpy.data.objects.new('lamp', bpy.data.lights.new('lamp', 'SUN'))
            lamp.data.angle = self.lamp_angle
            lamp.rotation_mode = 'QUATERNION'
            self.scene.collection.objects.link(lamp)
            self.lamps.append(lamp)
        for i, lamp in enumerate(self.lamps):
            lamp.hide_render = i >= len(r['lamps'])
            if lamp.hide_render:
                continue
            # A white Lambertian surface facing a sun of irradiance E has radiance E / pi: the
            # sun's strength is pi * strength for that surface to read `strength`, as in the
            # OpenGL renderer.
            lamp.data.energy = math.pi * float(r['lamps'][i]['strength'])
            in_camera = Vector(r['lamps'][i]['direction_in_camera']).normalized()
            direction = world_T_blender_camera.to_3x3() @ (ICGP_TO_BLENDER_CAMERA.to_3x3() @ in_camera)
            lamp.rotation_quaternion = direction.to_track_quat('-Z', 'Y')

    def set_world(self):
        """Uniform ambient light that lights the scene but is not seen: the camera sees black
        where nothing is, as with the OpenGL renderer."""
        world = bpy.data.worlds.new('world')
        self.scene.world = world
        world.use_nodes = True
        nodes, links = world.node_tree.nodes, world.node_tree.links
        lit = nodes['Background']
        self.ambient = lit
        dark = nodes.new('ShaderNodeBackground')
        dark.inputs['Color'].default_value = (0.0, 0.0, 0.0, 1.0)
        path = nodes.new('ShaderNodeLightPath')
        mix = nodes.new('ShaderNodeMixShader')
        links.new(path.outputs['Is Camera Ray'], mix.inputs['Fac'])
        links.new(lit.outputs['Background'], mix.inputs[1])
        links.new(dark.outputs['Background'], mix.inputs[2])
        links.new(mix.outputs['Shader'], nodes['World Output'].inputs['Surface'])

    def set_geometry_output(self, folder):
        """Compositor nodes that write the depth (planar Z) and world normals of a render
        into one 32-bit OpenEXR: RGB = normal, A = Z."""
        layer = self.scene.view_layers[0]
        layer.use_pass_z = True
        layer.use_pass_normal = True
        self.scene.use_nodes = True
        tree = self.scene.node_tree
        for node in list(tree.nodes):
            tree.nodes.remove(node)
        passes = tree.nodes.new('CompositorNodeRLayers')
        packed = tree.nodes.new('CompositorNodeSetAlpha')
        packed.mode = 'REPLACE_ALPHA'
        tree.links.new(passes.outputs['Normal'], packed.inputs['Image'])
        tree.links.new(passes.outputs['Depth'], packed.inputs['Alpha'])
        out = tree.nodes.new('CompositorNodeOutputFile')
        out.base_path = folder
        out.format.file_format = 'OPEN_EXR'
        out.format.color_depth = '32'
        out.format.color_mode = 'RGBA'
        out.format.exr_codec = 'NONE'
        out.file_slots[0].path = 'geometry'
        tree.links.new(packed.outputs['Image'], out.inputs[0])
        self.geometry_output = os.path.join(folder, 'geometry%04d.exr' % self.scene.frame_current)

    def body(self, r):
        objects = []
        for index, part in enumerate(r['parts']):
            objects.append(self.make_part('body%d_%d' % (r['handle'], index), part))
        self.bodies[r['handle']] = objects

    def make_part(self, name, part):
        vertices = np.fromfile(part['vertices'], dtype=np.float32)
        triangles = np.fromfile(part['triangles'], dtype=np.int32)
        mesh = bpy.data.meshes.new(name)
        mesh.vertices.add(len(vertices) // 3)
        mesh.vertices.foreach_set('co', vertices)
        mesh.loops.add(len(triangles))
        mesh.loops.foreach_set('vertex_index', triangles)
        count = len(triangles) // 3
        mesh.polygons.add(count)
        mesh.polygons.foreach_set('loop_start', np.arange(0, 3 * count, 3, dtype=np.int32))
        mesh.polygons.foreach_set('loop_total', np.full(count, 3, dtype=np.int32))
        if part.get('texcoords'):
            uv = np.fromfile(part['texcoords'], dtype=np.float32).reshape(-1, 2)
            mesh.uv_layers.new().data.foreach_set('uv', uv[triangles].ravel())
        mesh.update()
        mesh.validate()
        mesh.materials.append(self.make_material(name, part))
        obj = bpy.data.objects.new(name, mesh)
        self.scene.collection.objects.link(obj)
        return obj

    def make_material(self, name, part):
        material = bpy.data.materials.new(name)
        material.use_nodes = True
        nodes, links = material.node_tree.nodes, material.node_tree.links
        bsdf = nodes['Principled BSDF']
        bsdf.inputs['Roughness'].default_value = float(part['roughness'])
        bsdf.inputs['Specular'].default_value = float(part['specular'])
        bsdf.inputs['Metallic'].default_value = float(part['metallic'])
        if part.get('texture'):
            texture = nodes.new('ShaderNodeTexImage')
            texture.image = bpy.data.images.load(part['texture'])
            texture.image.colorspace_settings.name = 'sRGB'
            links.new(texture.outputs['Color'], bsdf.inputs['Base Color'])
        else:
            bsdf.inputs['Base Color'].default_value = tuple(part['diffuse']) + (1.0,)
        return material

    def place(self, r):
        """Poses and visibility of the bodies, and the camera's intrinsics and pose."""
        for body in r['bodies']:
            world_T_body = matrix(body['world_T_body'])
            for obj in self.bodies[body['handle']]:
                obj.matrix_world = world_T_body
                obj.hide_render = not body['visible']
        fu, fv, pu, pv, width, height = r['intrinsics']
        render = self.scene.render
        render.resolution_x, render.resolution_y = int(width), int(height)
        # Non-square pixels: Blender's pixel aspect, which must be at least 1 on both axes.
        render.pixel_aspect_x, render.pixel_aspect_y = (1.0, fu / fv) if fu >= fv else (fv / fu, 1.0)
        camera = self.camera.data
        camera.sensor_width = float(width)
        camera.lens = float(fu)
        # Blender's optical axis meets the image at its centre, (width - 1) / 2 in icgp's
        # pixel-centre coordinates, moved by shift x width pixels (right; y: up).
        camera.shift_x = ((width - 1) / 2.0 - pu) / width
        camera.shift_y = (pv - (height - 1) / 2.0) / width * (fu / fv)
        end = matrix(r['world_T_camera']) @ ICGP_TO_BLENDER_CAMERA
        self.camera.animation_data_clear()
        start = r.get('exposure_start_world_T_camera')
        if start is None:
            self.camera.matrix_world = end
            self.scene.render.use_motion_blur = False
        else:
            # Cycles blurs along the camera's motion from frame 0 (the exposure's start) to
            # frame 1 (its end, the capture).
            self.key_camera(matrix(start) @ ICGP_TO_BLENDER_CAMERA, 0, None)
            self.key_camera(end, 1, self.camera.rotation_quaternion.copy())
            for curve in self.camera.animation_data.action.fcurves:
                for key in curve.keyframe_points:
                    key.interpolation = 'LINEAR'
            self.scene.render.use_motion_blur = True
            self.scene.cycles.motion_blur_position = 'END'
            self.scene.render.motion_blur_shutter = 1.0
            self.scene.frame_set(1)
        return end

    def key_camera(self, world_T_camera, frame, previous_rotation):
        location, rotation, _ = world_T_camera.decompose()
        if previous_rotation is not None and rotation.dot(previous_rotation) < 0.0:
            rotation.negate()  # the short way round
        self.camera.location = location
        self.camera.rotation_quaternion = rotation
        self.camera.keyframe_insert('location', frame=frame)
        self.camera.keyframe_insert('rotation_quaternion', frame=frame)

    def color(self, r):
        end = self.place(r)
        self.set_light(r, end)
        self.scene.cycles.samples = self.samples
        self.scene.cycles.seed = int(r['seed']) % 2147483647
        self.scene.cycles.pixel_filter_type = 'BLACKMAN_HARRIS'
        self.scene.cycles.filter_width = 1.5
        self.scene.use_nodes = False
        self.scene.render.filepath = r['out']
        bpy.ops.render.render(write_still=True)

    def geometry(self, r):
        """Depth and camera-frame normals: one sample through each pixel's centre, so that
        every pixel holds one surface's values, as the OpenGL renderer gives them."""
        end = self.place(r)
        self.scene.render.use_motion_blur = False
        self.scene.cycles.samples = 1
        self.scene.cycles.pixel_filter_type = 'BOX'
        self.scene.cycles.filter_width = 0.01
        self.scene.use_nodes = True
        self.scene.render.filepath = os.path.join(os.path.dirname(self.geometry_output), 'unused')
        bpy.ops.render.render(write_still=False)
        image = bpy.data.images.load(self.geometry_output)
        width, height = image.size
        pixels = np.empty(width * height * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
        bpy.data.images.remove(image)
        pixels = pixels.reshape(height, width, 4)[::-1]  # Blender's rows run bottom to top
        normals = pixels[:, :, :3]
        depth = pixels[:, :, 3].copy()
        seen = np.linalg.norm(normals, axis=2) > 0.5
        depth[~seen] = 0.0
        camera_R_world = np.array((end @ ICGP_TO_BLENDER_CAMERA).to_3x3().transposed())
        out = np.zeros((height, width, 4), dtype=np.float32)
        out[:, :, :3] = (normals @ camera_R_world.T) * seen[:, :, None]
        out[:, :, 3] = depth
        out.tofile(r['out'])


def main():
    reply = int(sys.argv[sys.argv.index('--') + 1])
    server = Server()
    handlers = {'setup': server.setup, 'body': server.body, 'color': server.color, 'geometry': server.geometry}
    for line in sys.stdin:
        request = json.loads(line)
        if request['op'] == 'quit':
            break
        try:
            handlers[request['op']](request)
            os.write(reply, b'ok\n')
        except Exception as error:  # the backend turns it into its exception, with the log
            traceback.print_exc()
            message = ('%s: %s' % (type(error).__name__, error)).replace('\n', ' ')
            os.write(reply, ('error ' + message + '\n').encode())


main()
