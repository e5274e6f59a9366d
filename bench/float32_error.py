"""The change float32 storage makes to a table's lookups: random points, float64 against float32,
multilinear (n points) and cubic (n/10), the force differences in % of the local wheel load (the
fz output there).

    build/python/python3 bench/float32_error.py TABLE.h5 [n = 1000000]
"""
import sys, numpy as np, wrc
path = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 1000000
a = wrc.Table(path); b = wrc.Table(path); b.storage = 'float32'
axes = [np.asarray(a.axes[name]) for name in a.axis_names]
rng = np.random.default_rng(1)
pts = np.column_stack([rng.uniform(x[0], x[-1], n) for x in axes])
names = a.output_names
for mode in ('linear', 'cubic'):
    m = n if mode == 'linear' else n // 10
    a.interpolation = mode; b.interpolation = mode
    ya = np.asarray(a.eval(pts[:m])); yb = np.asarray(b.eval(pts[:m]))
    load = np.abs(ya[:, names.index('fz')])
    for out in ('fx', 'fy', 'fz'):
        k = names.index(out)
        rel = np.abs(yb[:, k] - ya[:, k]) / load * 100
        print(f'{mode} {out}: max {rel.max():.2e} % of the load, p95 {np.percentile(rel, 95):.2e} %  ({m} points)')
    k = names.index('z') if 'z' in names else None
    if k is not None:
        print(f'{mode} z: max {np.abs(yb[:, k]-ya[:, k]).max():.2e} mm')
