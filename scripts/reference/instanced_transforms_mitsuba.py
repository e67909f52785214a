"""Independent reference for test/accel/instanced-transforms-reference.test.ts, rendered with Mitsuba 3.

The scene is test/accel/fixtures/instanced-transforms/: scene.glb is what our renderer loads (shared
meshes placed by reused nodes and EXT_mesh_gpu_instancing, with rotations, non-uniform and mirroring
scales); scripts/reference/instanced-transforms-scene.ts wrote it together with its flattened
world-space triangles (mitsuba/*.ply, one per material: its own TRS composition, normals by the
inverse transpose, winding reversed under a negative determinant) and scene.json (image, camera,
environment, light, materials). Mitsuba renders the PLY files, none of the glTF:
  - every object material and the ground: `diffuse` with the reflectance; ours is glTF metallic 0,
    roughness 1, ior 1 (Lambertian). The icosphere PLY carries vertex normals (`face_normals`
    false), the L prisms, the ground and the light are flat;
  - light: a one-sided `area` emitter (it emits along the face normal of its counter-clockwise
    winding, as glTF's front face) on a black `diffuse`; it is out of view;
  - environment: a `constant` emitter (ours: `environment: { color }`); the ground fills the view.
Depth (ours D is Mitsuba's D + 1) and the block statistics of the output: mitsuba_blocks.py.

    node scripts/reference/instanced-transforms-scene.ts
    python -m venv .venv && .venv/bin/pip install mitsuba numpy
    .venv/bin/python scripts/reference/instanced_transforms_mitsuba.py --passes 64 --spp 256
"""

import os

from mitsuba_blocks import main, perspective_sensor

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
FOLDER = os.path.join(ROOT, 'test', 'accel', 'fixtures', 'instanced-transforms')
OUT = os.path.join(FOLDER, 'mitsuba-reference.json')


def rgb(value):
    return {'type': 'rgb', 'value': value}


def scene_dict(spec, max_depth, spp, seed):
    scene = {
        'type': 'scene',
        'integrator': {'type': 'path', 'max_depth': max_depth},
        'sensor': perspective_sensor(spec['camera'], spec['width'], spec['height'], spp, seed),
        'environment': {'type': 'constant', 'radiance': rgb(spec['environment'])},
        'light': {'type': 'ply', 'filename': os.path.join(FOLDER, spec['light']['ply']), 'face_normals': True,
                  'bsdf': {'type': 'diffuse', 'reflectance': rgb([0, 0, 0])},
                  'emitter': {'type': 'area', 'radiance': rgb(spec['light']['radiance'])}},
    }
    for i, shape in enumerate(spec['shapes']):
        scene[f'shape_{i}_{shape["material"]}'] = {
            'type': 'ply', 'filename': os.path.join(FOLDER, shape['ply']), 'face_normals': not shape['smooth'],
            'bsdf': {'type': 'diffuse', 'reflectance': rgb(spec['materials'][shape['material']])},
        }
    return scene


if __name__ == '__main__':
    main(__doc__, os.path.join(FOLDER, 'scene.json'), OUT, 128, 'instanced_transforms_mitsuba.py',
         lambda spec, max_depth, spp, seed, _folder: scene_dict(spec, max_depth, spp, seed))
