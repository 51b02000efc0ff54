"""glTF 2.0 binary data as NumPy arrays: buffers, buffer views and accessors (strided, sparse,
normalised integers). pygltflib parses the JSON and the GLB container; decoding the accessors into
arrays is this module."""

from __future__ import annotations

import json
import os
import struct

import numpy as np

from ..errors import AnimationError, MeshFileError

#: glTF componentType -> little-endian NumPy dtype.
COMPONENT_DTYPES = {5120: "<i1", 5121: "<u1", 5122: "<i2", 5123: "<u2", 5125: "<u4", 5126: "<f4"}

#: glTF accessor type -> shape of one element.
ELEMENT_SHAPES = {"SCALAR": (), "VEC2": (2,), "VEC3": (3,), "VEC4": (4,), "MAT2": (2, 2), "MAT3": (3, 3),
                  "MAT4": (4, 4)}


def field(item, name: str, default=None):
    """An attribute of a pygltflib object, or a key of a plain dict (pygltflib leaves morph
    targets and some extension data as dicts)."""
    if isinstance(item, dict):
        return item.get(name, default)
    value = getattr(item, name, default)
    return default if value is None else value


def read_gltf(path: str):
    """The parsed glTF/GLB file (a ``pygltflib.GLTF2``), with a clear error when it is broken.

    pygltflib's ``Node`` has no ``weights`` (a node's default morph weights), so they are read
    from the file's JSON and set on the nodes here."""
    import pygltflib

    try:
        gltf = pygltflib.GLTF2().load(os.fspath(path))
        nodes = _json_of(path).get("nodes", [])
    except Exception as exc:  # pygltflib raises JSON, struct and key errors for broken files
        raise MeshFileError(f"cannot read the glTF file {path!r}: {exc}") from exc
    if gltf is None:
        raise MeshFileError(f"cannot read the glTF file {path!r}: no JSON chunk")
    for node, raw in zip(gltf.nodes, nodes):
        node.weights = raw.get("weights")
    return gltf


def _json_of(path: str) -> dict:
    """The JSON document of a .gltf file, or of the first chunk of a .glb (binary glTF §4.4)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"glTF":
        return json.loads(data)
    length, kind = struct.unpack_from("<I4s", data, 12)
    if kind != b"JSON":
        raise ValueError("the first GLB chunk is not JSON")
    return json.loads(data[20:20 + length])


class Accessors:
    """Decodes the accessors of one glTF file, each once."""

    def __init__(self, gltf, name: str):
        self._gltf = gltf
        self._name = name
        self._buffers: dict[int, bytes] = {}
        self._cache: dict[int, np.ndarray] = {}

    def _buffer(self, index: int) -> bytes:
        if index not in self._buffers:
            buffer = self._gltf.buffers[index]
            data = self._gltf.get_data_from_buffer_uri(buffer.uri)
            if data is None or len(data) < (buffer.byteLength or 0):
                raise MeshFileError(f"{self._name}: buffer {index} ({buffer.uri or 'GLB chunk'}) is missing or "
                                    f"shorter than its {buffer.byteLength} bytes")
            self._buffers[index] = data
        return self._buffers[index]

    def _view(self, index: int, offset: int, dtype: np.dtype, shape: tuple, count: int) -> np.ndarray:
        """``count`` elements of ``shape`` from buffer view ``index``, honouring its byte stride."""
        view = self._gltf.bufferViews[index]
        compressed = [name for name in field(view, "extensions", {}) if "compression" in name.lower()]
        if compressed:
            raise AnimationError(f"{self._name}: buffer view {index} is compressed ({', '.join(compressed)}); "
                                 "decompress the file first (e.g. gltf-transform copy)")
        data = self._buffer(view.buffer)
        start = (view.byteOffset or 0) + (offset or 0)
        width = int(np.prod(shape, dtype=np.int64)) * dtype.itemsize
        stride = view.byteStride or width
        needed = (count - 1) * stride + width if count else 0
        if start + needed > (view.byteOffset or 0) + view.byteLength or start + needed > len(data):
            raise MeshFileError(f"{self._name}: an accessor reads past the end of buffer view {index}")
        rows = np.lib.stride_tricks.as_strided(np.frombuffer(data, np.uint8, needed, start),
                                               (count, width), (stride, 1)) if count else np.zeros((0, width), np.uint8)
        return np.ascontiguousarray(rows).view(dtype).reshape((count,) + shape)

    def __call__(self, index: int) -> np.ndarray:
        """Accessor ``index`` as float64 ``(count, *element_shape)`` (integers kept as int64 unless
        normalised); matrices are returned row-major (``M[i, j]``: row i, column j)."""
        if index in self._cache:
            return self._cache[index]
        if index is None or not 0 <= index < len(self._gltf.accessors):
            raise AnimationError(f"{self._name}: accessor {index} does not exist")
        accessor = self._gltf.accessors[index]
        dtype = np.dtype(COMPONENT_DTYPES[accessor.componentType])
        shape = ELEMENT_SHAPES[accessor.type]
        if accessor.bufferView is None:
            values = np.zeros((accessor.count,) + shape, dtype)
        else:
            values = self._view(accessor.bufferView, accessor.byteOffset, dtype, shape, accessor.count).copy()
        sparse = accessor.sparse
        if sparse is not None and sparse.count:
            indices = self._view(sparse.indices.bufferView, sparse.indices.byteOffset,
                                 np.dtype(COMPONENT_DTYPES[sparse.indices.componentType]), (), sparse.count)
            values[indices.astype(np.int64)] = self._view(sparse.values.bufferView, sparse.values.byteOffset, dtype,
                                                          shape, sparse.count)
        if len(shape) == 2:
            values = np.swapaxes(values, 1, 2)  # glTF stores matrices column by column
        self._cache[index] = _as_numbers(values, bool(accessor.normalized))
        return self._cache[index]


def _as_numbers(values: np.ndarray, normalized: bool) -> np.ndarray:
    """float64 values; normalised integers mapped to [0, 1] or [-1, 1] as the glTF spec says."""
    if values.dtype.kind == "f":
        return values.astype(np.float64)
    if not normalized:
        return values.astype(np.int64)
    top = float(np.iinfo(values.dtype).max)
    return np.maximum(values.astype(np.float64) / top, -1.0)
