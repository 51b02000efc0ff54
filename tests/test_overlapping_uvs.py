"""A file whose UV layout folds one half of the surface over the other is re-atlased with
``uv="auto"``: its per-vertex H matches the same mesh with a clean atlas within the Monte
Carlo error, in the file's vertex order, and a warning says what happened."""

import warnings

import numpy as np
import pytest
import trimesh

import uvfeat
from uvfeat import UVWarning

RADIUS = "4%"
OPTIONS = dict(samples=64, compute_resolution=128, standard_error=True)


def _torus_file(tmp_path, fold: bool):
    """A 64 x 32 lat-long torus as an OBJ, with per-corner UVs; ``fold`` maps the inner half of the
    tube onto the outer half's UVs (v -> 1 - |1 - 2v|)."""
    torus = uvfeat.shapes.torus(2.0, 0.5, 64, 32)
    corners = torus.faces.reshape(-1)
    uv = torus.uvs[torus.uv_faces.reshape(-1)].copy()
    if fold:
        uv[:, 1] = 1.0 - np.abs(1.0 - 2.0 * uv[:, 1])
    mesh = trimesh.Trimesh(torus.positions[corners], np.arange(len(corners)).reshape(-1, 3),
                           visual=trimesh.visual.TextureVisuals(uv=uv), process=False)
    path = tmp_path / ("folded.obj" if fold else "clean.obj")
    mesh.export(path)
    return path


def test_folded_uvs_are_reatlased_and_give_the_clean_atlas_values(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        clean = uvfeat.load(_torus_file(tmp_path, fold=False))
    with pytest.warns(UVWarning, match=r"overlap on \d+\.\d% of their texels.*re-atlased"):
        folded = uvfeat.load(_torus_file(tmp_path, fold=True))
    assert clean.n_charts == 1 and folded.n_charts > 1
    np.testing.assert_array_equal(folded.positions, clean.positions)
    np.testing.assert_array_equal(folded.faces, clean.faces)

    reference = uvfeat.Atlas(clean, 512).compute("mean_curvature", RADIUS, **OPTIONS)["mean_curvature"]
    repaired = uvfeat.Atlas(folded, 512).compute("mean_curvature", RADIUS, **OPTIONS)["mean_curvature"]
    h_clean, h_folded = reference.per_vertex(), repaired.per_vertex()
    error = np.nanmedian(reference.standard_error)
    difference = np.abs(h_folded - h_clean)
    assert np.median(difference) < 3.0 * error, (np.median(difference), error)
    assert np.percentile(difference, 95) < 10.0 * error


def test_folded_uvs_are_kept_with_require_and_counted(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        kept = uvfeat.load(_torus_file(tmp_path, fold=True), uv="require")
    atlas = uvfeat.Atlas(kept, 256)
    assert kept.n_charts == 1
    assert atlas.overlap_share > 0.3
    assert any("overlapping UVs" in w for w in atlas.warnings())
