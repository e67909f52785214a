"""Intel Open Image Denoise (the native library, CPU device, through the `pyoidn` binding) on the
images bench/oidn-native/dump.ts wrote: the flows our renderer runs, to check our WebGPU network
against Intel's per pixel, and OIDN's recommended flow for noisy auxiliary images (prefilter the
albedo and normal with the rt_alb / rt_nrm weights, then the clean-auxiliary rt_hdr_calb_cnrm
weights), base weights (quality 'balanced') and large (quality 'high').

    pip install pyoidn numpy    # pyoidn 2.5.1.0 bundles OIDN 2.5.1
    python bench/oidn-native/native.py
"""
import glob
import json
import os

import numpy as np
import pyoidn

DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'results', 'oidn-native')
device = pyoidn.Device()
device.commit()
QUALITY = {'high': pyoidn.OIDN_QUALITY_HIGH, 'balanced': pyoidn.OIDN_QUALITY_BALANCED}


def oidn(color=None, albedo=None, normal=None, clean_aux=False, quality='high'):
    """One RT filter run; colour is HDR; without colour it denoises the albedo or normal alone."""
    images = {'color': color, 'albedo': albedo, 'normal': normal}
    out = np.zeros_like(next(v for v in images.values() if v is not None))
    f = pyoidn.Filter(device, 'RT')
    for name, image in images.items():
        if image is not None:
            f.set_image(name, np.ascontiguousarray(image, dtype=np.float32), pyoidn.OIDN_FORMAT_FLOAT3)
    f.set_image('output', out, pyoidn.OIDN_FORMAT_FLOAT3)
    if color is not None:
        f.set_bool('hdr', True)
        f.set_bool('cleanAux', clean_aux)
    f.set_quality(QUALITY[quality])
    f.commit()
    f.execute()
    error = device.get_error()
    if error:
        raise RuntimeError(error)
    f.release()
    return out


for meta in sorted(glob.glob(os.path.join(DIR, '*.json'))):
    scene = os.path.basename(meta)[:-5]
    size = json.load(open(meta))
    w, h = size['width'], size['height']

    def load(name):
        return np.fromfile(os.path.join(DIR, name), dtype=np.float32).reshape(h, w, 4)[:, :, :3].copy()

    def save(name, rgb):
        rgba = np.ones((h, w, 4), np.float32)
        rgba[:, :, :3] = rgb
        rgba.tofile(os.path.join(DIR, name))

    for spp in (4, 16, 64):
        p = f'{scene}.{spp}'
        if not os.path.exists(os.path.join(DIR, f'{p}.color.f32')):
            continue
        color = np.maximum(load(f'{p}.color.f32'), 0)
        albedo = np.clip(load(f'{p}.albedo.f32'), 0, 1)
        normal = np.clip(load(f'{p}.normal.f32'), -1, 1)
        emission = np.maximum(load(f'{p}.emission.f32'), 0)
        reflected = np.maximum(color - emission, 0)
        native = {
            'intel_network': oidn(color, albedo, normal),
            'intel_exact': oidn(reflected, albedo, normal) + emission,
        }
        for quality, tag in (('balanced', 'base'), ('high', 'large')):
            pre_albedo = oidn(albedo=albedo, quality=quality)
            pre_normal = oidn(normal=normal, quality=quality)
            native[f'intel_cleanaux_{tag}_exact'] = oidn(reflected, pre_albedo, pre_normal, True, quality) + emission
            native[f'intel_cleanaux_{tag}_network'] = oidn(color, pre_albedo, pre_normal, True, quality)
        for name, image in native.items():
            save(f'{p}.{name}.f32', image)
        for ours, theirs in (('ours_exact', 'intel_exact'), ('ours_network', 'intel_network')):
            a = load(f'{p}.{ours}.f32')
            b = native[theirs]
            relative = np.abs(a - b) / (np.abs(b) + 0.01)
            print(f'{p}: {ours} vs {theirs}: relative difference worst {relative.max():.1e}, mean {relative.mean():.1e}')
