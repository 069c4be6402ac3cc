#!/usr/bin/env python3
"""Writes docs' animated glTF: a hub cube turning (linear rotation) with a moon cube on a child
node (it rides along the hub's turn) that bobs up and down (cubic spline) and pulses (step).
Usage: docs/animated_scene.py OUT_FOLDER  -> OUT_FOLDER/orbit.gltf + orbit.bin"""
import json, math, struct, sys, os

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
corners = [((i >> 0) & 1, (i >> 1) & 1, (i >> 2) & 1) for i in range(8)]
pos = [c * 1.0 - 0.5 for p in corners for c in p]
faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
idx = [i for f in faces for i in (f[0], f[1], f[2], f[0], f[2], f[3])]
times = [0.0, 1.0, 2.0, 3.0, 4.0]
rot = []
for t in times:
    a = t / 4.0 * 2 * math.pi / 2  # a quaternion's half angle: one full turn over 4 s
    rot += [0.0, math.sin(a), 0.0, math.cos(a)]
bob = []  # cubic: in-tangent, value, out-tangent per key
for k, t in enumerate(times):
    y = 0.6 if k % 2 else -0.2
    bob += [0, 0, 0, 2.2, y, 0, 0, 0, 0]
pulse = []
for k in range(len(times)):
    s = 0.55 if k % 2 else 0.4
    pulse += [s, s, s]
blobs = [struct.pack('<%df' % len(pos), *pos), struct.pack('<%dH' % len(idx), *idx),
         struct.pack('<%df' % len(times), *times), struct.pack('<%df' % len(rot), *rot),
         struct.pack('<%df' % len(bob), *bob), struct.pack('<%df' % len(pulse), *pulse)]
data, views = b'', []
for b in blobs:
    views.append({'buffer': 0, 'byteOffset': len(data), 'byteLength': len(b)})
    data += b + b'\0' * (-len(b) % 4)
open(os.path.join(out, 'orbit.bin'), 'wb').write(data)
acc = [{'bufferView': 0, 'componentType': 5126, 'count': 8, 'type': 'VEC3',
        'min': [-0.5] * 3, 'max': [0.5] * 3},
       {'bufferView': 1, 'componentType': 5123, 'count': len(idx), 'type': 'SCALAR'},
       {'bufferView': 2, 'componentType': 5126, 'count': len(times), 'type': 'SCALAR',
        'min': [times[0]], 'max': [times[-1]]},
       {'bufferView': 3, 'componentType': 5126, 'count': len(times), 'type': 'VEC4'},
       {'bufferView': 4, 'componentType': 5126, 'count': 3 * len(times), 'type': 'VEC3'},
       {'bufferView': 5, 'componentType': 5126, 'count': len(times), 'type': 'VEC3'}]
gltf = {
    'asset': {'version': '2.0', 'generator': 'tessera docs/animated_scene.py'},
    'scene': 0, 'scenes': [{'nodes': [0]}],
    'nodes': [{'name': 'hub', 'mesh': 0, 'children': [1]},
              {'name': 'moon', 'mesh': 1, 'translation': [2.2, 0, 0], 'scale': [0.4] * 3}],
    'meshes': [{'primitives': [{'attributes': {'POSITION': 0}, 'indices': 1, 'material': 0}]},
               {'primitives': [{'attributes': {'POSITION': 0}, 'indices': 1, 'material': 1}]}],
    'materials': [{'pbrMetallicRoughness': {'baseColorFactor': [0.9, 0.45, 0.15, 1]}},
                  {'pbrMetallicRoughness': {'baseColorFactor': [0.3, 0.6, 0.95, 1]}}],
    'buffers': [{'uri': 'orbit.bin', 'byteLength': len(data)}],
    'bufferViews': views, 'accessors': acc,
    'animations': [{'name': 'orbit', 'samplers': [
        {'input': 2, 'output': 3, 'interpolation': 'LINEAR'},
        {'input': 2, 'output': 4, 'interpolation': 'CUBICSPLINE'},
        {'input': 2, 'output': 5, 'interpolation': 'STEP'}],
        'channels': [{'sampler': 0, 'target': {'node': 0, 'path': 'rotation'}},
                     {'sampler': 1, 'target': {'node': 1, 'path': 'translation'}},
                     {'sampler': 2, 'target': {'node': 1, 'path': 'scale'}}]}]}
json.dump(gltf, open(os.path.join(out, 'orbit.gltf'), 'w'), indent=1)
