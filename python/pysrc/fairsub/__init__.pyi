"""Type hints of the fairsub package (see the docstrings of ``fairsub/__init__.py``)."""

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

FloatArray = npt.NDArray[np.float64]

class Net:
    """A validated control net (polygon mesh)."""

    def __init__(
        self,
        vertices: npt.ArrayLike,
        faces: Union[Sequence[Sequence[int]], Tuple[npt.ArrayLike, npt.ArrayLike]],
        *,
        tolerant: bool = False,
        creases: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = None,
        corners: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = None,
        holes: Optional[npt.ArrayLike] = None,
        uv: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = None,
    ) -> None:
        """A net from vertices (n, 3) and faces (vertex-index lists, or the flat pair
        ``(sizes, indices)`` of numpy arrays), with OpenSubdiv's tags ``creases=(edges (m, 2),
        sharpness (m,))``, ``corners=(vertices (k,), sharpness (k,))``, ``holes=faces`` and
        face-varying texture coordinates ``uv=(values (t, 2), indices (one per face corner))``.
        ``tolerant=True`` accepts non-manifold nets and keeps unused vertices in place."""
        ...
    @property
    def vertices(self) -> FloatArray: ...
    @property
    def faces(self) -> List[List[int]]: ...
    @property
    def face_arrays(self) -> Tuple[npt.NDArray[np.uint32], npt.NDArray[np.uint32]]:
        """The faces as the flat pair (sizes, indices)."""
        ...
    @property
    def creases(self) -> Tuple[npt.NDArray[np.uint32], npt.NDArray[np.float32]]:
        """Sharp edges (edges (m, 2), sharpness (m,)); on a refined Catmull-Clark or Loop net
        the refined sharpness, with boundary and non-manifold edges at 10 (infinitely sharp)."""
        ...
    @property
    def corners(self) -> Tuple[npt.NDArray[np.uint32], npt.NDArray[np.float32]]:
        """Sharp vertices (vertices (k,), sharpness (k,)), refined like ``creases``."""
        ...
    @property
    def holes(self) -> npt.NDArray[np.uint32]: ...
    @property
    def uv(self) -> Optional[Tuple[FloatArray, npt.NDArray[np.uint32]]]:
        """Face-varying texture coordinates (values (t, 2), one index per face corner), refined
        by OpenSubdiv's face-varying rules on a refined Catmull-Clark or Loop net."""
        ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def num_faces(self) -> int: ...
    @property
    def source(self) -> Optional[str]: ...
    @property
    def warnings(self) -> List[str]: ...
    def info(self) -> Dict[str, Any]: ...
    def info_json(self) -> str: ...
    def write(self, path: str) -> None: ...

class Surface:
    """An exact Bezier patch complex with provenance."""

    def __len__(self) -> int: ...
    @property
    def patches(self) -> List[FloatArray]: ...
    @property
    def provenance(self) -> List[Dict[str, Any]]: ...
    def provenance_json(self) -> str: ...
    @property
    def notes(self) -> List[str]: ...
    @property
    def scheme(self) -> str: ...
    def evaluate(
        self, face: npt.ArrayLike, u: npt.ArrayLike, v: npt.ArrayLike
    ) -> Dict[str, Any]: ...
    def evaluate_arrays(
        self, face: npt.NDArray[np.int64], u: FloatArray, v: FloatArray
    ) -> Dict[str, Any]: ...
    def tessellate(self, n: int) -> Tuple[FloatArray, npt.NDArray[np.uint32]]: ...
    def tessellation(self, n: int) -> Dict[str, Any]:
        """``tessellate(n)`` with per vertex the exact ``normals``, ``patch``, ``patch_uv`` and
        ``gauss``, ``mean`` curvature, and per triangle its ``triangle_patch``."""
        ...
    def check(self) -> Dict[str, Any]: ...
    def check_json(self) -> str: ...
    def measure_json(self, tolerance: float = 1e-14, per_face: bool = False) -> str: ...
    def measure(self, tolerance: float = 1e-14, per_face: bool = False) -> Dict[str, Any]:
        """``fairsub measure --json`` of the surface: area, centroids, inertia tensors and,
        for a closed surface, the enclosed volume, exact from the patches."""
        ...
    def closest_arrays(self, points: FloatArray) -> Dict[str, Any]: ...
    def closest(self, points: FloatArray) -> Dict[str, Any]:
        """The closest points of the surface to ``points`` (n, 3): face, u, v (as
        ``evaluate`` takes them), point, distance, normal, on_boundary."""
        ...
    def write(self, path: str, tess: int = 8) -> None: ...
    def stencils(self) -> PatchTable:
        """The patch stencil table of this surface (what ``fairsub subdivide NET --scheme S
        --rings K --stencils FILE`` writes, built by the same code): the weights from the
        net's control points to every Bezier coefficient, built once and re-applied to moved
        points without redoing the construction.

        Example::

            s = fairsub.surface("gallery:torus-evs", "catmull-clark", rings=2)
            t = s.stencils()
            net = fairsub.read("gallery:torus-evs")
            patches = t.apply(net.vertices + 0.1 * np.random.rand(48, 3))
        """
        ...

class PatchTable:
    """The patch stencil table of a Surface: one row per Bezier coefficient (patch order,
    ``b[i, j]`` at ``first_rows[p] + i * (deg_v + 1) + j``), then the data rows of the G^1
    caps, which ``apply`` rebuilds in their tangent plane (their one step that is not linear
    in the points)."""

    def __len__(self) -> int: ...
    @property
    def num_sources(self) -> int: ...
    @property
    def num_rows(self) -> int: ...
    @property
    def shapes(self) -> List[Tuple[int, int]]: ...
    @property
    def first_rows(self) -> npt.NDArray[np.uint64]: ...
    @property
    def cap_patches(self) -> List[bool]: ...
    def csr(
        self,
    ) -> Tuple[npt.NDArray[np.uint64], npt.NDArray[np.uint32], FloatArray]:
        """The rows in CSR form: (indptr, indices, weights)."""
        ...
    def apply(self, points: npt.NDArray[np.float64]) -> List[FloatArray]:
        """Moved control points (num_sources, 3) -> the patches, (deg_u+1, deg_v+1, 3) arrays,
        equal to the surface recomputed from the moved net. Other widths (num_sources, d) are
        per-point data (``apply_data``)."""
        ...
    def apply_data(self, values: npt.NDArray[np.float64]) -> List[FloatArray]:
        """Per-point data (num_sources, d) through the same rows: (deg_u+1, deg_v+1, d)
        arrays (G^1 caps fit their tangents in the data's own space)."""
        ...
    def write(self, path: str) -> None:
        """Writes the table as ``subdivide --stencils FILE`` does."""
        ...

class Stencils:
    """A sparse stencil table (refined points from control points)."""

    @property
    def num_rows(self) -> int: ...
    @property
    def num_sources(self) -> int: ...
    def csr(
        self,
    ) -> Tuple[npt.NDArray[np.uint64], npt.NDArray[np.uint32], FloatArray]: ...
    def apply(self, points: npt.ArrayLike) -> FloatArray: ...

def read(path: str, tolerant: bool = False) -> Net: ...
def info(net: Union[Net, str]) -> Dict[str, Any]: ...
def schemes() -> List[Dict[str, Any]]: ...
def subdivide(
    net: Union[Net, str], scheme: str, levels: int = 1, limit: bool = False, **options: Any
) -> Union[Net, Tuple[Net, FloatArray]]: ...
def surface(
    net: Union[Net, str], scheme: str, rings: int = 6, fill: bool = True, **options: Any
) -> Surface: ...
def analyze(
    scheme: str, valence: int, replicated_centre: bool = False, **options: Any
) -> Dict[str, Any]: ...
def render(
    what: Union[Net, Surface, str],
    mode: Optional[str] = None,
    size: Union[Tuple[int, int], int, str, None] = None,
    *,
    aa: Optional[int] = None,
    azimuth: Optional[float] = None,
    elevation: Optional[float] = None,
    distance: Optional[float] = None,
    fov: Optional[float] = None,
    focus: Union[int, str, None] = None,
    zoom_rings: Union[Tuple[int, int], int, str, None] = None,
    range: Optional[float] = None,
    overlay: Union[str, Sequence[str], None] = None,
    stripes: Optional[float] = None,
    stripe_width: Optional[float] = None,
    light_angle: Optional[float] = None,
    legend: Optional[bool] = None,
    no_legend: Optional[bool] = None,
) -> npt.NDArray[np.uint8]: ...
def render_defaults() -> Dict[str, Any]: ...
def scheme_options(scheme: str) -> List[Dict[str, Any]]: ...
def curvature_colours(
    values: npt.ArrayLike, range: Optional[float] = None, percentile: float = 0.98
) -> Tuple[FloatArray, float]: ...
def level_stencils(
    net: Union[Net, str], scheme: str, levels: int = 1, **options: Any
) -> Tuple[Net, Stencils]: ...
