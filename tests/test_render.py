"""The matplotlib painter's renderer of per-vertex values (uvfeat.pictures.render)."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

import uvfeat
from uvfeat.pictures.render import UP_AXES, VIEW, draw_vertex_values, view_rotation

TOP = (90.0, -90.0)  # with up="z": camera on +z, screen x = object x, screen y = object y


def render(positions, faces, values, cmap="viridis", low=0.0, high=1.0, view=VIEW, up="y", size=200):
    """RGB pixels (row 0 at the top) of the mesh drawn on a black figure filled by the axes."""
    fig = plt.figure(figsize=(size / 100, size / 100), dpi=100, facecolor="black")
    ax = fig.add_axes([0, 0, 1, 1])
    mappable = draw_vertex_values(ax, positions, faces, values, cmap, low, high, view=view, up=up)
    fig.canvas.draw()
    pixels = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(float) / 255
    plt.close(fig)
    return pixels, mappable


def colour(cmap, t):
    return np.asarray(matplotlib.colormaps[cmap](t))[:3]


def mostly(pixels, expected, tolerance=0.03, fraction=0.85):
    """Most pixels (antialiased hairlines between faces aside) have the expected colour, and the
    typical pixel has it exactly."""
    distance = np.abs(pixels - expected).max(axis=-1)
    return np.median(distance) < 0.01 and np.mean(distance < tolerance) > fraction


def halves(pixels):
    w = pixels.shape[1]
    return pixels[20:-20, 10: w // 2 - 20], pixels[20:-20, w // 2 + 20: -10]


@pytest.mark.parametrize("elevation, azimuth", [(0, 0), (25, -60), (-40, 130), (90, 10), (-90, -170), (13.5, 359)])
def test_view_rotation_is_a_rotation(elevation, azimuth):
    r = view_rotation(elevation, azimuth)
    np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(r) == pytest.approx(1.0)
    e, a = np.radians(elevation), np.radians(azimuth)
    np.testing.assert_allclose(r[2], [np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)], atol=1e-12)
    assert abs(r[0, 2]) < 1e-12          # "right" stays horizontal
    assert r[1, 2] >= -1e-12             # "up" never points down


def test_view_rotation_from_above():
    np.testing.assert_allclose(view_rotation(*TOP), np.eye(3), atol=1e-12)


def test_up_axes_are_cyclic_permutations():
    for axis, order in UP_AXES.items():
        permutation = np.eye(3)[order]
        assert np.linalg.det(permutation) == pytest.approx(1.0), axis   # no mirroring
        assert order[2] == "xyz".index(axis)


def square():
    plane = uvfeat.shapes.plane(1.0, 16)
    return plane.positions, plane.faces


def test_faces_coloured_by_values_in_the_right_halves():
    positions, faces = square()
    values = (positions[:, 0] > 0.5).astype(float)
    pixels, mappable = render(positions, faces, values, view=TOP, up="z")
    left, right = halves(pixels)
    assert mostly(left, colour("viridis", 0.0))
    assert mostly(right, colour("viridis", 1.0))
    assert not mostly(left, colour("viridis", 1.0)) and not mostly(right, colour("viridis", 0.0))
    assert mappable.norm.vmin == 0.0 and mappable.norm.vmax == 1.0 and mappable.cmap.name == "viridis"


def test_top_of_the_picture_is_the_up_axis():
    # y up (the default): the vertices' y values are high at the top of the picture
    sphere = uvfeat.shapes.uv_sphere(1.0, 32, 16)
    for up, axis in (("y", 1), ("x", 0)):
        values = sphere.positions[:, axis]
        pixels, _ = render(sphere.positions, sphere.faces, values, "gray", -1.0, 1.0, up=up)
        brightness = pixels.mean(axis=-1)
        covered = brightness > 0.02
        rows = np.nonzero(covered.any(axis=1))[0]
        third = len(rows) // 3
        top = brightness[rows[:third]][covered[rows[:third]]].mean()
        bottom = brightness[rows[-third:]][covered[rows[-third:]]].mean()
        assert top > 0.5 and bottom < 0.3 and top > 2 * bottom, (up, top, bottom)


def test_near_faces_hide_far_ones():
    # a closed sphere seen from +z: the near cap (values 1) must cover the far cap (values 0)
    sphere = uvfeat.shapes.uv_sphere(1.0, 32, 16)
    values = (sphere.positions[:, 2] > 0).astype(float)
    pixels, _ = render(sphere.positions, sphere.faces, values, view=TOP, up="z")
    h, w, _ = pixels.shape
    centre = pixels[h // 2 - 20: h // 2 + 20, w // 2 - 20: w // 2 + 20]
    # facing the viewer: shading factor close to 1
    assert np.abs(centre - colour("viridis", 1.0)).max(axis=-1).mean() < 0.06
    assert np.all(np.abs(centre - colour("viridis", 0.0)).max(axis=-1) > 0.3)


def test_faces_darken_as_they_turn_away():
    sphere = uvfeat.shapes.uv_sphere(1.0, 64, 32)
    values = np.full(sphere.n_vertices, 1.0)
    pixels, _ = render(sphere.positions, sphere.faces, values, "gray", 0.0, 1.0, view=TOP, up="z")
    h, w, _ = pixels.shape
    middle_row = pixels[h // 2, :, 0]
    covered = np.nonzero(middle_row > 0.01)[0]
    assert middle_row[w // 2] > 0.95
    rim = middle_row[covered[:3]].max()          # faces seen edge-on at the silhouette
    assert 0.3 < rim < 0.6                       # 0.35 + 0.65 * facing, facing near 0


def test_nan_values_drawn_grey():
    positions, faces = square()
    values = np.where(positions[:, 0] > 0.5, 1.0, np.nan)
    pixels, _ = render(positions, faces, values, view=TOP, up="z")
    left, right = halves(pixels)
    assert mostly(left, 0.5)
    assert mostly(right, colour("viridis", 1.0))


def test_one_nan_corner_does_not_grey_a_face():
    positions, faces = square()
    values = np.full(len(positions), 1.0)
    values[faces[0, 0]] = np.nan                 # a corner of the first faces
    pixels, _ = render(positions, faces, values, view=TOP, up="z")
    grey = np.abs(pixels - 0.5).max(axis=-1) < 0.05
    assert not grey.any()


def test_values_outside_the_range_are_clamped():
    positions, faces = square()
    values = np.where(positions[:, 0] > 0.5, 50.0, -50.0)
    pixels, _ = render(positions, faces, values, "viridis", -1.0, 1.0, view=TOP, up="z")
    left, right = halves(pixels)
    assert mostly(left, colour("viridis", 0.0))
    assert mostly(right, colour("viridis", 1.0))


def test_axes_limits_and_aspect():
    positions, faces = square()
    fig, ax = plt.subplots()
    draw_vertex_values(ax, positions + 100.0, faces, np.zeros(len(positions)), "viridis", 0.0, 1.0, view=TOP, up="z")
    # centred on the mesh, spanning its extent
    np.testing.assert_allclose(ax.get_xlim(), (-0.5, 0.5), atol=1e-9)
    np.testing.assert_allclose(ax.get_ylim(), (-0.5, 0.5), atol=1e-9)
    assert ax.get_aspect() == 1.0
    # one picture at the axes' own pixel size (the default figure: 640 x 480 px, axes 77.5 % x 77 %)
    (image,) = ax.images
    width, height = ax.get_window_extent().width, ax.get_window_extent().height
    assert all(abs(n - min(width, height)) <= 1 for n in image.get_array().shape[:2])
    plt.close(fig)


def test_a_closed_mesh_wound_inwards_shows_its_near_side():
    """Back faces of a closed mesh are culled by the winding: an inward-wound mesh (negative
    volume) must still show the side facing the viewer, not the far one."""
    from uvfeat.pictures.render import render_values

    torus = uvfeat.shapes.torus(2.0, 0.5, 48, 24)
    height = torus.positions[:, 2]
    outward = render_values(torus.positions, torus.faces, height, "viridis", -0.5, 0.5, view=(60.0, 0.0), up="z")
    inward = render_values(torus.positions, torus.faces[:, ::-1], height, "viridis", -0.5, 0.5, view=(60.0, 0.0),
                           up="z")
    np.testing.assert_allclose(inward, outward, atol=1e-9)


def test_front_side_of_closed_open_and_inward_meshes():
    from uvfeat.pictures.render import front_side

    torus = uvfeat.shapes.torus(2.0, 0.5, 48, 24)
    assert front_side(torus.positions, torus.faces) == 1
    assert front_side(torus.positions, torus.faces[:, ::-1]) == -1
    assert front_side(torus.positions, torus.faces[1:]) == 0
    with pytest.raises(uvfeat.UvfeatError, match="vertex"):
        front_side(torus.positions, torus.faces + len(torus.positions))
