"""Frame sources: where the vertex positions of each animation frame come from — a NumPy array
``(n_frames, V, 3)``, a sequence of mesh files with the mesh's connectivity, or the animation of
a glTF/GLB file sampled at a frame rate. Each gives frame times and positions on demand."""

from __future__ import annotations

import os

import numpy as np

from ..errors import AnimationError, MeshFileError
from ..mesh import Mesh
from .frame_rate import check_fps


#: File formats that carry their own animation.
ANIMATED_FORMATS = (".glb", ".gltf")


class ArrayFrames:
    """Frames from an ``(n_frames, V, 3)`` array of positions; frame k at time ``k / fps``."""

    def __init__(self, frames, mesh: Mesh, fps: float):
        array = np.asarray(frames, dtype=np.float64)
        if array.ndim != 3 or array.shape[2] != 3:
            raise AnimationError(f"frames must be an array of shape (n_frames, {mesh.n_vertices}, 3) or a list of "
                                 f"mesh files, got an array of shape {array.shape}")
        if array.shape[0] == 0:
            raise AnimationError("frames holds no frame (shape (0, V, 3))")
        if array.shape[1] != mesh.n_vertices:
            raise AnimationError(f"frames have {array.shape[1]} vertices each, the mesh {mesh.name!r} has "
                                 f"{mesh.n_vertices}; frames must list every vertex of the mesh, in its order")
        bad = ~np.isfinite(array).all(axis=(1, 2))
        if bad.any():
            raise AnimationError(f"frame {int(np.flatnonzero(bad)[0])} has NaN or Inf positions "
                                 f"({int(bad.sum())} frames are affected)")
        self._array = array
        self.times = np.arange(len(array)) / fps

    def __len__(self) -> int:
        return len(self._array)

    def positions(self, k: int) -> np.ndarray:
        return self._array[k]


class FileFrames:
    """Frames from mesh files (OBJ, PLY, ...), one per frame, each with the mesh's vertices and
    faces (checked as each is read); frame k at time ``k / fps``."""

    def __init__(self, paths, mesh: Mesh, fps: float):
        self._paths = [os.fspath(p) for p in paths]
        if not self._paths:
            raise AnimationError("frames is an empty list of mesh files")
        missing = [p for p in self._paths if not os.path.isfile(p)]
        if missing:
            raise MeshFileError(f"{len(missing)} frame file(s) do not exist, the first: {missing[0]!r}")
        self._mesh = mesh
        self.times = np.arange(len(self._paths)) / fps

    def __len__(self) -> int:
        return len(self._paths)

    def positions(self, k: int) -> np.ndarray:
        from ..io import read_geometry

        positions, faces = read_geometry(self._paths[k])
        name = os.path.basename(self._paths[k])
        if len(positions) != self._mesh.n_vertices:
            raise AnimationError(f"frame {k} ({name}) has {len(positions)} vertices, the mesh {self._mesh.name!r} "
                                 f"{self._mesh.n_vertices}; every frame needs the mesh's vertices in the same order")
        if not np.array_equal(faces, self._mesh.faces):
            raise AnimationError(f"frame {k} ({name}) has different faces from the mesh {self._mesh.name!r} "
                                 f"({len(faces)} vs {self._mesh.n_faces}); frames must share the mesh's connectivity")
        return positions


class GltfFrames:
    """The animation of a glTF/GLB file, sampled every ``1/fps`` seconds from its first to its last key."""

    def __init__(self, path: str, mesh: Mesh, fps: float, animation: int | str | None):
        from .gltf import GltfAnimation

        self.gltf = GltfAnimation(path, reference=mesh)
        self.animation = self.gltf.index(animation)
        self.times = self.gltf.times(fps, self.animation)

    @property
    def animation_name(self) -> str:
        return self.gltf.names[self.animation]

    def __len__(self) -> int:
        return len(self.times)

    def positions(self, k: int) -> np.ndarray:
        return self.gltf.positions(self.times[k], self.animation)


def frame_source(mesh: Mesh, path: str | None, frames, fps, animation):
    """The frame source for :func:`uvfeat.animate`'s arguments (see there), with clear errors."""
    fps = check_fps(fps)
    if frames is None:
        if path is None:
            raise AnimationError("a Mesh carries no animation of its own: pass frames= (an (n_frames, V, 3) array "
                                 "or a list of mesh files), or give the path of an animated glTF/GLB file")
        if os.path.splitext(path)[1].lower() not in ANIMATED_FORMATS:
            raise AnimationError(f"{os.path.basename(path)} has no animation of its own (only glTF/GLB files carry "
                                 "one); pass frames= (an (n_frames, V, 3) array or a list of mesh files)")
        return GltfFrames(path, mesh, fps, animation)
    if animation is not None:
        raise AnimationError("animation= chooses an animation of a glTF file; it cannot be combined with frames=")
    if isinstance(frames, (str, os.PathLike)):
        raise AnimationError("frames must be an (n_frames, V, 3) array or a list of mesh files, got a single path")
    if isinstance(frames, (list, tuple)) and frames and all(isinstance(f, (str, os.PathLike)) for f in frames):
        return FileFrames(frames, mesh, fps)
    return ArrayFrames(frames, mesh, fps)
