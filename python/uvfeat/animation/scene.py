"""The static side of a glTF scene: node hierarchy, local TRS transforms, world matrices and the
triangle primitives drawn by nodes (with their morph targets and skin attributes).

Primitives are listed in the order in which ``uvfeat.load`` (through trimesh) concatenates them:
trimesh walks the scene graph depth first from the scene's root nodes, taking the last pushed
node next, and gives every primitive of a node's mesh its own part.
"""

from __future__ import annotations

from dataclasses import dataclass, field as dataclass_field

import numpy as np

from ..errors import AnimationError
from .accessors import Accessors, field

#: Primitive modes trimesh loads as triangle meshes (TRIANGLES, TRIANGLE_STRIP).
TRIANGLE_MODES = (4, 5)


def quaternion_matrix(q) -> np.ndarray:
    """3x3 rotation of a unit quaternion ``(x, y, z, w)`` (glTF order); normalised first."""
    x, y, z, w = np.asarray(q, dtype=np.float64) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def trs_matrix(translation, rotation, scale) -> np.ndarray:
    """4x4 ``T @ R @ S`` (the glTF order of a node's local transform)."""
    matrix = np.eye(4)
    matrix[:3, :3] = quaternion_matrix(rotation) * np.asarray(scale, dtype=np.float64)[None, :]
    matrix[:3, 3] = translation
    return matrix


@dataclass
class Pose:
    """Local transforms of every node: TRS parts (animatable) or a fixed matrix, plus morph weights."""

    translation: dict[int, np.ndarray]
    rotation: dict[int, np.ndarray]
    scale: dict[int, np.ndarray]
    matrix: dict[int, np.ndarray]
    weights: dict[int, np.ndarray]

    def copy(self) -> Pose:
        return Pose(*({k: v.copy() for k, v in part.items()} for part in
                      (self.translation, self.rotation, self.scale, self.matrix, self.weights)))

    def local(self, node: int) -> np.ndarray:
        if node in self.matrix:
            return self.matrix[node]
        return trs_matrix(self.translation[node], self.rotation[node], self.scale[node])


@dataclass
class Primitive:
    """One triangle primitive drawn by one node: rest positions ``(V, 3)``, morph-target position
    offsets ``(T, V, 3)`` and, when skinned, joints and weights ``(V, 4k)``."""

    node: int
    mesh: int
    index: int
    positions: np.ndarray
    targets: np.ndarray | None = None
    skin: int | None = None
    joints: np.ndarray | None = None
    weights: np.ndarray | None = dataclass_field(default=None, repr=False)


class SceneGraph:
    """Nodes, hierarchy and drawn primitives of a parsed glTF file (``pygltflib.GLTF2``)."""

    def __init__(self, gltf, accessors: Accessors, name: str):
        self.gltf, self.name, self._read = gltf, name, accessors
        self.parent: dict[int, int] = {}
        for index, node in enumerate(gltf.nodes):
            for child in node.children or []:
                if not 0 <= child < len(gltf.nodes):
                    raise AnimationError(f"{name}: node {index} has a child {child} that does not exist")
                self.parent[child] = index
        self.roots = self._scene_roots()
        self.order = self._parents_first()
        self.rest = self._rest_pose()
        self.primitives = self._drawn_primitives()

    def _scene_roots(self) -> list[int]:
        if not self.gltf.scenes:
            return [n for n in range(len(self.gltf.nodes)) if n not in self.parent]
        scene = self.gltf.scene if self.gltf.scene is not None else 0
        return list(self.gltf.scenes[scene].nodes or [])

    def _parents_first(self) -> list[int]:
        """Every node after its parent: the scene's trees first, then nodes outside the scene (a
        skin's joints may hang there)."""
        outside = [n for n in range(len(self.gltf.nodes)) if n not in self.parent and n not in self.roots]
        order, stack, seen = [], list(reversed(self.roots + outside)), set()
        while stack:
            node = stack.pop()
            if node in seen:
                raise AnimationError(f"{self.name}: node {node} is reached twice; the node hierarchy must be a tree")
            seen.add(node)
            order.append(node)
            stack.extend(reversed(self.gltf.nodes[node].children or []))
        return order

    def _rest_pose(self) -> Pose:
        pose = Pose({}, {}, {}, {}, {})
        for index, node in enumerate(self.gltf.nodes):
            if node.matrix is not None:
                pose.matrix[index] = np.asarray(node.matrix, dtype=np.float64).reshape(4, 4).T
            pose.translation[index] = np.asarray(node.translation or (0.0, 0.0, 0.0), dtype=np.float64)
            pose.rotation[index] = np.asarray(node.rotation or (0.0, 0.0, 0.0, 1.0), dtype=np.float64)
            pose.scale[index] = np.asarray(node.scale or (1.0, 1.0, 1.0), dtype=np.float64)
            if node.mesh is not None:
                count = self.morph_target_count(node.mesh)
                weights = field(node, "weights") or self.gltf.meshes[node.mesh].weights or [0.0] * count
                if len(weights) != count:
                    raise AnimationError(f"{self.name}: node {index} has {len(weights)} default morph weights for "
                                         f"{count} morph targets")
                pose.weights[index] = np.asarray(weights, dtype=np.float64)
        return pose

    def morph_target_count(self, mesh: int) -> int:
        counts = {len(p.targets or []) for p in self.gltf.meshes[mesh].primitives}
        if len(counts) > 1:
            raise AnimationError(f"{self.name}: the primitives of mesh {mesh} have different numbers of morph "
                                 f"targets {sorted(counts)}; glTF requires the same number")
        return counts.pop() if counts else 0

    def world_matrices(self, pose: Pose) -> dict[int, np.ndarray]:
        """World matrix of every node of the scene under ``pose``."""
        world = {}
        for node in self.order:
            parent = self.parent.get(node)
            local = pose.local(node)
            world[node] = local if parent is None or parent not in world else world[parent] @ local
        return world

    def _trimesh_node_order(self) -> list[int]:
        """Mesh nodes in the order trimesh's glTF loader adds them (see the module docstring)."""
        queue, consumed, out = [(None, root) for root in self.roots], set(), []
        while queue:
            edge = queue.pop()
            if edge in consumed:
                continue
            consumed.add(edge)
            node = edge[1]
            queue.extend((node, child) for child in self.gltf.nodes[node].children or [])
            if self.gltf.nodes[node].mesh is not None:
                out.append(node)
        return out

    def _drawn_primitives(self) -> list[Primitive]:
        out = []
        for node in self._trimesh_node_order():
            mesh = self.gltf.nodes[node].mesh
            for index, primitive in enumerate(self.gltf.meshes[mesh].primitives):
                if (primitive.mode if primitive.mode is not None else 4) in TRIANGLE_MODES:
                    out.append(self._primitive(node, mesh, index, primitive))
        return out

    def _primitive(self, node: int, mesh: int, index: int, primitive) -> Primitive:
        what = f"{self.name}: mesh {mesh} primitive {index}"
        if field(primitive, "extensions"):
            compressed = [e for e in primitive.extensions if "compression" in e.lower()]
            if compressed:
                raise AnimationError(f"{what} is compressed ({', '.join(compressed)}); animation needs plain "
                                     "accessors (decompress the file first, e.g. with gltf-transform)")
        attributes = primitive.attributes
        positions = self._read(field(attributes, "POSITION"))
        targets = None
        if primitive.targets:
            offsets = [field(t, "POSITION") for t in primitive.targets]
            targets = np.stack([np.zeros_like(positions) if a is None else self._read(a) for a in offsets])
            if targets.shape[1:] != positions.shape:
                raise AnimationError(f"{what}: morph targets have {targets.shape[1]} vertices, the primitive "
                                     f"{len(positions)}")
        out = Primitive(node, mesh, index, positions, targets)
        skin = self.gltf.nodes[node].skin
        if skin is not None:
            joints, weights = self._skin_attributes(attributes, len(positions), what)
            if joints.size and joints.max() >= len(self.gltf.skins[skin].joints):
                raise AnimationError(f"{what}: joint index {int(joints.max())} is beyond the "
                                     f"{len(self.gltf.skins[skin].joints)} joints of skin {skin}")
            out.skin, out.joints, out.weights = skin, joints, weights
        return out

    def _skin_attributes(self, attributes, count: int, what: str) -> tuple[np.ndarray, np.ndarray]:
        """Joint indices and weights of every set (JOINTS_n/WEIGHTS_n), side by side; weights are
        rescaled to sum to 1 (quantised weights only add up approximately)."""
        joints, weights, n = [], [], 0
        while field(attributes, f"JOINTS_{n}") is not None and field(attributes, f"WEIGHTS_{n}") is not None:
            joints.append(self._read(field(attributes, f"JOINTS_{n}")).astype(np.int64).reshape(count, -1))
            weights.append(self._read(field(attributes, f"WEIGHTS_{n}")).astype(np.float64).reshape(count, -1))
            n += 1
        if not joints:
            raise AnimationError(f"{what} is skinned but has no JOINTS_0/WEIGHTS_0 attributes")
        joints, weights = np.concatenate(joints, axis=1), np.concatenate(weights, axis=1)
        total = weights.sum(axis=1, keepdims=True)
        return joints, np.divide(weights, total, out=np.zeros_like(weights), where=total > 0)
