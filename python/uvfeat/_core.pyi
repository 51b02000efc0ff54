"""Type stubs of the native module (crates/uvfeat-python): the Rust engine behind the package.
Users call the Python classes (uvfeat.Atlas, uvfeat.Mesh, ...), which wrap these."""

from collections.abc import Sequence
from typing import Any, Optional, final

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "__version__",
    "SEVERAL_SHEETS",
    "Topology",
    "Atlas",
    "shape",
    "unwrap",
    "shaded_view",
    "front_side",
    "atlas_bytes",
    "surfel_grid_width",
    "ComputeSettings",
    "FeatureMaps",
    "compute_settings",
    "sampling_settings",
    "check_options",
    "feature_names",
    "default_options",
    "paper_options",
    "option_choices_by_name",
    "compute_maps",
    "vertex_feature_values",
    "sums_apply",
    "neighbourhood_tile_arrays",
    "ReferenceMesh",
]

__version__: str
SEVERAL_SHEETS: float

_Matrix = tuple[tuple[float, float], tuple[float, float]]
_UV = Sequence[float]

def atlas_bytes(resolution: int, n_faces: int) -> int:
    """Bytes an atlas of ``n_faces`` faces takes at ``resolution``² (buffers and per-face tables)."""

def surfel_grid_width(surface_area: float, uv_area: float, radius: float, per_ball: float, largest: int) -> int:
    """The surfel grid for balls of ``radius`` summed over about ``per_ball`` surfels on charts of
    ``surface_area`` over ``uv_area`` of the unit square: the width whose texels of the mean size put
    ``per_ball`` in a plane's ball, to a multiple of 16 from 64 up to ``largest``; ``largest`` where
    the areas, the radius or ``per_ball`` are not positive and finite."""

def shape(
    name: str, sizes: list[float], counts: list[int], mirrored: bool = False
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.float64], NDArray[np.int64]]:
    """Analytic mesh by name: ``(positions, faces, uvs, uv_faces)``."""

def unwrap(
    positions: NDArray[np.float64],
    faces: NDArray[np.int64],
    resolution: int | None = None,
    padding: float | None = None,
    max_angle: float | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.int64], int]:
    """Normal-cone charts packed into the unit square: ``(uvs, uv_faces, n_charts)``."""

def shaded_view(
    view: NDArray[np.float64],
    faces: NDArray[np.int64],
    values: NDArray[np.float64],
    palette: NDArray[np.float64],
    range: tuple[float, float],
    corner: tuple[float, float],
    scale: float,
    size: tuple[int, int],
    supersampling: int,
    front: int,
) -> NDArray[np.float64]:
    """RGBA picture of per-vertex ``values`` on the faces seen from ``front``, shaded by a headlight."""

def front_side(positions: NDArray[np.float64], faces: NDArray[np.int64]) -> int:
    """0 for an open mesh (both sides show), 1 for a closed one wound outwards, -1 inwards."""

@final
class Topology:
    """Welded connectivity, charts, seams and sides of a UV-mapped mesh (built once)."""

    def __new__(
        cls,
        positions: NDArray[np.float64],
        faces: NDArray[np.int64],
        uvs: NDArray[np.float64],
        uv_faces: NDArray[np.int64],
        weld_tolerance: float = 0.0,
    ) -> Topology: ...
    @property
    def n_charts(self) -> int: ...
    @property
    def n_geometric_vertices(self) -> int: ...
    @property
    def vertex_ids(self) -> NDArray[np.int64]: ...
    @property
    def face_chart(self) -> NDArray[np.int32]: ...
    @property
    def diagnostics(self) -> dict[str, int]: ...

@final
class Atlas:
    """The rasterised atlas: per-texel buffers and per-frame quantities."""

    def __new__(
        cls,
        topology: Topology,
        positions: NDArray[np.float64],
        resolution: int = 1024,
        precision: str = "f32",
        memory_budget: int = ...,
        coverage_on_first_use: bool = False,
    ) -> Atlas: ...
    def update(self, positions: NDArray[np.float64]) -> None: ...
    @property
    def resolution(self) -> int: ...
    @property
    def precision(self) -> str: ...
    @property
    def position(self) -> NDArray[Any]: ...
    @property
    def normal(self) -> NDArray[Any]: ...
    @property
    def sigma(self) -> NDArray[np.float32]: ...
    @property
    def theta(self) -> NDArray[np.float32]: ...
    @property
    def chart(self) -> NDArray[np.int32]: ...
    @property
    def face(self) -> NDArray[np.int32]: ...
    @property
    def border_side(self) -> NDArray[np.int32]: ...
    @property
    def border(self) -> NDArray[np.bool_]: ...
    @property
    def adjacent_chart(self) -> NDArray[np.int32]: ...
    @property
    def diagnostics(self) -> dict[str, Any]: ...
    def locate(
        self, start: _UV, chart: int, target: _UV, max_jumps: int = 32
    ) -> tuple[str, int, Optional[tuple[float, float]], Optional[_Matrix], int]: ...
    def cross_seam(self, uv: _UV, chart: int) -> Optional[tuple[int, tuple[float, float], _Matrix, int]]: ...
    def seam_map(self, side: int) -> Optional[tuple[tuple[float, float], tuple[float, float], _Matrix]]: ...
    def reverse_side(self, side: int) -> int: ...
    def surface_point(
        self, uv: _UV, chart: int
    ) -> Optional[tuple[tuple[float, float, float], tuple[float, float, float], int]]: ...

@final
class ComputeSettings:
    """Validated settings of a feature computation (built by :func:`compute_settings`)."""

@final
class FeatureMaps:
    """The feature maps of one computation over the computation texture."""

    @property
    def resolution(self) -> int: ...
    @property
    def features(self) -> list[str]: ...
    def values(self, k: int) -> NDArray[np.float32]: ...
    def standard_errors(self, k: int) -> Optional[NDArray[np.float32]]: ...
    @property
    def chart(self) -> NDArray[np.int32]: ...
    @property
    def n_valid(self) -> NDArray[np.uint32]: ...
    @property
    def n_missing(self) -> NDArray[np.uint32]: ...
    @property
    def n_border(self) -> NDArray[np.uint32]: ...
    @property
    def second_stage(self) -> NDArray[np.bool_]: ...
    @property
    def principal_directions(self) -> Optional[NDArray[np.float32]]: ...
    @property
    def fit_residual(self) -> Optional[NDArray[np.float32]]: ...
    @property
    def area_ratio(self) -> NDArray[np.float32]: ...
    @property
    def sheet_area(self) -> NDArray[np.float32]: ...
    def per_vertex_directions(self, atlas: Atlas) -> NDArray[np.float32]: ...
    @property
    def summary(self) -> dict[str, Any]: ...
    def per_vertex(self, atlas: Atlas, query: str) -> list[NDArray[np.float32]]: ...
    def per_corner(
        self, atlas: Atlas
    ) -> tuple[NDArray[np.float64], NDArray[np.int64], list[NDArray[np.float32]]]: ...

def compute_settings(features: list[str], radius: float, options: dict[str, Any]) -> ComputeSettings: ...
def sampling_settings(radius: float, options: dict[str, Any]) -> ComputeSettings: ...
def check_options(options: dict[str, Any]) -> None:
    """Validates options on their own, before there is a mesh or a radius."""

def feature_names() -> list[str]:
    """Every feature name, in output order."""

def default_options() -> dict[str, Any]:
    """Every option of a feature computation with its default, in order."""

def paper_options() -> dict[str, Any]:
    """The options the paper's choices change, with the paper's values."""

def option_choices_by_name() -> dict[str, list[str]]:
    """The names each choice option takes, the default first."""

def compute_maps(atlas: Atlas, settings: ComputeSettings) -> FeatureMaps: ...
def sums_apply(atlas: Atlas, settings: ComputeSettings) -> bool:
    """Whether `settings` are evaluated at the vertices from the surfels' moments on `atlas` (the
    core's choice of integration) rather than read from maps."""

def vertex_feature_values(
    atlas: Atlas, settings: ComputeSettings, radii: NDArray[np.float64] | None = None
) -> tuple[list[NDArray[np.float32]], NDArray[np.uint32], NDArray[np.uint32]]: ...
def neighbourhood_tile_arrays(
    atlas: Atlas, settings: ComputeSettings, start: int, stop: int
) -> tuple[
    NDArray[np.uint32],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.float64],
    NDArray[np.bool_],
]: ...

@final
class ReferenceMesh:
    """Half-edge connectivity and Voronoi areas of the object-space reference."""

    def __new__(cls, positions: NDArray[np.float64], faces: NDArray[np.int64]) -> ReferenceMesh: ...
    @property
    def n_welded_vertices(self) -> int: ...
    def geodesic_distances(self, source: int, max_distance: float) -> NDArray[np.float64]: ...
    def compute(
        self,
        features: list[str],
        radius: float,
        gaussian_method: str,
        volume_weighting: str,
        rho_min: float,
        flat_tol: float,
        method: str,
        vertices: Optional[NDArray[np.int64]] = None,
    ) -> tuple[list[NDArray[np.float64]], NDArray[np.uint32]]: ...
