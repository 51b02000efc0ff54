"""Vertex positions of an animated glTF/GLB file at any time: node animation channels, morph
targets (weights channels) and linear-blend skinning, per glTF 2.0 §3.7.3 and §3.11.

Per primitive and frame: ``p = base + sum_t w_t d_t`` (morph targets), then
``p' = sum_k w_k J_k p`` with joint matrices ``J_j = world(joint_j) @ inverse_bind_j`` for skinned
primitives (the skinned node's own transform is ignored, as the spec says), or
``p' = world(node) @ p`` otherwise.
"""

from __future__ import annotations

import os

import numpy as np

from ..errors import AnimationError, MeshFileError
from .accessors import Accessors, read_gltf
from .interpolation import Channel
from .scene import Pose, SceneGraph
from .frame_rate import check_fps

#: Numbers per key of each animated property.
PATH_WIDTHS = {"translation": 3, "rotation": 4, "scale": 3}


def _transform(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    # einsum, not BLAS products (here and for the morph targets): OpenBLAS's threads spin on the
    # cores after a large product, slowing the frame's features that follow (uvfeat.pictures.render).
    return np.einsum("ij,vj->vi", matrix[:3, :3], points) + matrix[:3, 3]


def linear_blend_skinning(points: np.ndarray, joints: np.ndarray, weights: np.ndarray,
                          joint_matrices: np.ndarray) -> np.ndarray:
    """``sum_k weights[:, k] * joint_matrices[joints[:, k]] @ points`` for ``(V, 3)`` points,
    ``(V, K)`` joints and weights and ``(J, 4, 4)`` matrices; ``(V, 3)`` float64."""
    blend = np.einsum("vk,vkij->vij", weights, joint_matrices[joints][:, :, :3, :])
    return np.einsum("vij,vj->vi", blend[:, :, :3], points) + blend[:, :, 3]


class GltfAnimation:
    """The animations of a glTF/GLB file, evaluated into vertex positions.

    Positions come in the order of ``uvfeat.load(path).positions`` (primitives concatenated as
    trimesh walks the scene, vertices as stored). Pass ``reference`` (a :class:`~uvfeat.Mesh` or
    its ``(V, 3)`` positions) to check that order against a loaded mesh: each primitive is found
    by its rest positions, so the check also fixes the order should trimesh walk the scene
    differently.

    Raises
    ------
    MeshFileError
        Missing or unreadable file.
    AnimationError
        Inconsistent animation data (key and value counts, morph targets, joints), or positions
        that do not line up with ``reference``.
    """

    def __init__(self, path: str | os.PathLike, reference=None):
        self.path = os.fspath(path)
        if not os.path.isfile(self.path):
            raise MeshFileError(f"no such file: {self.path!r}")
        self.name = os.path.basename(self.path)
        gltf = read_gltf(self.path)
        self._gltf, self._read = gltf, Accessors(gltf, self.name)
        self.scene = SceneGraph(gltf, self._read, self.name)
        if not self.scene.primitives:
            raise AnimationError(f"{self.name} draws no triangle mesh")
        self._channels: dict[int, list] = {}
        self._joint_bind: dict[int, tuple[list[int], np.ndarray]] = {}
        if reference is not None:
            self.match(getattr(reference, "positions", reference))

    # -- animations -------------------------------------------------------------------------------
    @property
    def names(self) -> list[str]:
        """Names of the file's animations (``"animation <i>"`` for unnamed ones)."""
        return [a.name or f"animation {i}" for i, a in enumerate(self._gltf.animations)]

    @property
    def n_vertices(self) -> int:
        return sum(len(p.positions) for p in self.scene.primitives)

    def _listing(self) -> str:
        return ", ".join(f"{i}: {name!r}" for i, name in enumerate(self.names))

    def index(self, animation: int | str | None = None) -> int:
        """Index of an animation given by index or name (default: the first)."""
        if not self.names:
            raise AnimationError(f"{self.name} has no animation; pass frames= (positions or mesh files) instead")
        if animation is None:
            return 0
        if isinstance(animation, str) and animation not in self.names and animation.strip().isdigit():
            animation = int(animation)
        if isinstance(animation, (int, np.integer)) and not isinstance(animation, bool):
            if 0 <= animation < len(self.names):
                return int(animation)
            raise AnimationError(f"{self.name} has no animation {animation}; it has {len(self.names)}: {self._listing()}")
        if isinstance(animation, str) and animation in self.names:
            return self.names.index(animation)
        raise AnimationError(f"{self.name} has no animation {animation!r}; choose one by name or index: {self._listing()}")

    def channels(self, animation: int | str | None = None) -> list[tuple[int, str, Channel]]:
        """``(node, path, channel)`` of every channel of an animation that moves a node."""
        index = self.index(animation)
        if index not in self._channels:
            gltf_animation = self._gltf.animations[index]
            out = []
            for number, channel in enumerate(gltf_animation.channels):
                node, path = channel.target.node, channel.target.path
                if node is None or path not in (*PATH_WIDTHS, "weights"):
                    continue  # targets defined by extensions (KHR_animation_pointer): nothing of ours
                what = f"{self.name}: animation {self.names[index]!r} channel {number} ({path} of node {node})"
                if path == "weights":
                    if node not in self.scene.rest.weights:
                        raise AnimationError(f"{what} animates morph weights of a node without a mesh")
                    width = len(self.scene.rest.weights[node])
                else:
                    width = PATH_WIDTHS[path]
                    if node in self.scene.rest.matrix:
                        raise AnimationError(f"{what}: the node has a matrix, which glTF does not allow to animate")
                sampler = gltf_animation.samplers[channel.sampler]
                out.append((node, path, Channel.from_sampler(self._read(sampler.input), self._read(sampler.output),
                                                             sampler.interpolation, width, path == "rotation", what)))
            if not out:
                raise AnimationError(f"{self.name}: animation {self.names[index]!r} has no channel that moves a node")
            self._channels[index] = out
        return self._channels[index]

    def time_range(self, animation: int | str | None = None) -> tuple[float, float]:
        """First and last key time (seconds) over the animation's channels."""
        channels = self.channels(animation)
        return min(c.start for _, _, c in channels), max(c.end for _, _, c in channels)

    def times(self, fps: float = 24.0, animation: int | str | None = None) -> np.ndarray:
        """Frame times from the first to the last key, ``1/fps`` apart (the last key included when
        the duration is a whole number of frames)."""
        fps = check_fps(fps)
        start, end = self.time_range(animation)
        count = int(np.floor((end - start) * fps + 1e-6)) + 1
        return start + np.arange(count) / fps

    def pose(self, time: float | None = None, animation: int | str | None = None) -> Pose:
        """Local transforms and morph weights at ``time`` (the file's rest pose when None)."""
        pose = self.scene.rest.copy()
        if time is None:
            return pose
        for node, path, channel in self.channels(animation):
            getattr(pose, path)[node] = channel.at(float(time))
        return pose

    # -- positions --------------------------------------------------------------------------------
    def _joint_matrices(self, skin: int, world: dict[int, np.ndarray]) -> np.ndarray:
        if skin not in self._joint_bind:
            gltf_skin = self._gltf.skins[skin]
            joints = list(gltf_skin.joints or [])
            if gltf_skin.inverseBindMatrices is None:
                bind = np.broadcast_to(np.eye(4), (len(joints), 4, 4))
            else:
                bind = self._read(gltf_skin.inverseBindMatrices)
                if len(bind) < len(joints):
                    raise AnimationError(f"{self.name}: skin {skin} has {len(joints)} joints but only "
                                         f"{len(bind)} inverse bind matrices")
            self._joint_bind[skin] = joints, bind
        joints, bind = self._joint_bind[skin]
        return np.stack([world[j] for j in joints]) @ bind[:len(joints)]

    def positions(self, time: float | None = None, animation: int | str | None = None) -> np.ndarray:
        """``(n_vertices, 3)`` float64 positions at ``time`` seconds of ``animation`` (index or
        name, default the first); ``time=None`` gives the rest pose (node transforms and default
        morph weights of the file, skins applied)."""
        pose = self.pose(time, animation)
        world = self.scene.world_matrices(pose)
        joint_matrices, parts = {}, []
        for primitive in self.scene.primitives:
            points = primitive.positions
            weights = pose.weights.get(primitive.node)
            if primitive.targets is not None and weights is not None and np.any(weights):
                points = points + np.einsum("t,tvi->vi", weights, primitive.targets)
            if primitive.skin is None:
                parts.append(_transform(world[primitive.node], points))
                continue
            if primitive.skin not in joint_matrices:
                joint_matrices[primitive.skin] = self._joint_matrices(primitive.skin, world)
            skinned = linear_blend_skinning(points, primitive.joints, primitive.weights, joint_matrices[primitive.skin])
            unweighted = ~primitive.weights.any(axis=1)  # no joint: the vertex follows its node
            skinned[unweighted] = _transform(world[primitive.node], points[unweighted])
            parts.append(skinned)
        return np.concatenate(parts)

    def static_positions(self) -> np.ndarray:
        """The file's positions as trimesh loads them: rest positions moved by each node's world
        matrix, without morph targets or skins (what ``uvfeat.load`` gives)."""
        world = self.scene.world_matrices(self.scene.rest)
        return np.concatenate([_transform(world[p.node], p.positions) for p in self.scene.primitives])

    def match(self, positions) -> None:
        """Orders the primitives like ``positions`` (a loaded mesh's), or raises AnimationError."""
        positions = np.asarray(positions, dtype=np.float64)
        world = self.scene.world_matrices(self.scene.rest)
        tolerance = 1e-6 * max(1.0, float(np.abs(positions).max(initial=0.0)))
        left, ordered, offset = list(self.scene.primitives), [], 0
        while left:
            for primitive in left:
                count = len(primitive.positions)
                block = positions[offset:offset + count]
                if len(block) == count and np.allclose(_transform(world[primitive.node], primitive.positions), block,
                                                       rtol=0.0, atol=tolerance):
                    break
            else:
                raise AnimationError(f"{self.name}: the mesh's vertices from {offset} on match no primitive of the "
                                     f"file (it has {self.n_vertices} vertices, the mesh {len(positions)}); load the "
                                     "mesh with uvfeat.load from the same file")
            left.remove(primitive)
            ordered.append(primitive)
            offset += count
        if offset != len(positions):
            raise AnimationError(f"{self.name} animates {offset} vertices, the mesh has {len(positions)}")
        self.scene.primitives = ordered
