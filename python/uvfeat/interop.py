"""Meshes from the objects users already hold, and results back into them.

Every entry point that takes a mesh (:func:`uvfeat.compute`, :class:`uvfeat.Atlas`,
:func:`uvfeat.reference.compute`, :func:`uvfeat.converged_reference`, :func:`uvfeat.compare.compare`,
:func:`uvfeat.plot`, :func:`uvfeat.view`, :func:`uvfeat.bake`, :func:`uvfeat.animate`) takes
any of :data:`ACCEPTED`. trimesh, PyVista and Open3D are recognised only when the caller has
imported them already: none of them is a dependency of uvfeat for this.

Per-vertex results follow the source's own vertices (a trimesh's ``vertices``, a PolyData's
``points``, an Open3D mesh's ``vertices``); :func:`attach` stores them on the source object and
:func:`to_pyvista` gives a PyVista mesh coloured by a feature.
"""

from __future__ import annotations

import sys
import warnings
from dataclasses import dataclass

import numpy as np

from .errors import InvalidMeshError, InvalidParameterError
from .mesh import Mesh

#: What a mesh argument may be.
ACCEPTED = ("a uvfeat.Mesh, a trimesh.Trimesh, a pyvista.PolyData or UnstructuredGrid, an "
            "open3d.geometry.TriangleMesh, or a (positions, faces) or (positions, faces, uvs, uv_faces) "
            "tuple of arrays")


@dataclass(frozen=True)
class MeshSource:
    """A :class:`~uvfeat.Mesh` made from a user's object, and where its vertices came from."""

    #: The mesh uvfeat computes on.
    mesh: Mesh
    #: Number of points of the source object.
    n_points: int
    #: The source's point of each mesh vertex, or None where they are the same rows.
    point_of_vertex: np.ndarray | None = None

    def to_points(self, values: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Per-vertex ``values`` (last axis over the mesh's vertices) in the source's point order,
        NaN at points that are on no face (a volume grid's interior)."""
        if self.point_of_vertex is None:
            return values
        out = {}
        for name, array in values.items():
            array = np.asarray(array)
            full = np.full(array.shape[:-1] + (self.n_points,), np.nan, dtype=np.result_type(array, np.float32))
            full[..., self.point_of_vertex] = array
            out[name] = full
        return out


def _module(name: str):
    """The module ``name`` if the caller imported it (uvfeat never imports it for them)."""
    return sys.modules.get(name)


def _from_trimesh(source) -> MeshSource:
    positions, faces = np.asarray(source.vertices), np.asarray(source.faces)
    visual = getattr(source, "visual", None)
    uv = getattr(visual, "uv", None) if getattr(visual, "kind", None) == "texture" else None
    uvs = None if uv is None or len(uv) != len(positions) else np.asarray(uv, dtype=np.float64)[:, :2]
    name = (getattr(source, "metadata", None) or {}).get("name")
    return MeshSource(Mesh(positions, faces, uvs, name=name or "trimesh"), len(positions))


def _texture_coordinates(surface) -> np.ndarray | None:
    for attribute in ("active_texture_coordinates", "active_t_coords"):  # PyVista >= 0.43, older
        try:
            coordinates = getattr(surface, attribute)
        except AttributeError:
            continue
        return None if coordinates is None else np.asarray(coordinates, dtype=np.float64)[:, :2]
    return None


def _outer_surface(dataset):
    """The boundary surface of a PyVista dataset, with the dataset's point of each of its points."""
    with warnings.catch_warnings():
        # PyVista announces a change of the default algorithm; the current one is what is wanted.
        warnings.simplefilter("ignore", FutureWarning)
        return dataset.extract_surface(pass_pointid=True)


def _from_pyvista(source, pyvista) -> MeshSource:
    point_of_vertex = None
    surface = source
    if not isinstance(source, pyvista.PolyData):
        surface = _outer_surface(source)
        point_of_vertex = np.asarray(surface.point_data["vtkOriginalPointIds"], dtype=np.int64)
    if len(surface.faces) == 0:
        raise InvalidMeshError(f"the {type(source).__name__} has no polygons to take as a surface")
    if not surface.is_all_triangles:
        # Quads and polygons split into triangles; the points stay as they are.
        surface = surface.triangulate()
    cells = np.asarray(surface.faces).reshape(-1, 4)
    uvs = _texture_coordinates(surface)
    mesh = Mesh(np.asarray(surface.points, dtype=np.float64), cells[:, 1:], uvs, name=type(source).__name__)
    return MeshSource(mesh, source.n_points, point_of_vertex)


def _from_open3d(source) -> MeshSource:
    positions, faces = np.asarray(source.vertices), np.asarray(source.triangles)
    uvs = uv_faces = None
    if source.has_triangle_uvs():
        # Open3D stores one UV per face corner, in face order.
        uvs = np.asarray(source.triangle_uvs, dtype=np.float64)
        uv_faces = np.arange(len(uvs)).reshape(-1, 3)
    return MeshSource(Mesh(positions, faces, uvs, uv_faces, name="open3d"), len(positions))


def mesh_source(source) -> MeshSource:
    """The :class:`MeshSource` of any of :data:`ACCEPTED`.

    Raises
    ------
    InvalidMeshError
        ``source`` is none of them, or its arrays do not make a mesh.
    """
    if isinstance(source, Mesh):
        return MeshSource(source, source.n_vertices)
    if isinstance(source, (tuple, list)) and len(source) in (2, 4):
        mesh = Mesh(*source)
        return MeshSource(mesh, mesh.n_vertices)
    trimesh = _module("trimesh")
    if trimesh is not None and isinstance(source, trimesh.Trimesh):
        return _from_trimesh(source)
    pyvista = _module("pyvista")
    if pyvista is not None and isinstance(source, pyvista.DataSet):
        return _from_pyvista(source, pyvista)
    open3d = _module("open3d")
    if open3d is not None and isinstance(source, open3d.geometry.TriangleMesh):
        return _from_open3d(source)
    kind = type(source)
    shape = f" of {len(source)} items" if isinstance(source, (tuple, list)) else ""
    raise InvalidMeshError(f"cannot take a {kind.__module__}.{kind.__qualname__}{shape} as a mesh; uvfeat takes "
                           f"{ACCEPTED}")


def as_mesh(source) -> Mesh:
    """The :class:`~uvfeat.Mesh` of any of :data:`ACCEPTED` (``source`` itself for a Mesh)."""
    return mesh_source(source).mesh


def _point_columns(values: dict[str, np.ndarray], n_points: int) -> dict[str, np.ndarray]:
    """Per-point arrays (points first: one column per radius where there are several)."""
    columns = {}
    for name, array in values.items():
        array = np.asarray(array)
        if array.shape[-1] != n_points:
            raise InvalidParameterError(f"{name!r} has {array.shape[-1]} values per row, the mesh {n_points} points")
        columns[name] = array.T if array.ndim == 2 else array
    return columns


def attach(target, values: dict[str, np.ndarray]):
    """Stores per-vertex ``values`` (as :func:`uvfeat.compute` returns them for ``target``) on
    ``target`` and returns it: a trimesh's ``vertex_attributes``, a PyVista dataset's ``point_data``
    (several radii: one column per radius). Other objects have no place for them: keep the arrays.

    Raises
    ------
    InvalidParameterError
        ``target`` has no per-vertex fields, or the arrays do not match its vertices.
    """
    trimesh, pyvista = _module("trimesh"), _module("pyvista")
    if trimesh is not None and isinstance(target, trimesh.Trimesh):
        target.vertex_attributes.update(_point_columns(values, len(target.vertices)))
        return target
    if pyvista is not None and isinstance(target, pyvista.DataSet):
        for name, column in _point_columns(values, target.n_points).items():
            target.point_data[name] = column
        return target
    raise InvalidParameterError(f"a {type(target).__name__} has no per-vertex fields to attach values to; keep the "
                                "arrays, or take a PyVista mesh with uvfeat.to_pyvista")


def to_pyvista(source, values: dict[str, np.ndarray] | None = None, feature: str | None = None):
    """A ``pyvista.PolyData`` of ``source`` (any of :data:`ACCEPTED`; a PolyData is copied) with
    ``values`` as point data and ``feature`` (default: the first) as its active scalars, for a
    quick look: ``uvfeat.to_pyvista(mesh, values).plot()``. Needs PyVista (``pip install pyvista``).
    """
    try:
        import pyvista
    except ImportError as error:
        raise ImportError("uvfeat.to_pyvista needs PyVista: pip install pyvista") from error
    if isinstance(source, pyvista.PolyData):
        poly = source.copy()
    elif isinstance(source, pyvista.DataSet):
        poly = _outer_surface(source)
        points = np.asarray(poly.point_data["vtkOriginalPointIds"], dtype=np.int64)
        values = values and {name: np.asarray(array)[..., points] for name, array in values.items()}
    else:
        mesh = mesh_source(source).mesh
        cells = np.column_stack([np.full(mesh.n_faces, 3), mesh.faces]).ravel()
        poly = pyvista.PolyData(np.array(mesh.positions), cells)
    if values:
        attach(poly, values)
        name = feature or next(iter(values))
        if name not in values:
            raise InvalidParameterError(f"feature {name!r} is not among the values ({', '.join(values)})")
        poly.set_active_scalars(name)
    return poly
