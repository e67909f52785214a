"""Reads an OpenEXR file with the reference OpenEXR library (the `openexr` PyPI package, ASWF's
official bindings) and prints its header and every channel as JSON, so tests can compare what our
encoder wrote with what the reference decoder sees. Usage: python openexr-dump.py FILE.exr"""
import json
import sys

import OpenEXR


def plain(value):
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, (int, float, str, bool)) or value is None:
        return value
    return str(value)


with OpenEXR.File(sys.argv[1], separate_channels=True) as exr:
    header = exr.header()
    channels = {}
    for name, channel in exr.channels().items():
        pixels = channel.pixels
        channels[name] = {"type": str(pixels.dtype), "shape": list(pixels.shape), "values": [float(v) for v in pixels.astype("float64").ravel()]}
    print(json.dumps({"header": {k: plain(v) for k, v in header.items()}, "channels": channels}))
