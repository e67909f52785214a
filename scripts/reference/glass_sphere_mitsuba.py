"""Independent reference for test/materials/glass-sphere-reference.test.ts, rendered with Mitsuba 3.

The scene is test/materials/fixtures/glass-sphere/scene.json: the same meshes as the test builds
(the icosphere of test/helpers/meshes.ts, ported below, with its vertex normals; two-triangle plane
and light quads), the same pinhole camera (vertical field of view, box pixel filter) and materials:
  - sphere: Mitsuba's smooth `dielectric` (int_ior, ext_ior 1): exact Fresnel, TIR, the 1 / eta^2
    radiance scaling; ours is glTF transmission 1 + volume with the same ior;
  - plane: `diffuse` with the reflectance; ours is glTF metallic 0, ior 1 (no specular layer: the
    exact Fresnel term vanishes at ior 1, so the glTF BSDF is Lambertian);
  - light: a one-sided `area` emitter (it emits along the face normal of its counter-clockwise
    winding, as glTF's front face) on a black `diffuse`.
Depth (ours D is Mitsuba's D + 1) and the block statistics of the output: mitsuba_blocks.py.

    python -m venv .venv && .venv/bin/pip install mitsuba numpy
    .venv/bin/python scripts/reference/glass_sphere_mitsuba.py --passes 32 --spp 64
"""

import math
import os

from mitsuba_blocks import main, perspective_sensor, write_ply

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
SCENE = os.path.join(ROOT, 'test', 'materials', 'fixtures', 'glass-sphere', 'scene.json')
OUT = os.path.join(ROOT, 'test', 'materials', 'fixtures', 'glass-sphere', 'mitsuba-reference.json')


def icosphere(radius, center, subdivisions):
    """test/helpers/meshes.ts icosphere: subdivided icosahedron, outward counter-clockwise winding."""
    t = (1 + math.sqrt(5)) / 2
    verts = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
             [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    verts = [[c / math.hypot(*v) for c in v] for v in verts]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6],
             [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10],
             [8, 6, 7], [9, 8, 1]]
    for _ in range(subdivisions):
        cache = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key in cache:
                return cache[key]
            m = [(verts[a][c] + verts[b][c]) / 2 for c in range(3)]
            length = math.hypot(*m)
            verts.append([c / length for c in m])
            cache[key] = len(verts) - 1
            return cache[key]

        out = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            out += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = out
    positions = [[v[i] * radius + center[i] for i in range(3)] for v in verts]
    return positions, verts, faces


def quad(corners):
    """Two counter-clockwise triangles over the corners in order (as the test builds them)."""
    return corners, [[0, 1, 2], [0, 2, 3]]


def plane_corners(h):
    # Counter-clockwise seen from above (+y): the front face points up.
    return [[-h, 0, h], [h, 0, h], [h, 0, -h], [-h, 0, -h]]


def scene_dict(spec, folder, max_depth, spp, seed):
    sphere = spec['sphere']
    positions, normals, faces = icosphere(sphere['radius'], sphere['center'], sphere['subdivisions'])
    write_ply(os.path.join(folder, 'sphere.ply'), positions, faces, normals)
    write_ply(os.path.join(folder, 'plane.ply'), *quad(plane_corners(spec['plane']['halfSize'])))
    write_ply(os.path.join(folder, 'light.ply'), *quad(spec['light']['corners']))
    cam = spec['camera']
    return {
        'type': 'scene',
        'integrator': {'type': 'path', 'max_depth': max_depth},
        'sensor': perspective_sensor(cam, spec['width'], spec['height'], spp, seed),
        'sphere': {'type': 'ply', 'filename': os.path.join(folder, 'sphere.ply'), 'face_normals': False,
                   'bsdf': {'type': 'dielectric', 'int_ior': sphere['ior'], 'ext_ior': 1.0}},
        'plane': {'type': 'ply', 'filename': os.path.join(folder, 'plane.ply'), 'face_normals': True,
                  'bsdf': {'type': 'diffuse', 'reflectance': {'type': 'rgb', 'value': spec['plane']['reflectance']}}},
        'light': {'type': 'ply', 'filename': os.path.join(folder, 'light.ply'), 'face_normals': True,
                  'bsdf': {'type': 'diffuse', 'reflectance': {'type': 'rgb', 'value': [0, 0, 0]}},
                  'emitter': {'type': 'area', 'radiance': {'type': 'rgb', 'value': spec['light']['radiance']}}},
    }


if __name__ == '__main__':
    main(__doc__, SCENE, OUT, 64, 'glass_sphere_mitsuba.py',
         lambda spec, max_depth, spp, seed, folder: scene_dict(spec, folder, max_depth, spp, seed))
