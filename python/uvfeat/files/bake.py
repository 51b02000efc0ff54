"""Bakes: a feature written the way other tools read it. A texture on the mesh's own UVs with its
gutters fitted and dilated (16-bit PNG, float32 TIFF, and an 8-bit curvature map centred on 0.5 grey), GLB
files coloured per vertex and by the texture, and a PLY whose ``quality`` property MeshLab reads
(and Blender imports as an attribute). ``pip install 'uvfeat[bake]'`` brings SciPy (the
dilation) and tifffile. :func:`bake` writes them all for a mesh; ``uvfeat bake`` is its command."""

from __future__ import annotations

import json
import os

import numpy as np

from .._core import __version__
from ..pictures.images import SIGNED_FEATURES, colour_range, colour_values
from ..mesh import Mesh

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
    from ..extras import require

    ndimage = require("scipy.ndimage", "dilating texture gutters")
    if not np.isfinite(texture).any():
        return np.zeros_like(texture)
    texture = _average_into_first_ring(texture)
    nearest = ndimage.distance_transform_edt(~np.isfinite(texture), return_distances=False, return_indices=True)
    return texture[nearest[0], nearest[1]]


def bilinear_footprints(shape: tuple[int, ...], uvs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The 2 x 2 texels a GPU's bilinear filter reads at each of ``(n, 2)`` UVs of a ``shape``
    texture (``[j, i]``, v up, texel centres at ``(i + 0.5)/W``, clamped at the edges): flat texel
    indices ``(n, 4)`` and their weights ``(n, 4)``."""
    height, width = shape
    size = np.array([width, height], dtype=np.float64)
    x = np.clip(uvs * size - 0.5, 0.0, size - 1.0)
    low = np.minimum(np.floor(x).astype(np.int64), (size - 2).astype(np.int64).clip(0))
    t = x - low
    i0, j0 = low[:, 0], low[:, 1]
    i1, j1 = np.minimum(i0 + 1, width - 1), np.minimum(j0 + 1, height - 1)
    texels = np.stack([j0 * width + i0, j0 * width + i1, j1 * width + i0, j1 * width + i1], axis=1)
    weights = np.stack([(1 - t[:, 0]) * (1 - t[:, 1]), t[:, 0] * (1 - t[:, 1]), (1 - t[:, 0]) * t[:, 1],
                        t[:, 0] * t[:, 1]], axis=1)
    return texels, weights


def sample_bilinear(texture: np.ndarray, uvs: np.ndarray) -> np.ndarray:
    """Bilinear lookup of a ``(W, W)`` texture at ``(n, 2)`` UVs as a GPU samples it (see
    :func:`bilinear_footprints`)."""
    texels, weights = bilinear_footprints(texture.shape, uvs)
    return (texture.reshape(-1)[texels] * weights).sum(axis=1)


def fit_gutters(texture: np.ndarray, uvs: np.ndarray, values: np.ndarray, smoothness: float = 1e-3) -> np.ndarray:
    """The texture with the empty texels that the corners' bilinear footprints reach set so that a
    renderer's read at each corner UV ``uvs`` gives its value ``values`` (least squares: where
    several corners share an empty texel it takes their best compromise; a weak pull towards the
    mean of its filled neighbours settles what the corners leave free). Filled texels are kept.

    The values are :meth:`FeatureMap.corner_values` (for a texture interpolated from the vertices,
    each corner's vertex value: :func:`vertex_corners`): the chart-masked lookup renormalises over
    the filled texels of a footprint, which no single gutter value reproduces for every corner, so
    a plain dilation left seam vertices a few % of the range off (``tests/test_bake.py``)."""
    from ..extras import require

    sparse = require("scipy.sparse", "fitting texture gutters")
    linalg = require("scipy.sparse.linalg", "fitting texture gutters")
    texels, weights = bilinear_footprints(texture.shape, uvs)
    flat = texture.reshape(-1).astype(np.float64)
    empty = ~np.isfinite(flat[texels]) & (weights > 0)
    rows = np.flatnonzero(empty.any(axis=1) & np.isfinite(values))
    if len(rows) == 0:
        return texture
    empty, texels, weights = empty[rows], texels[rows], weights[rows]
    unknown, column = np.unique(texels[empty], return_inverse=True)
    known = np.where(empty, 0.0, weights * np.nan_to_num(flat[texels])).sum(axis=1)
    corner_of = np.repeat(np.arange(len(rows)), empty.sum(axis=1))
    fit = sparse.csr_matrix((weights[empty], (corner_of, column.ravel())), shape=(len(rows), len(unknown)))
    prior = _average_into_first_ring(texture).reshape(-1)[unknown]
    prior = np.where(np.isfinite(prior), prior, float(np.nanmean(values[rows])))
    system = sparse.vstack([fit, smoothness * sparse.identity(len(unknown), format="csr")])
    rhs = np.concatenate([values[rows] - known, smoothness * prior])
    solution = linalg.lsqr(system, rhs, atol=1e-12, btol=1e-12, iter_lim=20 * len(unknown))[0]
    out = flat.copy()
    # Within the charts' range widened by twice it on each side: renormalised footprints need some
    # extrapolation (Spot's seams need more than half the range beyond it), but a corner that
    # weighs an empty texel little (its footprint mostly on another chart's texels) could push it
    # ten ranges out, and the texture's range with it.
    finite = flat[np.isfinite(flat)]
    if finite.size:
        low, high = float(finite.min()), float(finite.max())
        margin = 2.0 * (high - low)
        solution = np.clip(solution, low - margin, high + margin)
    out[unknown] = solution
    return out.reshape(texture.shape).astype(texture.dtype)


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
    from ..extras import require

    tifffile = require("tifffile", "writing float TIFF")
    tifffile.imwrite(path, np.flipud(texture).astype(np.float32), description=json.dumps(fields))


def split_by_uv(mesh: Mesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vertices split where their UVs differ (as glTF needs one UV per vertex): positions'
    source vertex per new vertex, its UV and the new faces."""
    pairs = np.stack([mesh.faces.ravel(), mesh.uv_faces.ravel()], axis=1)
    unique, inverse = np.unique(pairs, axis=0, return_inverse=True)
    return unique[:, 0], mesh.uvs[unique[:, 1]], inverse.reshape(-1, 3)


def vertex_corners(mesh: Mesh, per_vertex: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every distinct (vertex, UV) corner of ``mesh``: its UV and its vertex's value, which a
    texture interpolated from the vertices gives there (as :meth:`FeatureMap.corner_values`)."""
    source, uvs, _ = split_by_uv(mesh)
    return uvs, np.asarray(per_vertex, dtype=np.float64)[source]


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
                 radius: float, corners: tuple[np.ndarray, np.ndarray] | None = None) -> dict[str, str]:
    """Writes every bake of one feature at one radius; returns the paths by kind. ``corners`` (the
    map's :meth:`~uvfeat.FeatureMap.corner_values`, or :func:`vertex_corners` for a texture
    interpolated from the vertices) fits the gutters the vertices' footprints reach
    (:func:`fit_gutters`) before the rest is dilated."""
    from PIL import Image

    filled = dilate(texture if corners is None else fit_gutters(texture, *corners))
    # The range of what is written: fitted gutters may reach a little past the charts' values.
    low, high = (float(filled.min()), float(filled.max())) if np.isfinite(texture).any() else (0.0, 1.0)
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


def bake(mesh, features, radius, *, out: str = "uvfeat-out/bake", **options) -> dict:
    """Bakes ``features`` at each radius into textures on the mesh's own UVs and writes them to
    ``out``, as ``uvfeat bake`` does.

    Parameters
    ----------
    mesh
        A :class:`~uvfeat.Mesh` or any of :data:`uvfeat.interop.ACCEPTED`; without UVs (or with
        overlapping ones) it gets an automatic atlas, as :func:`uvfeat.load` gives a file
        (``uv`` option).
    features, radius
        As for ``uvfeat bake``: names (or "all"), one radius or several (a list or "1%,4%").
    out : str
        The folder of the files.
    **options
        ``samples``, ``resolution``, ``compute_resolution``, ``adaptive``, ``paper_mode``, ``seed``,
        ``query``, ``method``, ``sampling``, ``quadrature``, ``surface``, ``standard_error``, ``uv``
        (a mesh's UVs are taken as given: ``strict_uv`` is for files; bakes hold no directions).

    Returns
    -------
    dict
        What ``bake.json`` holds: per radius the files of each feature by kind, the settings and
        the notes.
    """
    from .feature_files import FeatureJob
    from ..interop import as_mesh
    from ..io import with_uv_policy
    from .notes import recorded_notes

    job = FeatureJob.of(features, radius, **options)
    with recorded_notes() as notes:
        mesh = with_uv_policy(as_mesh(mesh), job.uv, job.resolution)
    return write_bakes(mesh, job, out, notes)


def write_bakes(mesh: Mesh, job, out: str, load_notes: list[str], advance=lambda description, done=True: None) -> dict:
    """The work of :func:`bake` and ``uvfeat bake`` on a mesh with UVs; ``advance`` reports each
    step (``1 + 2 n_radii``)."""
    from ..extras import require
    from .feature_files import computed_radii, job_atlases, radius_tag
    from .writers import write_json, write_per_vertex

    require("scipy.ndimage", "dilating texture gutters")  # before minutes of computing, not after
    require("tifffile", "writing float TIFF")
    os.makedirs(out, exist_ok=True)
    summary = {"uvfeat": __version__, "mesh": mesh.name, "warnings": list(load_notes), "radii": {},
               "settings": {"features": list(job.features), "radii": list(job.radii), "samples": job.samples,
                            "resolution": job.resolution, "compute_resolution": job.compute_resolution,
                            "method": job.method, "seed": job.seed}}
    advance("pre-processing + rasterising", done=False)
    atlas, at_vertices, _ = job_atlases(mesh, job)
    summary["warnings"] += atlas.warnings()
    advance("buffers ready")
    for computed in computed_radii(atlas, job, advance, at_vertices):
        summary["warnings"] += computed.notes
        advance(f"bakes at r = {computed.radius}", done=False)
        tag = radius_tag(computed.radius)
        files = {}
        for name, texture in computed.textures.items():
            # Maps interpolated from the vertices read each corner's own vertex value.
            corners = vertex_corners(atlas.mesh, computed.per_vertex[name]) if computed.maps is None \
                else computed.maps[name].corner_values()
            files[name] = {kind: os.path.basename(path) for kind, path in
                           bake_feature(out, f"{name}_r{tag}", atlas.mesh, name, texture, computed.per_vertex[name],
                                        computed.length, corners).items()}
        write_per_vertex(out, tag, atlas.mesh, computed.length, computed.per_vertex)
        summary["radii"][computed.radius] = {"radius": computed.length, "files": files,
                                             "ply": f"per_vertex_r{tag}.ply"}
        advance(f"bakes at r = {computed.radius} written")
    write_json(os.path.join(out, "bake.json"), summary)
    return summary
