# Water-surface height at probes along a flume, per frame, from binary PLY frames (x, y, z and
# 5 more float32 columns, then an int32 id: 36 bytes a row).
import json, sys
import numpy as np
out = sys.argv[1]
d = json.load(open(out + '/frames.json'))
probes = [0.1, 0.5, 1.0, 1.55, 2.5]
half = float(sys.argv[2]) if len(sys.argv) > 2 else 0.005
rows = []
for f in d['frames']:
    raw = open(out + '/' + f['file'], 'rb').read()
    body = raw[raw.index(b'end_header\n') + len(b'end_header\n'):]
    dt = np.dtype([('x', '<f4'), ('y', '<f4'), ('z', '<f4'), ('r', '<f4', 5), ('id', '<i4')])
    a = np.frombuffer(body, dtype=dt)
    row = []
    for p in probes:
        sel = np.abs(a['x'] - p) < half
        row.append(float(a['y'][sel].max()) if sel.any() else -1)
    rows.append((f['time'], row))
    print(round(f['time'], 2), ' '.join(f'{v:.4f}' for v in row))
for p_i, p in enumerate(probes[:4]):
    tops = [r[p_i] for t, r in rows if t >= 2.5]
    print(f'H@{p} = {max(tops) - min(tops):.4f} m (t >= 2.5 s)')
