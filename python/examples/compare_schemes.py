"""Catmull-Clark, EG and guided subdivision on one gallery net, compared in Python.

Notebook style: each block below is a cell. It builds the three exact surfaces of the saddle
c-net of valence 5, prints their continuity checks, plots the Gauss-curvature range of every
ring (ring 0 is the cap) and saves highlight-line pictures of the three side by side.

    pip install ./python matplotlib
    python python/examples/compare_schemes.py [OUT_DIR]
"""

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import fairsub  # noqa: E402

out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "compare-out")
out.mkdir(parents=True, exist_ok=True)

# %% The net and the three surfaces
net = fairsub.read("gallery:cnet-5-saddle")
print(net, net.info()["extraordinary_vertices"])
schemes = ["catmull-clark", "eg", "guided-bi6"]
surfaces = {s: fairsub.surface(net, s, rings=6) for s in schemes}

# %% Continuity: the worst G^1 defect over all joins (radians)
for s, surf in surfaces.items():
    c = surf.check()["continuity"]
    print(f"{s:15s} {len(surf):4d} patches, G1 {c['all']['g1']:.2e} rad, C1 {c['all']['c1']:.2e}")

# %% Gauss curvature per ring (the cap is ring 0), from `check`
fig, ax = plt.subplots(figsize=(6, 4))
for s, surf in surfaces.items():
    rings = sorted(surf.check()["curvature"][0]["rings"], key=lambda r: r["ring"])
    k = [r["ring"] for r in rings]
    lo = [r["gauss_min"] for r in rings]
    hi = [r["gauss_max"] for r in rings]
    ax.fill_between(k, lo, hi, alpha=0.3, step="mid")
    ax.plot(k, hi, marker="o", label=s)
ax.set_xlabel("ring (0 = cap)")
ax.set_ylabel("Gauss curvature range")
ax.legend()
fig.tight_layout()
fig.savefig(out / "curvature-per-ring.png", dpi=100)

# %% Gauss curvature along a ray into the extraordinary vertex, by evaluation (Catmull-Clark)
cc = surfaces["catmull-clark"]
t = np.linspace(0.0, 1.0, 200)
e = cc.evaluate(np.zeros_like(t, dtype=np.int64), t, t)
fig, ax = plt.subplots(figsize=(6, 3))
ax.plot(t, e["gauss"])
ax.set_xlabel("u = v on face 0")
ax.set_ylabel("K (Catmull-Clark)")
fig.tight_layout()
fig.savefig(out / "gauss-along-diagonal.png", dpi=100)

# %% Highlight lines side by side
pics = [fairsub.render(surf, "highlight", size=(300, 300)) for surf in surfaces.values()]
fig, axes = plt.subplots(1, len(pics), figsize=(3 * len(pics), 3.2))
for a, s, p in zip(axes, schemes, pics):
    a.imshow(p)
    a.set_title(s)
    a.axis("off")
fig.tight_layout()
fig.savefig(out / "highlight-lines.png", dpi=100)
print("wrote", sorted(p.name for p in out.iterdir()))
