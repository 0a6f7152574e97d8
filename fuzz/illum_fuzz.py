#!/usr/bin/env python3
"""Black-box fuzzing of the `illum` program (fuzz/README.md, "illum_fuzz.py").

    fuzz/illum_fuzz.py KIND ILLUM [--runs N] [--seed S] [--out DIR] [--ext .ply]

KIND is one of
  json     JSON scene files of the repository with mutated values, rendered by
           a random method;
  mesh     mesh files (McGuire's Cornell box OBJ+MTL, a Stanford bunny as ASCII
           and binary PLY, a glTF, a GLB, an STL) with mutated bytes, loaded by
           `illum info` or rendered tiny; --ext keeps only one format;
  texture  textures and environment maps (PNG, EXR half and float, HDR, PFM,
           written by ILLUM itself) with mutated bytes, in a small JSON scene;
  options  random options of every method's --help with odd values.

Each case must end with exit code 0, 1 or 2, no sanitizer report, an output
image after a success and none after a failure, within the time limit.
Cases that break this are copied to DIR with their stderr in DIR/log.txt.
Build ILLUM with -DIL_SANITIZE=ON to catch memory errors as well.
"""
import argparse
import base64
import json
import os
import random
import re
import shutil
import struct
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(ROOT), 'shared', 'scenes')
METHODS = ['pt', 'radiosity', 'hr', 'photon', 'sppm', 'ibl', 'linespace', 'rsm']
SMALL = ['--width', '12', '--height', '10', '--spp', '1']
BYTE_TOKENS = [b'nan', b'1e30', b'-1', b'4294967295', b'99999999', b'0', b'-2147483648', b'inf', b'\0',
               b'"', b'{', b'}', b'[', b']', b',', b'\n', b'255', b'65535', b'\xff\xff\xff\xff',
               b'\x00\x00\x80\x7f', b'-Y 99999 +X 99999\n', b'dataWindow\0box2i\0']
NASTY_VALUES = [0, -1, 1, 2, 1e30, -1e30, 1e-30, 3.4e38, 1e300, 4294967296, -2147483649, 0.5, 1e15, 1e16,
                179.999, 180, 65536, 1e-45, 'x', '', None, True, [], {}, [0], [1, 2], [0, 0, 0],
                [1e30, 1e30, 1e30], [-1, -1, -1], [1, 0, 0, 90]]
ODD_OPTION_VALUES = ['0', '1', '-1', '2', '8', '0.5', '0.1', '16', '64', '1e30', '-1e30', 'nan', 'inf',
                     '1e-30', '4294967296', '18446744073709551616', '', 'on', 'off', 'x', '0,0,0',
                     '1,2,3', '1e30,0,0', 'nan,0,0', '1,2', '65536', '0x10', '.5', '3x', '100000']


def mutate_bytes(data, rng):
    b = bytearray(data)
    for _ in range(rng.randint(1, 6)):
        r, p = rng.random(), rng.randrange(max(1, len(b)))
        if r < 0.3 and b:
            b[p] = rng.randrange(256)
        elif r < 0.5:
            del b[p:p + rng.randint(1, 64)]
        elif r < 0.65:
            q = rng.randrange(max(1, len(b)))
            b[p:p] = b[q:q + rng.randint(1, 64)]
        elif r < 0.9:
            b[p:p + rng.randint(0, 8)] = rng.choice(BYTE_TOKENS)
        else:
            del b[p:]
    return bytes(b)


def json_paths(o, path=()):
    yield path
    items = o.items() if isinstance(o, dict) else enumerate(o) if isinstance(o, list) else []
    for k, v in items:
        yield from json_paths(v, path + (k,))


def mutate_json(doc, rng):
    for _ in range(rng.randint(1, 3)):
        path = rng.choice([p for p in json_paths(doc) if p])
        parent = doc
        for k in path[:-1]:
            parent = parent[k]
        cur = parent[path[-1]]
        if isinstance(cur, (int, float)) and not isinstance(cur, bool) and rng.random() < 0.6:
            parent[path[-1]] = cur * rng.choice([0, -1, 0.5, 2, 10, 1e3, 1e6, 1e-3]) + rng.choice([0, 0.1, 1])
        elif rng.random() < 0.1:
            del parent[path[-1]]
        else:
            parent[path[-1]] = rng.choice(NASTY_VALUES)


def bunny_plys():
    text = open(os.path.join(SHARED, 'stanford-bunny', 'bun_zipper_res4.ply'), 'rb').read()
    lines = text.decode().split('\n')
    end = lines.index('end_header')
    nv = int(next(l for l in lines if l.startswith('element vertex')).split()[2])
    nf = int(next(l for l in lines if l.startswith('element face')).split()[2])
    body = b''.join(struct.pack('<3f', *map(float, l.split()[:3])) for l in lines[end + 1:end + 1 + nv])
    body += b''.join(struct.pack('<B3i', 3, *map(int, l.split()[1:4]))
                     for l in lines[end + 1 + nv:end + 1 + nv + nf])
    header = ('ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n'
              'property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n' % (nv, nf))
    return text, header.encode() + body


def gltf_pair():
    buf = struct.pack('<12f', -1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1) + struct.pack('<6H', 0, 2, 1, 0, 3, 2)
    g = {'asset': {'version': '2.0'}, 'scene': 0, 'scenes': [{'nodes': [0, 1]}],
         'nodes': [{'mesh': 0}, {'extensions': {'KHR_lights_punctual': {'light': 0}}, 'translation': [0, 1, 0]}],
         'extensionsUsed': ['KHR_lights_punctual'],
         'extensions': {'KHR_lights_punctual': {'lights': [{'type': 'point', 'intensity': 10}]}},
         'meshes': [{'primitives': [{'attributes': {'POSITION': 0}, 'indices': 1, 'material': 0}]}],
         'materials': [{'pbrMetallicRoughness': {'baseColorFactor': [0.8, 0.8, 0.8, 1]}}],
         'bufferViews': [{'buffer': 0, 'byteLength': 48}, {'buffer': 0, 'byteOffset': 48, 'byteLength': 12}],
         'accessors': [{'bufferView': 0, 'componentType': 5126, 'count': 4, 'type': 'VEC3',
                        'min': [-1, 0, -1], 'max': [1, 0, 1]},
                       {'bufferView': 1, 'componentType': 5123, 'count': 6, 'type': 'SCALAR'}]}
    embedded = dict(g, buffers=[{'byteLength': len(buf),
                                 'uri': 'data:application/octet-stream;base64,' + base64.b64encode(buf).decode()}])
    js = json.dumps(dict(g, buffers=[{'byteLength': len(buf)}])).encode()
    js += b' ' * (-len(js) % 4)
    bb = buf + b'\0' * (-len(buf) % 4)
    glb = (struct.pack('<III', 0x46546C67, 2, 28 + len(js) + len(bb)) + struct.pack('<II', len(js), 0x4E4F534A) + js
           + struct.pack('<II', len(bb), 0x004E4942) + bb)
    return json.dumps(embedded).encode(), glb


# Leaks inside assimp are not illum's (fuzz/lsan.supp says which and why).
SAN_ENV = dict(os.environ)
SAN_ENV['LSAN_OPTIONS'] = ':'.join(filter(None, [os.environ.get('LSAN_OPTIONS', ''),
                                                'suppressions=' + os.path.join(ROOT, 'fuzz', 'lsan.supp')]))


def run_case(cmd, renders, out, timeout):
    """Runs one case; its exit code, stderr, and whether it broke the rules."""
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, errors='replace', timeout=timeout, env=SAN_ENV)
        rc, err = r.returncode, r.stderr
    except subprocess.TimeoutExpired:
        rc, err = 'timeout', ''
    bad = (rc not in (0, 1, 2) or 'runtime error' in err or 'AddressSanitizer' in err
           or (renders and (rc == 0) != os.path.exists(out)))
    return rc, err, bad


def cases_json(args, rng, work):
    seeds = [os.path.join(ROOT, 'scenes', f) for f in ('studio.json', 'cornell-glass.json')]
    seeds.append(os.path.join(ROOT, 'bench', 'scenes', 'cornell-spot-rsm.json'))
    src = rng.choice(seeds)
    for f in os.listdir(os.path.dirname(src)):
        if not f.endswith('.json'):
            os.symlink(os.path.join(os.path.dirname(src), f), os.path.join(work, f))
    doc = json.load(open(src))
    mutate_json(doc, rng)
    scene = os.path.join(work, 'scene.json')
    json.dump(doc, open(scene, 'w'))
    method = rng.choice(METHODS)
    extra = {'photon': ['--photons', '2000'], 'sppm': ['--photons', '2000'],
             'linespace': ['--inject-rays', '2000', '--grid', '4']}.get(method, [])
    return [args.illum, 'render', scene, '--method', method] + SMALL + extra, True, [scene]


def cases_mesh(args, rng, work, seeds, mtl):
    name = rng.choice(sorted(n for n in seeds if n.endswith(args.ext or '')))
    path = os.path.join(work, name)
    open(path, 'wb').write(mutate_bytes(seeds[name], rng))
    if name.endswith('.obj'):
        open(os.path.join(work, 'CornellBox-Original.mtl'), 'wb').write(
            mutate_bytes(mtl, rng) if rng.random() < 0.5 else mtl)
    if rng.random() < 0.3:
        return [args.illum, 'render', path] + SMALL, True, [path]
    return [args.illum, 'info', path], False, [path]


def cases_texture(args, rng, work, images):
    name = rng.choice(sorted(images))
    open(os.path.join(work, name), 'wb').write(mutate_bytes(images[name], rng))
    scene = {'materials': {'m': {'diffuse': 0.8}}, 'meshes': [{'shape': 'quad', 'size': [2, 2], 'material': 'm'}],
             'camera': {'position': [0, 2, 2], 'target': [0, 0, 0], 'fov': 50}}
    env = rng.random() < 0.5
    if env:
        scene['environment'] = {'map': name}
    else:
        scene['materials']['m']['texture'] = name
        scene['lights'] = [{'type': 'point', 'position': [0, 1, 0], 'intensity': 1}]
    path = os.path.join(work, 'scene.json')
    json.dump(scene, open(path, 'w'))
    method = rng.choice(['pt', 'ibl']) if env else 'pt'
    return [args.illum, 'render', path, '--method', method] + SMALL, True, [path, os.path.join(work, name)]


def cases_options(args, rng, work, options):
    method = rng.choice(METHODS)
    cmd = [args.illum, 'render', rng.choice(['cornell', 'simple-room', os.path.join(ROOT, 'scenes', 'studio.json')]),
           '--method', method] + SMALL
    for _ in range(rng.choice([1, 1, 2, 3])):
        cmd += [rng.choice(options[method]), rng.choice(ODD_OPTION_VALUES)]
    if method in ('photon', 'sppm') and '--photons' not in cmd:
        cmd += ['--photons', '3000']
    if method == 'linespace' and '--inject-rays' not in cmd:
        cmd += ['--inject-rays', '3000']
    return cmd, True, []


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('kind', choices=['json', 'mesh', 'texture', 'options'])
    ap.add_argument('illum')
    ap.add_argument('--runs', type=int, default=200)
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--out', default='fuzz-out')
    ap.add_argument('--ext', help='mesh: only seeds with this extension (e.g. .ply)')
    ap.add_argument('--timeout', type=float, default=120)
    args = ap.parse_args()
    args.illum = os.path.abspath(args.illum)
    rng = random.Random(args.seed)
    os.makedirs(args.out, exist_ok=True)
    work = os.path.join(args.out, 'work')

    extra = ()
    if args.kind == 'mesh':
        box = os.path.join(SHARED, 'cornell-box-mcguire', 'CornellBox-Original')
        ascii_ply, binary_ply = bunny_plys()
        gltf, glb = gltf_pair()
        stl = b'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n'
        extra = ({'box.obj': open(box + '.obj', 'rb').read(), 'a.ply': ascii_ply, 'b.ply': binary_ply,
                  'q.gltf': gltf, 'q.glb': glb, 't.stl': stl}, open(box + '.mtl', 'rb').read())
    elif args.kind == 'texture':
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        outs = [os.path.join(work, n) for n in ('t.png', 't.exr', 't.hdr', 't.pfm')]
        subprocess.run([args.illum, 'render', 'cornell', '--width', '16', '--height', '12', '--spp', '4', '-q']
                       + sum([['-o', o] for o in outs], []), check=True)
        subprocess.run([args.illum, 'render', 'cornell', '--width', '16', '--height', '12', '--spp', '4', '-q',
                        '--exr-float', '-o', os.path.join(work, 'tf.exr')], check=True)
        extra = ({os.path.basename(o): open(o, 'rb').read() for o in outs + [os.path.join(work, 'tf.exr')]},)
    elif args.kind == 'options':
        skip = {'--help', '--threads', '--time', '--write-every', '--checkpoint-every', '--device', '--width',
                '--height', '--spp', '--stats', '--output', '--camera-file', '--method'}
        options = {}
        for m in METHODS:
            text = subprocess.run([args.illum, 'render', '--method', m, '--help'], capture_output=True,
                                  text=True).stdout
            options[m] = sorted(set(re.findall(r'^\s+(--[a-z][a-z0-9-]*)', text, re.M)) - skip)
        extra = (options,)
    make = {'json': cases_json, 'mesh': cases_mesh, 'texture': cases_texture, 'options': cases_options}[args.kind]

    found, codes = 0, {}
    with open(os.path.join(args.out, 'log.txt'), 'a') as log:
        for i in range(args.runs):
            shutil.rmtree(work, ignore_errors=True)
            os.makedirs(work)
            cmd, renders, keep = make(args, rng, work, *extra)
            if renders:
                cmd += ['-q', '-o', os.path.join(work, 'o.pfm')]
            rc, err, bad = run_case(cmd, renders, os.path.join(work, 'o.pfm'), args.timeout)
            codes[rc] = codes.get(rc, 0) + 1
            if bad:
                found += 1
                for k in keep:
                    shutil.copy(k, os.path.join(args.out, 'case%d-%s' % (i, os.path.basename(k))))
                log.write('case %d: exit %s\n%s\n%s\n---\n' % (i, rc, ' '.join(cmd), err[-3000:]))
                log.flush()
    print('%s: %d runs, %d found (log: %s), exit codes %s' % (args.kind, args.runs, found,
                                                            os.path.join(args.out, 'log.txt'), codes))
    return 1 if found else 0


if __name__ == '__main__':
    raise SystemExit(main())
