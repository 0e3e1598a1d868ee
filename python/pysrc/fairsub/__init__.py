"""fairsub: subdivision surfaces of high shape quality, from Python.

The schemes of the five fairsub papers (point-augmented, polar and ternary bi-2, Evolving Guide,
QAS+, guided and non-box subdivision) beside Catmull-Clark, Doo-Sabin and Loop: refined nets,
exact Bezier patch complexes, evaluation, continuity checks, spectra and pictures, with numpy
arrays in and out.

Every call goes through the Rust library's API (``fairsub::refine``, ``surface``, ``analyze``,
...), which runs the same code as the ``fairsub`` command line: keyword options are its typed
``Options`` and the command line's options of the same name (``split_ratio=0.3`` is
``--split-ratio 0.3``, ``smooth_triangles=True`` is ``--smooth-triangles``), with the same
defaults, limits and error messages (raised as ``ValueError``).

Example::

    import fairsub
    net = fairsub.read("gallery:cnet-5-saddle")
    s = fairsub.surface(net, "eg", rings=4)
    print(len(s.patches), s.check()["continuity"]["all"]["g1"])
    img = fairsub.render(s, "highlight", size=(400, 400))   # (400, 400, 3) uint8
    table = s.stencils()                                    # patch stencil table, built once
    moved = table.apply(net.vertices + 0.01)                # patches of moved control points
"""

import json as _json

import numpy as _np

from . import _fairsub
from ._fairsub import Net, PatchTable, Stencils, Surface

__all__ = [
    "Net",
    "Surface",
    "Stencils",
    "PatchTable",
    "read",
    "schemes",
    "subdivide",
    "surface",
    "analyze",
    "render",
    "render_defaults",
    "level_stencils",
    "info",
    "scheme_options",
    "curvature_colours",
]
__version__ = _fairsub.__version__


def read(path, tolerant=False):
    """Reads a control net: an ``.obj``, ``.off`` or ``.ply`` file, or ``gallery:NAME``.

    OBJ tag lines (creases, corners, holes, OpenSubdiv options), texture coordinates and FCVs
    are kept with the file: commands re-read the file the way the command line reads it for
    their scheme. ``tolerant=True`` accepts every net OpenSubdiv accepts (non-manifold edges
    and vertices, faces that repeat a vertex) for the arrays of the returned net.

    >>> net = read("gallery:cube")
    >>> net.num_vertices, net.num_faces
    (8, 6)
    """
    return _fairsub.read(str(path), tolerant)


def _net(net):
    if isinstance(net, Net):
        return net
    if isinstance(net, str):
        return read(net)
    raise ValueError("expected a fairsub.Net or a file / gallery name")


def info(net):
    """``fairsub info --json`` of a net, as a dict (counts, valences, extraordinary elements,
    problems, which rules each scheme uses per valence)."""
    return _json.loads(_net(net).info_json())


Net.info = lambda self: _json.loads(self.info_json())
Net.info.__doc__ = "``fairsub info --json`` of the net, as a dict."


def schemes():
    """The catalogue (``fairsub schemes --json``): a list of dicts, one per scheme."""
    return _json.loads(_fairsub.schemes_json())


def scheme_options(scheme):
    """The options ``scheme`` takes (beside ``levels`` / ``rings``), as the command line
    defines them: a list of dicts ``name`` (``"split-ratio"``; as a keyword ``split_ratio``),
    ``help``, ``choices`` (the values, when they are a fixed set), ``file`` (it names a file),
    ``flag`` (a switch without value) and ``repeated`` (it may be given several times).

    >>> [o["name"] for o in scheme_options("catmull-clark")][:3]
    ['boundary', 'crease-method', 'fvar']
    """
    return _json.loads(_fairsub.scheme_options_json(scheme))


def curvature_colours(values, range=None, percentile=0.98):
    """Curvature values (a 1-D array, e.g. ``Surface.tessellation(n)["mean"]``) as the colours
    ``render --mode mean|gauss`` paints them: blue negative, white 0, red positive, over the
    symmetric range ``[-range, range]`` (given, or the ``percentile`` of ``|value|`` rounded up
    to two significant digits). Returns ``(colours (n, 3) in 0..1, range)``."""
    v = _np.ascontiguousarray(values, dtype=_np.float64).reshape(-1)
    return _fairsub.curvature_colours(v, range, percentile)


def subdivide(net, scheme, levels=1, limit=False, **options):
    """Refines ``net`` ``levels`` times with ``scheme`` (``fairsub subdivide --levels``).

    Returns the refined Net; with ``limit=True`` its points are at their limit positions (for
    ``nonbox``: ``(net, normals)``, the limit mesh with its exact normals). Options are the
    command line's (``boundary="edge-only"``, ``crease_method="chaikin"``, ``fvar=...``,
    ``creases=FILE``, ``fcv_scale=S``, ``split_ratio=E``, ``rules="derived"``, ...).

    >>> fine = subdivide(read("gallery:cube"), "catmull-clark", levels=2)
    >>> fine.num_faces
    96
    """
    return _fairsub.subdivide(_net(net), scheme, levels=levels, limit=limit, options=options)


def surface(net, scheme, rings=6, fill=True, **options):
    """The exact patch complex of ``net`` under ``scheme`` (``fairsub subdivide --rings``):
    a Surface with ``patches`` ((du+1, dv+1, 3) arrays), ``provenance``, ``evaluate``,
    ``tessellate``, ``check`` and ``write``. ``fill=False`` leaves the hole inside the last
    ring open (``--no-fill``)."""
    return _fairsub.subdivide(_net(net), scheme, rings=rings, fill=fill, options=options)


def _provenance(self):
    """Per patch a dict, as ``fairsub check --json`` names it: ``{"kind": "regular", "face": F}``,
    ``{"kind": "ring", "element": {"type": "vertex", "index": V}, "ring": K, "sector": S}``
    (ring 1 outermost), ``{"kind": "cap", "element": ..., "sector": S}``."""
    return _json.loads(self.provenance_json())


def _evaluate(self, face, u, v):
    """Evaluates the complex at parameter (u, v) of input face ``face`` (scalars or arrays of
    one length): a dict of arrays ``point``, ``du``, ``dv``, ``duu``, ``duv``, ``dvv``,
    ``normal`` (n, 3), ``gauss``, ``mean`` (n), ``patch`` (n) and ``patch_uv`` (n, 2), as
    ``fairsub eval --rings K`` reports them. Parameter domains: quads [0,1]^2; an n-gon u in
    [0, n], v in [0, 1]; a Loop triangle barycentric (u, v)."""
    scalar = _np.ndim(face) == 0 and _np.ndim(u) == 0 and _np.ndim(v) == 0
    f = _np.ascontiguousarray(_np.atleast_1d(face), dtype=_np.int64)
    uu = _np.ascontiguousarray(_np.atleast_1d(u), dtype=_np.float64)
    vv = _np.ascontiguousarray(_np.atleast_1d(v), dtype=_np.float64)
    f, uu, vv = _np.broadcast_arrays(f, uu, vv)
    r = self.evaluate_arrays(
        _np.ascontiguousarray(f), _np.ascontiguousarray(uu), _np.ascontiguousarray(vv)
    )
    if scalar:
        return {k: a[0] for k, a in r.items()}
    return r


Surface.evaluate = _evaluate
Surface.provenance = property(_provenance)
Surface.check = lambda self: _json.loads(self.check_json())
Surface.check.__doc__ = (
    "``fairsub check NET --scheme S --rings K --json`` of the surface, as a dict "
    "(continuity defects per kind of join, curvature per ring, notes)."
)



def _measure(self, tolerance=1e-14, per_face=False):
    """``fairsub measure NET --scheme S --rings K --json`` of the surface, as a dict: ``area``
    (to the relative ``tolerance``), ``area_centroid``, ``area_inertia``, ``closed`` and, for
    a closed surface, ``volume`` (volume, centroid, inertia about it, principal moments),
    integrated exactly from the patches; ``per_face=True`` adds ``faces`` (the area over each
    input face)."""
    return _json.loads(self.measure_json(tolerance, per_face))


def _closest(self, points):
    """The closest points of the surface to ``points`` ((n, 3) or (3,)): a dict of arrays
    ``face``, ``u``, ``v`` (the parameters ``evaluate`` takes: evaluating there gives
    ``point``), ``point``, ``distance``, ``normal`` and ``on_boundary``, as ``fairsub
    project`` reports them."""
    p = _np.asarray(points, dtype=_np.float64)
    single = p.ndim == 1
    r = self.closest_arrays(_np.ascontiguousarray(_np.atleast_2d(p)))
    if single:
        return {k: a[0] for k, a in r.items()}
    return r


Surface.measure = _measure
Surface.closest = _closest


def analyze(scheme, valence, replicated_centre=False, **options):
    """``fairsub analyze --scheme S --valence N --json`` as a dict: spectrum, limit stencil,
    characteristic-map certificate, published numbers with their differences."""
    return _json.loads(_fairsub.analyze_json(scheme, valence, replicated_centre, options))


def render(what, mode=None, size=None, **look):
    """A picture as ``fairsub render`` draws it: a (height, width, 3) uint8 array of a Surface
    (exact normals and curvature per pixel), a Net, or a net file / gallery name.

    The keywords are the command's look options, typed (``None`` or omitted: the command's
    default, see ``render_defaults()``):

    - ``mode``: ``"shaded"``, ``"highlight"``, ``"reflection"``, ``"isophote"``, ``"gauss"``,
      ``"mean"`` or ``"provenance"`` (curvature and provenance need a Surface);
    - ``size``: ``(width, height)`` in pixels, a number for a square, or ``"WxH"``;
    - ``aa``: samples per pixel axis (1 to 8);
    - ``azimuth``, ``elevation``, ``fov``, ``light_angle``: degrees; ``distance``: model units
      (default: fit the view);
    - ``focus``: a vertex index, ``"vertex:V"`` or ``"face:F"``; ``zoom_rings``: ``(K, L)``,
      ``K`` or ``"K..L"`` (ring 1 the outermost);
    - ``range``: a fixed curvature range ``[-range, range]`` (default: automatic);
    - ``overlay``: ``"net"``, ``"patches"``, ``"net,patches"`` or a list of them;
    - ``stripes``, ``stripe_width``: stripe periods across the view and their dark fraction;
    - ``legend``: the numbers under curvature pictures (``no_legend=True``, the command
      line's spelling, also turns it off).

    A bad value raises ``ValueError`` naming the keyword (``bad stripe_width=1.5: must lie
    strictly between 0 and 1``); an unknown keyword raises ``ValueError`` listing them.

    >>> s = surface("gallery:cnet-5-saddle", "catmull-clark", rings=2)
    >>> render(s, "mean", size=(64, 48), legend=False).shape
    (48, 64, 3)
    """
    if isinstance(what, str):
        what = read(what)
    return _fairsub.render(what, mode=mode, size=size, **look)


def render_defaults():
    """The defaults of ``render``'s keywords, as a dict (the library's, which are the
    command line's: ``mode`` ``"shaded"``, ``size`` ``(800, 800)``, ``aa`` 2, ...)."""
    return _fairsub.render_defaults()


def level_stencils(net, scheme, levels=1, **options):
    """The stencil table from the control points of ``net`` to its ``levels``-fold refinement:
    ``(refined_net, stencils)``; ``stencils.apply(points)`` maps moved control points (n, 3)
    to the refined points, ``stencils.csr()`` gives (indptr, indices, weights)."""
    return _fairsub.level_stencils(_net(net), scheme, levels, options)
