"""Bakes: a feature written the way other tools read it. A texture on the mesh's own UVs with its
gutters dilated (16-bit PNG, float32 TIFF, and an 8-bit curvature map centred on 0.5 grey), GLB
files coloured per vertex and by the texture, and a PLY whose ``quality`` property MeshLab reads
(and Blender imports as an attribute). ``pip install 'uvfeat[bake]'`` brings SciPy (the
dilation) and tifffile."""

from __future__ import annotations

import json
import os

import numpy as np

from .images import SIGNED_FEATURES, colour_range, colour_values
from .mesh import Mesh

#: 16-bit PNG levels.
LEVELS_16 = 65535


def _average_into_first_ring(texture: np.ndarray) -> np.ndarray:
    """Empty texels next to filled ones set to the mean of their filled 8-neighbours: close to the
    chart-masked bilinear lookup behind ``FeatureMap.per_vertex``, which renormalises over the
    filled texels of a footprint (nearest-texel values alone bias corners at chart borders)."""
    filled = np.isfinite(texture)
    height, width = texture.shape
    values, counts = np.pad(np.where(filled, texture, 0.0), 1), np.pad(filled.astype(np.float64), 1)
    shifts = [(dj, di) for dj in range(3) for di in range(3)]
    total = sum(values[dj:dj + height, di:di + width] for dj, di in shifts)
    count = sum(counts[dj:dj + height, di:di + width] for dj, di in shifts)
    ring = ~filled & (count > 0)
    out = texture.copy()
    out[ring] = total[ring] / count[ring]
    return out


def dilate(texture: np.ndarray) -> np.ndarray:
    """The texture with every empty (NaN) texel filled: the first ring around the charts by the
    mean of its filled neighbours, the rest by the nearest filled texel, so bilinear and
    mip-mapped filtering near a chart's border never reach an empty texel (no dark seams)."""
    from .extras import require

    ndimage = require("scipy.ndimage", "dilating texture gutters")
    if not np.isfinite(texture).any():
        return np.zeros_like(texture)
    texture = _average_into_first_ring(texture)
    nearest = ndimage.distance_transform_edt(~np.isfinite(texture), return_distances=False, return_indices=True)
    return texture[nearest[0], nearest[1]]


def sample_bilinear(texture: np.ndarray, uvs: np.ndarray) -> np.ndarray:
    """Bilinear lookup of a ``(W, W)`` texture (``[j, i]``, v up, texel centres at ``(i + 0.5)/W``)
    at ``(n, 2)`` UVs, clamped at the edges, as a GPU samples it."""
    size = np.array(texture.shape[::-1], dtype=np.float64)
    x = np.clip(uvs * size - 0.5, 0.0, size - 1.0)
    low = np.minimum(np.floor(x).astype(np.int64), (size - 2).astype(np.int64).clip(0))
    t = x - low
    i0, j0 = low[:, 0], low[:, 1]
    i1, j1 = np.minimum(i0 + 1, texture.shape[1] - 1), np.minimum(j0 + 1, texture.shape[0] - 1)
    return ((1 - t[:, 0]) * (1 - t[:, 1]) * texture[j0, i0] + t[:, 0] * (1 - t[:, 1]) * texture[j0, i1]
            + (1 - t[:, 0]) * t[:, 1] * texture[j1, i0] + t[:, 0] * t[:, 1] * texture[j1, i1])


def _png_text(fields: dict):
    from PIL.PngImagePlugin import PngInfo

    info = PngInfo()
    for key, value in fields.items():
        info.add_text(key, str(value))
    return info


def write_png16(path: str, texture: np.ndarray, low: float, high: float, fields: dict) -> None:
    """16-bit grey PNG (v up) of ``texture`` mapped linearly from ``[low, high]`` to ``[0, 65535]``;
    the range is in the PNG's text chunks (``uvfeat.low``, ``uvfeat.high``) to map it back."""
    from PIL import Image

    span = high - low if high > low else 1.0
    levels = np.round(np.clip((texture - low) / span, 0.0, 1.0) * LEVELS_16).astype(np.uint16)
    Image.fromarray(np.flipud(levels)).save(path, pnginfo=_png_text(dict(fields, **{"uvfeat.low": repr(low),
                                                                                  "uvfeat.high": repr(high)})))


def write_curvature_png(path: str, texture: np.ndarray, bound: float, fields: dict) -> None:
    """8-bit grey curvature map: 128 is 0, 255 is ``+bound`` (convex), 1 is ``-bound``
    (concave); ``uvfeat.scale`` in the text chunks is the value of one grey level."""
    from PIL import Image

    grey = np.round(128.0 + 127.0 * np.clip(texture / bound, -1.0, 1.0)).astype(np.uint8)
    Image.fromarray(np.flipud(grey)).save(path, pnginfo=_png_text(dict(fields, **{"uvfeat.scale": repr(bound / 127.0),
                                                                                "uvfeat.bound": repr(bound)})))


def write_float_tiff(path: str, texture: np.ndarray, fields: dict) -> None:
    """float32 TIFF (v up) with the metadata as JSON in the image description."""
    from .extras import require

    tifffile = require("tifffile", "writing float TIFF")
    tifffile.imwrite(path, np.flipud(texture).astype(np.float32), description=json.dumps(fields))


def split_by_uv(mesh: Mesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vertices split where their UVs differ (as glTF needs one UV per vertex): positions'
    source vertex per new vertex, its UV and the new faces."""
    pairs = np.stack([mesh.faces.ravel(), mesh.uv_faces.ravel()], axis=1)
    unique, inverse = np.unique(pairs, axis=0, return_inverse=True)
    return unique[:, 0], mesh.uvs[unique[:, 1]], inverse.reshape(-1, 3)


def write_glbs(out: str, stem: str, mesh: Mesh, per_vertex: np.ndarray, colour_texture: np.ndarray,
               cmap: str, low: float, high: float) -> dict[str, str]:
    """``<stem>_colours.glb`` (the feature as vertex colours, COLOR_0) and ``<stem>_texture.glb``
    (as a base-colour texture on the mesh's UVs); two files because glTF multiplies the two."""
    import trimesh
    from PIL import Image

    source, uvs, faces = split_by_uv(mesh)
    rgba = np.full((len(source), 4), 255, dtype=np.uint8)
    rgba[:, :3] = np.round(colour_values(per_vertex[source], cmap, low, high) * 255).astype(np.uint8)
    coloured = trimesh.Trimesh(mesh.positions[source], faces, vertex_colors=rgba, process=False)
    material = trimesh.visual.material.PBRMaterial(baseColorTexture=Image.fromarray(colour_texture), metallicFactor=0.0,
                                                   roughnessFactor=1.0)
    textured = trimesh.Trimesh(mesh.positions[source], faces, process=False,
                               visual=trimesh.visual.TextureVisuals(uv=uvs, material=material))
    paths = {"colours": os.path.join(out, f"{stem}_colours.glb"), "texture": os.path.join(out, f"{stem}_texture.glb")}
    coloured.export(paths["colours"])
    textured.export(paths["texture"])
    return paths


def bake_feature(out: str, stem: str, mesh: Mesh, name: str, texture: np.ndarray, per_vertex: np.ndarray,
                 radius: float) -> dict[str, str]:
    """Writes every bake of one feature at one radius; returns the paths by kind."""
    from PIL import Image

    filled = dilate(texture)
    finite = texture[np.isfinite(texture)]
    low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    fields = {"uvfeat.feature": name, "uvfeat.radius": repr(float(radius))}
    paths = {"png16": os.path.join(out, f"{stem}.png"), "tiff": os.path.join(out, f"{stem}.tif")}
    write_png16(paths["png16"], filled, low, high, fields)
    write_float_tiff(paths["tiff"], filled, dict(fields, empty_texels_dilated=int((~np.isfinite(texture)).sum())))
    cmap, robust_low, robust_high = colour_range(name, texture)
    if name in SIGNED_FEATURES:
        paths["curvature"] = os.path.join(out, f"{stem}_curvature.png")
        write_curvature_png(paths["curvature"], filled, max(abs(robust_low), abs(robust_high)), fields)
    colour_texture = np.flipud(np.round(colour_values(filled, cmap, robust_low, robust_high) * 255).astype(np.uint8))
    paths["colour_texture"] = os.path.join(out, f"{stem}_colour.png")
    Image.fromarray(colour_texture).save(paths["colour_texture"])
    paths.update(write_glbs(out, stem, mesh, per_vertex, colour_texture, cmap, robust_low, robust_high))
    return paths
