# The fastest particles of a weir PLY frame: where they are, how fast, and their density.
import sys, numpy as np
def read(path):
    with open(path, 'rb') as f:
        names = []; n = 0
        while True:
            line = f.readline().decode().strip()
            if line.startswith('element vertex'): n = int(line.split()[-1])
            if line.startswith('property'): names.append(line.split()[-1])
            if line == 'end_header': break
        data = np.frombuffer(f.read(n * 4 * len(names)), dtype='<f4').reshape(n, len(names))
    return {k: data[:, i] for i, k in enumerate(names)}
for path in sys.argv[1:]:
    d = read(path)
    v = np.sqrt(d['vx']**2 + d['vy']**2 + d['vz']**2)
    order = np.argsort(v)[::-1]
    print(path, 'n', len(v), 'speed p50 %.2f p99 %.2f p99.99 %.2f max %.2f' % tuple(np.percentile(v, [50, 99, 99.99]).tolist() + [v.max()]))
    print('  over 2x p99.99:', int((v > 2 * np.percentile(v, 99.99)).sum()), ' pressure max %.0f' % d['pressure'].max(), ' density min %.1f max %.1f' % (d['density'].min(), d['density'].max()))
    for i in order[:8]:
        print('   x %.3f y %.3f z %.3f  v (%.2f %.2f %.2f) rho %.1f p %.0f' % (d['x'][i], d['y'][i], d['z'][i], d['vx'][i], d['vy'][i], d['vz'][i], d['density'][i], d['pressure'][i]))
