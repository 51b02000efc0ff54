"""Writes small animated glTF/GLB files from NumPy arrays, for the animation tests and benchmark.

Written from the JSON layout of the glTF 2.0 spec directly (not through pygltflib, which reads
them), so the reader is checked against an independent writer.
"""

from __future__ import annotations

import base64
import json
import struct

import numpy as np

FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT = 5126, 5121, 5123, 5125
_TYPES = {1: "SCALAR", 2: "VEC2", 3: "VEC3", 4: "VEC4", 16: "MAT4"}
_DTYPES = {FLOAT: "<f4", UNSIGNED_BYTE: "<u1", UNSIGNED_SHORT: "<u2", UNSIGNED_INT: "<u4"}


def per_vertex_uvs(mesh):
    """Positions, faces and per-vertex UVs of a uvfeat Mesh with per-corner UVs: one glTF vertex
    per distinct (vertex, uv) pair, as glTF stores seams."""
    pairs = np.stack([mesh.faces.reshape(-1), mesh.uv_faces.reshape(-1)], axis=1)
    unique, corners = np.unique(pairs, axis=0, return_inverse=True)
    return mesh.positions[unique[:, 0]], corners.reshape(-1, 3), mesh.uvs[unique[:, 1]]


class GltfBuilder:
    """Accumulates a glTF document and one binary buffer; ``save`` writes .glb or .gltf."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                    "accessors": [], "bufferViews": [], "materials": [{"name": "plain"}]}
        self.blob = bytearray()

    def _view(self, data: bytes) -> int:
        self.blob.extend(b"\0" * (-len(self.blob) % 4))
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)})
        self.blob.extend(data)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, array, component: int = FLOAT, normalized: bool = False) -> int:
        """An accessor of ``(count, width)`` values (``(count, 4, 4)`` matrices, stored by column)."""
        array = np.asarray(array)
        if array.ndim == 3:
            array = np.swapaxes(array, 1, 2).reshape(len(array), 16)
        array = array.reshape(len(array), -1)
        data = np.ascontiguousarray(array, dtype=_DTYPES[component])
        accessor = {"bufferView": self._view(data.tobytes()), "componentType": component, "count": len(array),
                    "type": _TYPES[array.shape[1]]}
        if normalized:
            accessor["normalized"] = True
        if component == FLOAT and array.shape[1] == 3:  # POSITION accessors must carry min and max
            accessor["min"], accessor["max"] = data.min(axis=0).tolist(), data.max(axis=0).tolist()
        self.doc["accessors"].append(accessor)
        return len(self.doc["accessors"]) - 1

    def sparse_accessor(self, count: int, indices, values) -> int:
        """A VEC3 accessor of ``count`` zeros except ``values`` at ``indices`` (no base buffer view)."""
        values = np.asarray(values, dtype="<f4").reshape(-1, 3)
        self.doc["accessors"].append({
            "componentType": FLOAT, "count": count, "type": "VEC3",
            "sparse": {"count": len(values),
                       "indices": {"bufferView": self._view(np.asarray(indices, "<u4").tobytes()),
                                   "componentType": UNSIGNED_INT},
                       "values": {"bufferView": self._view(values.tobytes())}}})
        return len(self.doc["accessors"]) - 1

    def primitive(self, positions, faces, uvs, targets=(), joints=None, weights=None,
                  weight_component: int = FLOAT) -> dict:
        """A triangle primitive; ``targets`` are morph-target accessors or offset arrays."""
        flipped = np.asarray(uvs) * [1.0, -1.0] + [0.0, 1.0]  # glTF's v points down; trimesh flips it back
        attributes = {"POSITION": self.accessor(positions), "TEXCOORD_0": self.accessor(flipped)}
        if joints is not None:
            attributes["JOINTS_0"] = self.accessor(joints, UNSIGNED_SHORT)
            scale = {FLOAT: 1.0, UNSIGNED_BYTE: 255.0, UNSIGNED_SHORT: 65535.0}[weight_component]
            attributes["WEIGHTS_0"] = self.accessor(np.round(np.asarray(weights) * scale) if scale > 1 else weights,
                                                    weight_component, normalized=scale > 1)
        primitive = {"attributes": attributes, "indices": self.accessor(np.asarray(faces).reshape(-1), UNSIGNED_INT),
                     "material": 0}
        if len(targets):
            primitive["targets"] = [{"POSITION": t if isinstance(t, int) else self.accessor(t)} for t in targets]
        return primitive

    def mesh(self, primitives: list[dict], weights=None) -> int:
        self.doc["meshes"].append({"primitives": primitives, **({"weights": list(weights)} if weights else {})})
        return len(self.doc["meshes"]) - 1

    def node(self, root: bool = False, **fields) -> int:
        """A node with glTF fields (mesh, skin, translation, rotation, scale, matrix, children, weights)."""
        node = {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in fields.items() if v is not None}
        self.doc["nodes"].append(node)
        index = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def skin(self, joints: list[int], inverse_bind) -> int:
        self.doc.setdefault("skins", []).append({"joints": joints, "inverseBindMatrices": self.accessor(inverse_bind)})
        return len(self.doc["skins"]) - 1

    def animation(self, name: str, channels) -> int:
        """``channels``: ``(node, path, times, values, interpolation)`` tuples."""
        samplers, targets = [], []
        for node, path, times, values, interpolation in channels:
            samplers.append({"input": self.accessor(np.asarray(times, dtype=float)),
                             "output": self.accessor(np.asarray(values, dtype=float)),
                             "interpolation": interpolation})
            targets.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": path}})
        self.doc.setdefault("animations", []).append({"name": name, "samplers": samplers, "channels": targets})
        return len(self.doc["animations"]) - 1

    def save(self, path) -> str:
        """Writes ``path`` (.glb: binary container; .gltf: the buffer as a base64 data URI)."""
        path = str(path)
        buffer = {"byteLength": len(self.blob)}
        if path.endswith(".gltf"):
            buffer["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.blob)).decode()
            with open(path, "w") as f:
                json.dump(dict(self.doc, buffers=[buffer]), f)
            return path
        text = json.dumps(dict(self.doc, buffers=[buffer])).encode()
        text += b" " * (-len(text) % 4)
        binary = bytes(self.blob) + b"\0" * (-len(self.blob) % 4)
        chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(binary), b"BIN\0") + binary
        with open(path, "wb") as f:
            f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks)
        return path
