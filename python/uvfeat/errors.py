"""Exceptions raised by uvfeat. Every message names the problem and, where there is one, the fix.

All derive from :class:`UvfeatError`; each also derives from the built-in exception a caller
would expect (``ValueError`` for bad values, ``OSError`` for files, ``MemoryError`` for sizes).
"""


class UvfeatError(Exception):
    """Base class of every uvfeat error."""


class InvalidMeshError(UvfeatError, ValueError):
    """The mesh cannot be used: empty, NaN/Inf positions, bad indices, wrong array shapes..."""


class UVError(InvalidMeshError):
    """The UV map cannot be used: missing, NaN/Inf, outside [0, 1] or degenerate."""


class InvalidParameterError(UvfeatError, ValueError):
    """A parameter (resolution, radius, precision, ...) is outside its valid range."""


class ResolutionTooLargeError(InvalidParameterError, MemoryError):
    """The requested buffers would not fit in memory; the message says how much they need."""


class MeshFileError(UvfeatError, OSError):
    """A mesh file is missing, unreadable or of an unsupported format."""


class UVWarning(UserWarning):
    """The UVs were changed (normalised into [0, 1]) or look suspicious (overlaps, tiny charts)."""


class NeighbourhoodWarning(UserWarning):
    """Some per-vertex values come from neighbourhoods that are not what the radius asks for: cut
    by a mesh border, partly missing, or holding more than one sheet of the surface (the radius is
    wider than a thin part). ``FeatureMap.vertex_flags()`` says which vertices."""


class MeshWarning(UserWarning):
    """The mesh was changed on load (polygons triangulated) or has defects uvfeat works around."""


class AnimationError(UvfeatError, ValueError):
    """An animation cannot be used: none in the file, unknown name, frames whose vertex count or
    connectivity disagrees with the mesh, inconsistent keyframe data."""


class MissingDependencyError(UvfeatError, ImportError):
    """An optional dependency is not installed; the message names the ``pip install uvfeat[...]``
    extra that brings it."""


class ViewerError(UvfeatError, RuntimeError):
    """The interactive viewer cannot start: no display or no OpenGL/EGL for its backend."""


class ClusterError(UvfeatError, OSError):
    """The Dask cluster cannot be reached or started."""
