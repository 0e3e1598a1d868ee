"""Area, volume and centroid of an exact fairsub surface, integrated over its Bezier patches
(``fairsub.Surface.patches``) by Gauss-Legendre quadrature; the add-on's own computation until
fairsub's ``measure`` command lands with its Python function (then :func:`measure` becomes a
call of it).

For a patch ``x(u, v)`` with ``n = x_u x x_v`` (not normalised):

- area ``A = sum of the integrals of |n|``; the integrand is not a polynomial, so it is taken
  with a rule of ``2d + 4`` points per direction (``d`` the larger degree) and again with ``6``
  more; their difference is reported as the area's error estimate;
- volume ``V = 1/3 sum of the integrals of x . n`` and first moments
  ``M_i = 1/2 sum of the integrals of x_i^2 n_i`` (the divergence theorem): polynomials of
  degree at most ``4d - 1`` per direction, integrated exactly with ``2d`` points (up to
  rounding); centroid ``M / V``;
- the surface is closed when the flux of a constant field vanishes, ``|sum of the integrals of
  n| <= 1e-9 A``; volume and centroid are given only for a closed surface (on an open one they
  depend on the origin)."""

import numpy as np


def _bernstein(d, t):
    """Bernstein polynomials of degree ``d`` and their derivatives at ``t``: two (len(t), d+1)
    arrays."""
    from math import comb

    t = np.asarray(t, dtype=np.float64)[:, None]
    i = np.arange(d + 1)[None, :]
    c = np.array([comb(d, k) for k in range(d + 1)], dtype=np.float64)[None, :]
    b = c * t**i * (1 - t) ** (d - i)
    if d == 0:
        return b, np.zeros_like(b)
    lower = _bernstein(d - 1, t[:, 0])[0]
    pad = np.zeros((len(t), 1))
    db = d * (np.hstack([pad, lower]) - np.hstack([lower, pad]))
    return b, db


def _rule(k):
    """Gauss-Legendre nodes and weights on [0, 1] with ``k`` points."""
    x, w = np.polynomial.legendre.leggauss(k)
    return (x + 1) / 2, w / 2


def _integrals(cps, k):
    """For patches of one shape (p, du+1, dv+1, 3) and ``k`` points per direction: per patch
    the integrals of |n|, x . n, x_i^2 n_i (3) and n (3)."""
    du, dv = cps.shape[1] - 1, cps.shape[2] - 1
    t, w = _rule(k)
    bu, dbu = _bernstein(du, t)
    bv, dbv = _bernstein(dv, t)
    x = np.einsum("ai,pijc,bj->pabc", bu, cps, bv)
    xu = np.einsum("ai,pijc,bj->pabc", dbu, cps, bv)
    xv = np.einsum("ai,pijc,bj->pabc", bu, cps, dbv)
    n = np.cross(xu, xv)
    ww = w[:, None] * w[None, :]
    area = np.einsum("ab,pab->p", ww, np.linalg.norm(n, axis=-1))
    vol = np.einsum("ab,pab->p", ww, np.einsum("pabc,pabc->pab", x, n)) / 3
    mom = np.einsum("ab,pabc->pc", ww, x * x * n) / 2
    flux = np.einsum("ab,pabc->pc", ww, n)
    return area, vol, mom, flux


def measure(surface):
    """Area, volume and centroid of an exact surface: a dict with ``area``, ``area_error``
    (the estimate above), ``closed``, ``volume`` and ``centroid`` (None for an open surface)
    and ``patches``. Volume is signed: positive when the patch normals point outward."""
    shapes = {}
    for p in surface.patches:
        shapes.setdefault(p.shape, []).append(p)
    area = area_fine = vol = 0.0
    mom = np.zeros(3)
    flux = np.zeros(3)
    for shape, ps in shapes.items():
        cps = np.stack(ps)
        d = max(shape[0], shape[1]) - 1
        a1 = _integrals(cps, 2 * d + 4)[0].sum()
        a2, v, m, f = _integrals(cps, 2 * d + 10)
        area += a1
        area_fine += a2.sum()
        vol += v.sum()
        mom += m.sum(axis=0)
        flux += f.sum(axis=0)
    closed = bool(np.linalg.norm(flux) <= 1e-9 * max(area_fine, 1e-300))
    return {
        "area": float(area_fine),
        "area_error": float(abs(area_fine - area)),
        "closed": closed,
        "volume": float(vol) if closed else None,
        "centroid": [float(c) for c in mom / vol] if closed and vol != 0 else None,
        "patches": len(surface.patches),
    }
