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
Depth: our `maxDepth` D counts scattering vertices (the camera hit is vertex 0, emission is
collected at vertices 0..D), Mitsuba's `max_depth` counts path segments (1: only emitters seen
directly), so ours D is Mitsuba's D + 1.

Output: per 8x8 block and channel, the mean of the pixel means and its standard error from P
independent passes (different sampler seeds): se_block = sqrt(sum_p var_p / P) / n_block, where var_p
is pixel p's variance across passes; plus the whole image's. CI reads the JSON and needs no Python.

    python -m venv .venv && .venv/bin/pip install mitsuba numpy
    .venv/bin/python scripts/reference/glass_sphere_mitsuba.py --passes 32 --spp 64
"""

import argparse
import json
import math
import os
import struct
import tempfile
import time

import mitsuba as mi
import numpy as np

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


def write_ply(path, positions, faces, normals=None):
    """Binary little-endian PLY (Mitsuba parses ASCII slowly)."""
    props = 'property float x\nproperty float y\nproperty float z\n'
    if normals is not None:
        props += 'property float nx\nproperty float ny\nproperty float nz\n'
    header = (f'ply\nformat binary_little_endian 1.0\nelement vertex {len(positions)}\n{props}'
              f'element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n')
    with open(path, 'wb') as f:
        f.write(header.encode('ascii'))
        for i, p in enumerate(positions):
            row = list(p) + (list(normals[i]) if normals is not None else [])
            f.write(struct.pack(f'<{len(row)}f', *row))
        for face in faces:
            f.write(struct.pack('<B3i', 3, *face))


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
        'sensor': {
            'type': 'perspective', 'fov': cam['fovYDegrees'], 'fov_axis': 'y',
            'to_world': mi.ScalarTransform4f().look_at(origin=cam['position'], target=cam['target'], up=cam['up']),
            'sampler': {'type': 'independent', 'sample_count': spp, 'seed': seed},
            'film': {'type': 'hdrfilm', 'width': spec['width'], 'height': spec['height'], 'rfilter': {'type': 'box'},
                     'pixel_format': 'rgb', 'component_format': 'float32'},
        },
        'sphere': {'type': 'ply', 'filename': os.path.join(folder, 'sphere.ply'), 'face_normals': False,
                   'bsdf': {'type': 'dielectric', 'int_ior': sphere['ior'], 'ext_ior': 1.0}},
        'plane': {'type': 'ply', 'filename': os.path.join(folder, 'plane.ply'), 'face_normals': True,
                  'bsdf': {'type': 'diffuse', 'reflectance': {'type': 'rgb', 'value': spec['plane']['reflectance']}}},
        'light': {'type': 'ply', 'filename': os.path.join(folder, 'light.ply'), 'face_normals': True,
                  'bsdf': {'type': 'diffuse', 'reflectance': {'type': 'rgb', 'value': [0, 0, 0]}},
                  'emitter': {'type': 'area', 'radiance': {'type': 'rgb', 'value': spec['light']['radiance']}}},
    }


def block_stats(passes, block):
    """passes: P x H x W x 3. Per block and channel: mean and standard error (pixels independent)."""
    p_count, h, w, _ = passes.shape
    mean = passes.mean(axis=0)
    var_of_mean = passes.var(axis=0, ddof=1) / p_count
    bh, bw = h // block, w // block
    n = block * block
    means = mean.reshape(bh, block, bw, block, 3).mean(axis=(1, 3))
    ses = np.sqrt(var_of_mean.reshape(bh, block, bw, block, 3).sum(axis=(1, 3))) / n
    image_mean = mean.reshape(-1, 3).mean(axis=0)
    image_se = np.sqrt(var_of_mean.reshape(-1, 3).sum(axis=0)) / (h * w)
    return means, ses, image_mean, image_se


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--passes', type=int, default=32)
    parser.add_argument('--spp', type=int, default=64, help='samples per pixel of each pass')
    parser.add_argument('--max-depth', type=int, default=None, help="Mitsuba's max_depth (default: the scene's maxDepth + 1)")
    parser.add_argument('--out', default=OUT)
    args = parser.parse_args()
    mi.set_variant('scalar_rgb')
    with open(SCENE) as f:
        spec = json.load(f)
    max_depth = args.max_depth if args.max_depth is not None else spec['maxDepth'] + 1
    started = time.time()
    images = []
    with tempfile.TemporaryDirectory() as folder:
        for k in range(args.passes):
            scene = mi.load_dict(scene_dict(spec, folder, max_depth, args.spp, seed=1000 + k))
            images.append(np.array(mi.render(scene, seed=1000 + k), dtype=np.float64)[:, :, :3])
            print(f'pass {k + 1}/{args.passes} ({time.time() - started:.0f} s)', flush=True)
    means, ses, image_mean, image_se = block_stats(np.stack(images), spec['block'])
    result = {
        'description': 'Mitsuba 3 reference of scene.json: per 8x8 block (row-major from the top-left, blocksX x blocksY) '
                       'and channel, the mean radiance and its standard error; generated by scripts/reference/glass_sphere_mitsuba.py.',
        'renderer': f'mitsuba {mi.__version__} {mi.variant()}, integrator path',
        'mitsubaMaxDepth': max_depth,
        'matchesMaxDepth': max_depth - 1,
        'passes': args.passes,
        'samplesPerPixel': args.passes * args.spp,
        'block': spec['block'],
        'blocksX': spec['width'] // spec['block'],
        'blocksY': spec['height'] // spec['block'],
        'imageMean': [round(float(v), 7) for v in image_mean],
        'imageStandardError': [float(f'{v:.4g}') for v in image_se],
        'mean': [[round(float(v), 7) for v in px] for px in means.reshape(-1, 3)],
        'standardError': [[float(f'{v:.4g}') for v in px] for px in ses.reshape(-1, 3)],
    }
    with open(args.out, 'w') as f:
        json.dump(result, f, separators=(',', ':'))
        f.write('\n')
    print(f'wrote {args.out} in {time.time() - started:.0f} s')


if __name__ == '__main__':
    main()
