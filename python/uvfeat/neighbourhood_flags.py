"""Which per-vertex values come from neighbourhoods that are not what the radius asks for, and the
plain-language notes about them:

- **truncated**: the ball reaches past a mesh border, so part of the neighbourhood is missing
  from the surface itself and the values are biased (normal near the border of an open mesh);
- **partly missing**: more than :data:`MISSING_SHARE` of the samples could not be relocated
  across seams (a broken atlas, or more seams than ``max_jumps``), unless the others found one
  sheet's ``pi r^2`` (:data:`COVERED_RATIOS`), so that the lost samples' surface is covered.
  That is the case round the pole of a latitude-longitude chart: the sampling domain overlaps
  itself across the pole's fan of slits, and the points lost beyond the pole are surface the
  domain reaches round the side (the clean 200K lat-long sphere at r = 2 %: 8 % of the texels
  lose 46 % of their points, and most of their neighbourhoods hold 1.00 ``pi r^2``);
- **several sheets**: the neighbourhood's area exceeds ``SEVERAL_SHEETS`` times one sheet's, so
  the ball holds more than one sheet of the surface (both sides of a part thinner than the
  radius): the values mix the sheets. One smooth sheet holds about ``pi r^2`` at any curvature,
  one rough sheet more: its facets tilt about the surface (``FeatureMap.sheet_area``, the mean
  roughness of the faces round the texel: 1.3-4 on the noisy lat-long sphere of docs/PEERS.md,
  1 on smooth meshes).

Area ratios are read in units of one sheet's area: ``area_ratio / sheet_area``.

A vertex is flagged when the texel under one of its corners is.
"""

from __future__ import annotations

import numpy as np

from . import _core

#: Share of missing samples above which a neighbourhood counts as partly missing.
MISSING_SHARE = 0.05

#: Area ratios (in units of one sheet's area) of a neighbourhood whose lost samples are surface its
#: other samples cover: one sheet within the share lost and the overlap of seam routes (up to 1.1).
#: Outside it the loss counts: short of the ball, or a second sheet making up for it.
COVERED_RATIOS = (1.0 - MISSING_SHARE, 1.1)

#: Flag names, in report order.
FLAGS = ("truncated", "partly_missing", "several_sheets")


def texel_flags(n_valid: np.ndarray, n_missing: np.ndarray, n_border: np.ndarray,
                area_ratio: np.ndarray, sheet_area: np.ndarray) -> dict[str, np.ndarray]:
    """Boolean maps of the three flags over the computation texture; ``sheet_area`` is the area
    one sheet of the surface holds in each texel's ball, over ``pi r^2``."""
    truncated = n_border > 0
    # Summed as floats (exact at these counts): one conversion instead of three to int64.
    drawn = np.maximum(n_valid.astype(np.float32) + n_missing + n_border, 1)
    sheets = area_ratio / sheet_area
    with np.errstate(invalid="ignore"):
        # NaN ratios (no samples, or off the charts) are not covered.
        covered = (sheets >= COVERED_RATIOS[0]) & (sheets <= COVERED_RATIOS[1])
        return {"truncated": truncated,
                "partly_missing": (n_missing > MISSING_SHARE * drawn) & ~covered,
                "several_sheets": sheets > _core.SEVERAL_SHEETS}


def vertex_flags(mesh, flags: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """``(n_vertices,)`` booleans per flag: some corner of the vertex lies on a flagged texel.
    The flags (eight at most) are packed into one bit each, looked up once per UV vertex and spread over the
    corners as bytes; only the flagged corners are then scattered (a million faces: a few MB, no
    per-corner coordinates; per flag, every corner's lookup and scatter took 1 ms per 100K
    vertices)."""
    resolution = next(iter(flags.values())).shape[-1]
    bits = np.zeros(resolution * resolution, dtype=np.uint8)
    for bit, texels in enumerate(flags.values()):
        bits |= texels.reshape(-1).astype(np.uint8) << bit
    texel = np.clip((mesh.uvs * resolution).astype(np.int32), 0, resolution - 1)
    corner_bits = bits[texel[:, 1] * resolution + texel[:, 0]][mesh.uv_faces.reshape(-1)]
    flagged_corners = np.flatnonzero(corner_bits != 0)  # on bytes, ten times as long
    vertices, corner_bits = mesh.faces.reshape(-1)[flagged_corners], corner_bits[flagged_corners]
    out = {}
    for bit, name in enumerate(flags):
        flagged = np.zeros(mesh.n_vertices, dtype=bool)
        flagged[vertices[(corner_bits >> bit) & 1 == 1]] = True
        out[name] = flagged
    return out


def vertex_share(count: int, n_vertices: int) -> str:
    """``"1,234 vertices (5.6 %)"``: how many of ``n_vertices`` a note is about."""
    return f"{count:,} {'vertex' if count == 1 else 'vertices'} ({100 * count / max(n_vertices, 1):.1f} %)"


def notes(counts: dict[str, int], n_vertices: int, scale: str) -> list[str]:
    """A note per flag with flagged vertices, saying what it means and what to do; ``scale`` opens
    it (``"at r = 4%"``, ``"at each vertex's own radius"``)."""
    share = {name: vertex_share(count, n_vertices) for name, count in counts.items()}
    texts = {
        "truncated": f"{scale}, {share['truncated']} have neighbourhoods cut by a mesh border: their values "
                     "are biased (a smaller radius shrinks the band)",
        "partly_missing": f"{scale}, {share['partly_missing']} have neighbourhoods that lost more than "
                          f"{MISSING_SHARE:.0%} of their samples across seams, and part of the surface with them: "
                          "raise max_jumps or re-atlas",
        "several_sheets": f"{scale}, {share['several_sheets']} have neighbourhoods holding more than one "
                          "sheet of the surface (the radius is wider than a thin part there): their values mix both "
                          "sides; use a smaller radius",
    }
    return [texts[name] for name in FLAGS if counts.get(name)]
