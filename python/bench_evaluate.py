"""Python `Surface.evaluate` against the Rust evaluation it wraps, on 10^6 points.

    python python/bench_evaluate.py [POINTS]

Builds the Catmull-Clark surface (2 rings) of a gallery net refined to about 12k quads,
evaluates POINTS random parameters (default 10^6) through the Python API and through the
Rust call alone (`Surface::evaluate_into` a buffer allocated before the clock starts,
timed inside the extension), best of 3 each, and prints the
ratio (the acceptance bound of issue 18 is 1.5).
"""

import sys
import time

import numpy as np

import fairsub

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
net = fairsub.subdivide("gallery:torus-evs", "catmull-clark", levels=3)
s = fairsub.surface(fairsub.Net(net.vertices, net.faces), "catmull-clark", rings=2)
rng = np.random.default_rng(1)
face = rng.integers(0, net.num_faces, n)
u, v = rng.random(n), rng.random(n)
s.evaluate(face[:10], u[:10], v[:10])  # builds the lookup once
py, rust = [], []
for _ in range(3):
    t = time.perf_counter()
    s.evaluate(face, u, v)
    py.append(time.perf_counter() - t)
    rust.append(s._rust_evaluate_seconds(face, u, v))
print(f"{n} points on {net.num_faces} faces ({len(s)} patches): python {min(py):.3f} s, "
      f"rust {min(rust):.3f} s, ratio {min(py) / min(rust):.2f}")
