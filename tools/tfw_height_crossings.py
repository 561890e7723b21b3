#!/usr/bin/env python3
"""tfw_height_crossings.py — the wrinkle height of a bin/wrinkle-tfw run along rest-domain lines, one
per panel, read straight from its outputs (a check of the scene probes that shares no code with them).

    tools/tfw_height_crossings.py OUTDIR PANEL U0 V0 U1 V1 [PANEL U0 V0 U1 V1 ...]

Samples the per-vertex `height` (a cos phase: the wrinkle height along the smooth base's normal) of
OUTDIR/wrinkled.ply at 1024 points of the segment (U0, V0)-(U1, V1) [m] in the rest chart of the
faces of group PANEL of OUTDIR/wrinkled.obj (per-corner vt on a welded sewn base; a point is taken in
the face where it is deepest inside), and prints the zero crossings (rest arc length from the start
[mm]), their spacings, and the waves = crossings / 2. A crossing counts only when the height has
reached ±10 % of the line's largest |height| since the last one (a Schmitt trigger: a wrinkle-free
stretch, height ≈ 0, would otherwise give crossings of round-off). Used for docs/notes-tfw-dress.md.
"""
import math
import struct
import sys


def read_obj(path):
    vt, faces, group = [], [], None
    for line in open(path):
        if line.startswith('vt '):
            vt.append(tuple(map(float, line.split()[1:3])))
        elif line.startswith('g '):
            group = line[2:].strip()
        elif line.startswith('f '):
            c = [x.split('/') for x in line.split()[1:]]
            faces.append((group, [int(x[0]) - 1 for x in c], [vt[int(x[1]) - 1] for x in c]))
    return faces


def read_height(path):
    data = open(path, 'rb').read()
    hdr, body = data.split(b'end_header\n', 1)
    lines = hdr.split(b'\n')
    props = [l.split()[-1].decode() for l in lines if l.startswith(b'property float')]
    nv = int([l for l in lines if l.startswith(b'element vertex')][0].split()[-1])
    k, n = props.index('height'), len(props)
    if b'binary_little_endian' in hdr:
        return [struct.unpack_from('<f', body, 4 * (i * n + k))[0] for i in range(nv)]
    return [float(l.split()[k]) for l in body.decode().split('\n')[:nv]]


def sample(faces, hgt, panel, a, b, n):
    own = [(v, t) for g, v, t in faces if g == panel]
    out = []
    for i in range(n):
        p = (a[0] + (b[0] - a[0]) * i / (n - 1), a[1] + (b[1] - a[1]) * i / (n - 1))
        best = None
        for v, t in own:
            e1 = (t[1][0] - t[0][0], t[1][1] - t[0][1])
            e2 = (t[2][0] - t[0][0], t[2][1] - t[0][1])
            q = (p[0] - t[0][0], p[1] - t[0][1])
            det = e1[0] * e2[1] - e1[1] * e2[0]
            if det == 0.0:
                continue
            b1 = (q[0] * e2[1] - q[1] * e2[0]) / det
            b2 = (e1[0] * q[1] - e1[1] * q[0]) / det
            m = min(1.0 - b1 - b2, b1, b2)
            if m >= -1e-9 and (best is None or m > best[0]):
                best = (m, (1.0 - b1 - b2) * hgt[v[0]] + b1 * hgt[v[1]] + b2 * hgt[v[2]])
        out.append(best[1] if best else None)
    return out, math.hypot(b[0] - a[0], b[1] - a[1]) / (n - 1)


def main(argv):
    if len(argv) < 7 or (len(argv) - 2) % 5:
        sys.stderr.write(__doc__)
        return 2
    faces = read_obj(argv[1] + '/wrinkled.obj')
    hgt = read_height(argv[1] + '/wrinkled.ply')
    for k in range(2, len(argv), 5):
        panel, u0, v0, u1, v1 = argv[k], *map(float, argv[k + 1:k + 5])
        s, ds = sample(faces, hgt, panel, (u0, v0), (u1, v1), 1024)
        inside = [x for x in s if x is not None]
        thr = 0.1 * max(abs(x) for x in inside)
        z, side, last = [], 0, None  # side: sign of the last excursion beyond thr; last: its last zero
        for i in range(len(s) - 1):
            if s[i] is None or s[i + 1] is None:
                continue
            if s[i] * s[i + 1] < 0:
                last = 1e3 * ds * (i + s[i] / (s[i] - s[i + 1]))
            if abs(s[i + 1]) >= thr:
                sg = 1 if s[i + 1] > 0 else -1
                if side and sg != side and last is not None:
                    z.append(last)
                side = sg
        print('%s: %d of %d samples inside, peak-to-peak %.1f mm, %d zero crossings (%.1f waves)'
              % (panel, len(inside), len(s), 1e3 * (max(inside) - min(inside)), len(z), len(z) / 2))
        print('  crossings [mm]:', ' '.join('%.0f' % x for x in z))
        print('  spacings  [mm]:', ' '.join('%.0f' % (z[i + 1] - z[i]) for i in range(len(z) - 1)))
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
