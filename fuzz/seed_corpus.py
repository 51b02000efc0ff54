"""Writes the loaders' seed corpus (fuzz/corpus/loaders): a small UV-mapped torus in every format
``uvfeat.load`` reads, each prefixed with the byte that makes fuzz_loaders.py pick its format."""

from __future__ import annotations

import io
import os

import numpy as np
import trimesh

import uvfeat

FOLDER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus", "loaders")


def torus() -> trimesh.Trimesh:
    shape = uvfeat.shapes.torus(2.0, 0.5, 8, 4)
    corners = shape.faces.reshape(-1)
    uv = shape.uvs[shape.uv_faces.reshape(-1)]
    return trimesh.Trimesh(shape.positions[corners], np.arange(len(corners)).reshape(-1, 3),
                           visual=trimesh.visual.TextureVisuals(uv=uv), process=False)


def main() -> None:
    os.makedirs(FOLDER, exist_ok=True)
    mesh = torus()
    for index, extension in enumerate(uvfeat.io.SUPPORTED_FORMATS):
        exported = mesh.export(file_type=extension)
        if isinstance(exported, dict):  # glTF: the JSON with its buffer embedded
            exported = exported["model.gltf"]
        if isinstance(exported, str):
            exported = exported.encode()
        with open(os.path.join(FOLDER, f"torus.{extension}"), "wb") as file:
            file.write(bytes([index]) + exported)


if __name__ == "__main__":
    main()
