"""Principal directions as a UV line field (uvfeat.pictures.line_field): the pull-back through each
texel's triangle, its sign, masking, and the segments drawn on a feature-map picture."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

import uvfeat
from uvfeat.pictures.line_field import draw_line_field, uv_line_field

MAJOR, MINOR = 2.0, 0.5
WIDTH = 64


@pytest.fixture(scope="module")
def torus_atlas():
    # u goes around z (angle phi), v around the tube (angle theta), both increasing with the angle
    return uvfeat.Atlas(uvfeat.shapes.torus(MAJOR, MINOR, 64, 32), 128)


def texel_frames(atlas, width=WIDTH):
    """Unit 3D tangents along u and along v, and the tube radius factor, at the positions the
    computation texels show (NaN off the charts)."""
    pick = ((np.arange(width) + 0.5) * atlas.resolution / width).astype(int)
    p = atlas.position[np.ix_(pick, pick)].astype(np.float64)
    phi = np.arctan2(p[..., 1], p[..., 0])
    ring = np.hypot(p[..., 0], p[..., 1]) - MAJOR
    theta = np.arctan2(p[..., 2], ring)
    t_u = np.stack([-np.sin(phi), np.cos(phi), np.zeros_like(phi)], -1)
    t_v = np.stack([-np.sin(theta) * np.cos(phi), -np.sin(theta) * np.sin(phi), np.cos(theta)], -1)
    return t_u, t_v, MAJOR + MINOR * np.cos(theta)


def test_directions_along_u_and_v(torus_atlas):
    t_u, t_v, _ = texel_frames(torus_atlas)
    field = uv_line_field(torus_atlas, np.stack([t_u, t_v], axis=2))
    assert field.shape == (WIDTH, WIDTH, 2, 2)
    ok = np.isfinite(field).all(axis=(-1, -2))
    assert ok.mean() > 0.8
    along_u, along_v = field[ok, 0], field[ok, 1]
    np.testing.assert_allclose(np.linalg.norm(field[ok], axis=-1), 1.0, atol=1e-9)
    assert np.median(along_u[:, 0]) > 0.995 and np.min(along_u[:, 0]) > 0.97     # +u: right
    assert np.median(along_v[:, 1]) > 0.995 and np.min(along_v[:, 1]) > 0.98     # +v: up


def test_pull_back_follows_the_metric(torus_atlas):
    # A 3D direction half-way between the u and v tangents is not diagonal in UV: the torus is
    # stretched (|dp/du| : |dp/dv| = (R + a cos theta) : a), so the UV direction is (a, R + a cos theta).
    t_u, t_v, ring = texel_frames(torus_atlas)
    diagonal = (t_u + t_v) / np.sqrt(2)
    field = uv_line_field(torus_atlas, diagonal)
    assert field.shape == (WIDTH, WIDTH, 2)
    expected = np.stack([np.full_like(ring, MINOR), ring], -1)
    expected /= np.linalg.norm(expected, axis=-1, keepdims=True)
    ok = np.isfinite(field).all(-1)
    cosine = (field[ok] * expected[ok]).sum(-1)
    assert np.median(cosine) > 0.999
    assert np.percentile(cosine, 5) > 0.99
    # not simply 45 degrees
    assert np.median(np.abs(field[ok][:, 1] / field[ok][:, 0])) > 3.0


def test_sign_follows_the_direction_and_normal_components_are_ignored(torus_atlas):
    t_u, t_v, _ = texel_frames(torus_atlas)
    d = 0.6 * t_u + 0.8 * t_v
    field = uv_line_field(torus_atlas, d)
    flipped = uv_line_field(torus_atlas, -d)
    np.testing.assert_allclose(flipped, -field, atol=1e-12)          # a line field: same line, sign of d
    np.testing.assert_allclose(uv_line_field(torus_atlas, 7.5 * d), field, atol=1e-12)   # scale-free
    # a normal component is dropped by the least-squares pull-back into the triangle's plane
    normal = np.cross(t_u, t_v)
    tilted = uv_line_field(torus_atlas, d + 0.5 * normal)
    ok = np.isfinite(field).all(-1)
    assert np.median((tilted[ok] * field[ok]).sum(-1)) > 0.999


def test_off_chart_texels_are_nan(torus_atlas):
    t_u, _, _ = texel_frames(torus_atlas)
    d = np.where(np.isfinite(t_u), t_u, 0.0)         # finite everywhere, also off the charts
    field = uv_line_field(torus_atlas, d)
    pick = ((np.arange(WIDTH) + 0.5) * torus_atlas.resolution / WIDTH).astype(int)
    covered = torus_atlas.face[np.ix_(pick, pick)] >= 0
    assert (~covered).any()
    assert np.all(np.isnan(field[~covered]))
    assert np.all(np.isfinite(field[covered]))


def test_planar_affine_chart_is_exact():
    # On the affine plane a 3D direction (x, y, 0) is the UV direction (x, y) up to the map's scale.
    atlas = uvfeat.Atlas(uvfeat.shapes.plane(1.0, 8), 128)
    angle = np.radians(30.0)
    d = np.zeros((32, 32, 3))
    d[..., 0], d[..., 1] = np.cos(angle), np.sin(angle)
    field = uv_line_field(atlas, d)
    ok = np.isfinite(field).all(-1)
    assert ok.mean() > 0.8
    np.testing.assert_allclose(field[ok], np.broadcast_to([np.cos(angle), np.sin(angle)], field[ok].shape),
                               atol=1e-9)


def test_principal_directions_of_the_torus(torus_atlas):
    # k1 = 1/a around the tube (along v), k2 along the big circle (along u); the sign is arbitrary
    maps = torus_atlas.compute(["k1", "k2"], 0.2, samples=64, compute_resolution=64, method="fit")
    field = maps["k1"].uv_principal_directions()
    assert field.shape == (64, 64, 2, 2)
    np.testing.assert_array_equal(np.isnan(field[..., 0, 0]), np.isnan(maps["k1"].texture))
    ok = np.isfinite(field).all(axis=(-1, -2))
    d1, d2 = field[ok, 0], field[ok, 1]
    assert np.median(np.abs(d1[:, 1])) > 0.999 and np.percentile(np.abs(d1[:, 1]), 5) > 0.99
    assert np.median(np.abs(d2[:, 0])) > 0.99 and np.percentile(np.abs(d2[:, 0]), 5) > 0.95


# -- drawing -------------------------------------------------------------------------------------

def segments_of(field, segments=48, texture=None):
    fig, ax = plt.subplots()
    if texture is not None:
        ax.imshow(np.flipud(texture), interpolation="nearest")
    draw_line_field(ax, field, segments=segments, colour="red")
    fig.canvas.draw()  # applies the aspect ratio of imshow to the transforms
    collection = ax.collections[-1]
    lines = np.asarray(collection.get_segments())
    display = np.stack([ax.transData.transform(line) for line in lines]) if len(lines) else lines
    colours = collection.get_colors()
    plt.close(fig)
    return lines, display, colours


def test_draw_one_segment_per_cell():
    field = np.zeros((64, 64, 2))
    field[..., 0] = 1.0
    lines, _, colours = segments_of(field, segments=16)        # step 4: a 16 x 16 grid
    assert lines.shape == (256, 2, 2)
    np.testing.assert_allclose(colours[0], matplotlib.colors.to_rgba("red"))
    lengths = np.linalg.norm(lines[:, 1] - lines[:, 0], axis=-1)
    np.testing.assert_allclose(lengths, 0.8 * 4)
    np.testing.assert_allclose(lines[:, 0, 1], lines[:, 1, 1])   # u: horizontal
    centres = lines.mean(axis=1)
    np.testing.assert_allclose(np.unique(centres[:, 0]), np.arange(2, 64, 4))


def test_draw_skips_nan_and_places_cells_v_up():
    field = np.full((64, 64, 2), np.nan)
    field[10, 30] = (0.0, 1.0)                  # buffer row 10: v low, near the bottom of the picture
    lines, _, _ = segments_of(field, segments=64)
    assert lines.shape == (1, 2, 2)
    np.testing.assert_allclose(lines[0].mean(axis=0), (30, 63 - 10))


def test_drawn_direction_matches_the_field_on_screen():
    # drawn over imshow(np.flipud(texture)) (image rows grow downwards), a UV direction (du, dv)
    # must point right by du and up by dv on the screen
    du, dv = 0.6, 0.8
    field = np.zeros((32, 32, 2))
    field[..., 0], field[..., 1] = du, dv
    texture = np.zeros((32, 32))
    _, display, _ = segments_of(field, segments=8, texture=texture)
    vectors = display[:, 1] - display[:, 0]     # display y grows upwards
    vectors /= np.linalg.norm(vectors, axis=-1, keepdims=True)
    np.testing.assert_allclose(vectors, np.broadcast_to([du, dv], vectors.shape), atol=1e-6)


def test_draw_empty_field_adds_empty_collection():
    lines, _, _ = segments_of(np.full((16, 16, 2), np.nan))
    assert len(lines) == 0
