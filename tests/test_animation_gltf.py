"""glTF animation evaluation against analytic expectations: keyframe interpolation (STEP, LINEAR
with slerp, CUBICSPLINE), skinning, morph targets, node hierarchies and the vertex order of
``uvfeat.load``; bad animation data."""

import warnings

import numpy as np
import pytest

import uvfeat
from gltf_builder import UNSIGNED_BYTE, GltfBuilder, per_vertex_uvs
from uvfeat.animation import Channel, GltfAnimation, slerp
from uvfeat.animation.scene import quaternion_matrix
from uvfeat.errors import AnimationError


def axis_angle(axis, degrees: float) -> np.ndarray:
    """Unit quaternion (x, y, z, w) of a rotation by ``degrees`` about ``axis``."""
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    half = np.radians(degrees) / 2
    return np.append(axis * np.sin(half), np.cos(half))


def translation(x, y, z) -> np.ndarray:
    matrix = np.eye(4)
    matrix[:3, 3] = (x, y, z)
    return matrix


# -- interpolation ----------------------------------------------------------------------------------
def test_step_holds_each_key_until_the_next():
    channel = Channel.from_sampler([0.0, 1.0, 2.0], [0.0, 10.0, 20.0], "STEP", 1)
    times = (-1.0, 0.0, 0.5, 0.999, 1.0, 1.5, 2.0, 3.0)
    assert [float(channel.at(t)[0]) for t in times] == [0, 0, 0, 0, 10, 10, 20, 20]


def test_linear_interpolates_vectors_and_clamps_outside_the_keys():
    channel = Channel.from_sampler([1.0, 3.0], [[0, 0, 0], [2, 4, -6]], "LINEAR", 3)
    np.testing.assert_allclose(channel.at(1.5), [0.5, 1.0, -1.5])
    np.testing.assert_allclose(channel.at(0.0), [0, 0, 0])
    np.testing.assert_allclose(channel.at(7.0), [2, 4, -6])


@pytest.mark.parametrize("flip", [False, True], ids=["q1", "-q1"])
def test_linear_rotation_turns_at_constant_speed_along_the_shorter_arc(flip):
    end = axis_angle([0, 0, 1], 90) * (-1 if flip else 1)  # -q is the same rotation
    channel = Channel.from_sampler([0.0, 1.0], [axis_angle([0, 0, 1], 0), end], "LINEAR", 4, rotation=True)
    for s in (0.25, 1 / 3, 0.5, 0.9):
        # a normalised lerp would give 21.6 degrees at s = 0.25 instead of 22.5
        np.testing.assert_allclose(quaternion_matrix(channel.at(s)), quaternion_matrix(axis_angle([0, 0, 1], 90 * s)),
                                   atol=1e-12)


def test_slerp_of_nearly_equal_rotations_stays_unit():
    q = axis_angle([1, 2, 3], 40)
    out = slerp(q, axis_angle([1, 2, 3], 40.001), 0.5)
    assert abs(np.linalg.norm(out) - 1) < 1e-12
    np.testing.assert_allclose(quaternion_matrix(out), quaternion_matrix(axis_angle([1, 2, 3], 40.0005)), atol=1e-9)


def test_cubic_spline_reproduces_a_cubic_from_its_derivatives():
    keys = np.array([0.0, 0.5, 2.0])  # unequal spans: the tangents are scaled by the span
    output = np.stack([3 * keys**2, keys**3, 3 * keys**2], axis=1)  # in-tangent, value, out-tangent
    channel = Channel.from_sampler(keys, output, "CUBICSPLINE", 1)
    for t in (0.1, 0.25, 0.5, 1.2, 1.9):
        assert channel.at(t)[0] == pytest.approx(t**3, abs=1e-12)


def test_cubic_spline_rotations_come_out_unit():
    keys = [axis_angle([0, 1, 0], 0), axis_angle([0, 1, 0], 120)]
    output = np.stack([np.stack([np.full(4, 0.3), q, np.full(4, 0.3)]) for q in keys])
    channel = Channel.from_sampler([0.0, 1.0], output, "CUBICSPLINE", 4, rotation=True)
    assert np.linalg.norm(channel.at(0.4)) == pytest.approx(1.0)


@pytest.mark.parametrize("times, values, interpolation, message", [
    ([0.0, 1.0], [1.0, 2.0, 3.0], "LINEAR", "2 key times need 2 outputs"),
    ([0.0, 1.0], [1.0, 2.0], "CUBICSPLINE", "need 6 outputs"),
    ([0.0, 0.0], [1.0, 2.0], "LINEAR", "strictly increasing"),
    ([0.0, 1.0], [1.0, 2.0], "BEZIER", "unknown interpolation"),
])
def test_inconsistent_samplers_are_refused(times, values, interpolation, message):
    with pytest.raises(AnimationError, match=message):
        Channel.from_sampler(times, values, interpolation, 1)


# -- skinning ---------------------------------------------------------------------------------------
def bending_bar(path):
    """A bar (cylinder r 0.2 along z in [-1, 1]) on two joints: the root at z = -1 slides along x,
    the hinge at z = 0 (its child) turns the upper half about x by 90 degrees over one second."""
    positions, faces, uvs = per_vertex_uvs(uvfeat.shapes.cylinder(0.2, 2.0, 32, 16))
    joints = np.zeros((len(positions), 4), dtype=int)
    joints[positions[:, 2] >= 0, 0] = 1
    weights = np.zeros((len(positions), 4))
    weights[:, 0] = 1.0
    b = GltfBuilder()
    mesh = b.mesh([b.primitive(positions, faces, uvs, joints=joints, weights=weights,
                               weight_component=UNSIGNED_BYTE)])
    hinge = b.node(translation=[0, 0, 1.0])
    root = b.node(root=True, translation=[0, 0, -1.0], children=[hinge])
    b.node(root=True, mesh=mesh, skin=b.skin([root, hinge], np.stack([translation(0, 0, 1), np.eye(4)])))
    b.animation("bend", [(hinge, "rotation", [0.0, 1.0], [axis_angle([1, 0, 0], 0), axis_angle([1, 0, 0], 90)],
                          "LINEAR"),
                         (root, "translation", [0.0, 1.0], [[0, 0, -1.0], [1.0, 0, -1.0]], "LINEAR")])
    return b.save(path)


def expected_bar(rest: np.ndarray, t: float) -> np.ndarray:
    upper = rest[:, 2] >= 0
    out = rest + [t, 0, 0]
    out[upper] = rest[upper] @ quaternion_matrix(axis_angle([1, 0, 0], 90 * t)).T + [t, 0, 0]
    return out


def test_two_joint_skin_follows_the_joints(tmp_path):
    path = bending_bar(tmp_path / "bar.glb")
    mesh = uvfeat.load(path, uv="require")
    animation = GltfAnimation(path, reference=mesh)
    assert animation.names == ["bend"] and animation.time_range() == (0.0, 1.0)
    np.testing.assert_allclose(animation.times(4), [0, 0.25, 0.5, 0.75, 1.0])
    np.testing.assert_allclose(animation.positions(None), mesh.positions, atol=1e-6)  # rest pose = bind pose
    for t in (0.0, 0.5, 0.8, 1.0):
        np.testing.assert_allclose(animation.positions(t, "bend"), expected_bar(mesh.positions, t), atol=1e-6)


# -- node hierarchy, instancing and vertex order ------------------------------------------------
def test_nodes_primitives_and_instances_come_in_the_order_of_uvfeat_load(tmp_path):
    b = GltfBuilder()
    two = b.mesh([b.primitive(*per_vertex_uvs(uvfeat.shapes.uv_sphere(1.0, 16, 8))),
                  b.primitive(*per_vertex_uvs(uvfeat.shapes.plane(1.0, 4)))])
    torus = per_vertex_uvs(uvfeat.shapes.torus(2.0, 0.5, 16, 8))
    one = b.mesh([b.primitive(*torus)])
    first = b.node(mesh=two, translation=[1, 2, 3])
    slider = b.node(mesh=one, rotation=axis_angle([1, 1, 0], 40), scale=[1, 2, 1])
    b.node(root=True, children=[first, slider], translation=[0, 0, 5], scale=[2, 2, 2])
    b.node(root=True, mesh=one, matrix=np.linalg.inv(translation(4, 0, 0)).T.reshape(-1).tolist())
    b.animation("slide", [(slider, "translation", [0.0, 1.0], [[0, 0, 0], [0, 3, 0]], "STEP")])
    path = b.save(tmp_path / "scene.gltf")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the parts' UV layouts get tiled
        mesh = uvfeat.load(path)
    animation = GltfAnimation(path)
    np.testing.assert_allclose(animation.static_positions(), mesh.positions, atol=1e-9)
    GltfAnimation(path, reference=mesh)
    moved = animation.positions(1.0) - mesh.positions
    shifted = np.abs(moved).max(axis=1) > 1e-9
    assert shifted.sum() == len(torus[0])  # one of the two torus instances, shifted in its scaled parent
    np.testing.assert_allclose(moved[shifted], np.tile([0, 6.0, 0], (shifted.sum(), 1)), atol=1e-9)
    np.testing.assert_allclose(animation.positions(0.99), mesh.positions, atol=1e-9)  # STEP: not yet
    with pytest.raises(AnimationError, match="match no primitive"):
        GltfAnimation(path, reference=mesh.positions[::-1])


# -- morph targets ----------------------------------------------------------------------------------
def test_morph_targets_with_sparse_offsets_and_default_weights(tmp_path):
    positions, faces, uvs = per_vertex_uvs(uvfeat.shapes.plane(1.0, 4))
    n = len(positions)
    b = GltfBuilder()
    sparse = b.sparse_accessor(n, [0, 7], [[0, 0, 1.0], [0, 0, -2.0]])
    lift = np.tile([0, 0, 0.5], (n, 1))
    mesh = b.mesh([b.primitive(positions, faces, uvs, targets=[sparse, lift])], weights=[1.0, 0.0])
    plain = b.node(root=True, mesh=mesh)
    b.node(root=True, mesh=mesh, translation=[3, 0, 0], weights=[0.5, 1.0])  # node weights override the mesh's
    b.animation("pulse", [(plain, "weights", [0.0, 1.0, 2.0], [[0, 0], [0, 2], [1, 1]], "LINEAR")])
    path = b.save(tmp_path / "morph.glb")
    mesh_ = uvfeat.load(path, uv="xatlas", resolution=64)
    animation = GltfAnimation(path, reference=mesh_)
    offsets = np.zeros((n, 3))
    offsets[[0, 7], 2] = [1.0, -2.0]
    plain_rows, moved_rows = slice(0, n), slice(n, 2 * n)
    if mesh_.positions[:n, 0].min() >= 3:  # trimesh takes the last root node first
        plain_rows, moved_rows = moved_rows, plain_rows
    rest = animation.positions(None)
    np.testing.assert_allclose(rest[plain_rows], positions + offsets, atol=1e-6)
    np.testing.assert_allclose(rest[moved_rows], positions + [3, 0, 0] + 0.5 * offsets + lift, atol=1e-6)
    np.testing.assert_allclose(animation.positions(0.5)[plain_rows], positions + lift, atol=1e-6)
    np.testing.assert_allclose(animation.positions(1.5)[plain_rows], positions + 0.5 * offsets + 1.5 * lift,
                               atol=1e-6)


def test_morph_targets_must_match_their_primitive(tmp_path):
    positions, faces, uvs = per_vertex_uvs(uvfeat.shapes.plane(1.0, 4))
    b = GltfBuilder()
    b.node(root=True, mesh=b.mesh([b.primitive(positions, faces, uvs, targets=[positions[:-1]])]))
    with pytest.raises(AnimationError, match="morph targets have 24 vertices, the primitive 25"):
        GltfAnimation(b.save(tmp_path / "bad.glb"))


# -- bad animation data ------------------------------------------------------------------------
def static_plane(b: GltfBuilder) -> int:
    return b.node(root=True, mesh=b.mesh([b.primitive(*per_vertex_uvs(uvfeat.shapes.plane(1.0, 4)))]))


def test_a_file_without_animation_says_so(tmp_path):
    b = GltfBuilder()
    static_plane(b)
    animation = GltfAnimation(b.save(tmp_path / "still.glb"))
    assert animation.names == []
    with pytest.raises(AnimationError, match="still.glb has no animation; pass frames="):
        animation.positions(0.5)


def test_unknown_animations_are_listed(tmp_path):
    b = GltfBuilder()
    node = static_plane(b)
    for name in ("Walk", "Run"):
        b.animation(name, [(node, "translation", [0.0, 1.0], [[0, 0, 0], [1, 0, 0]], "LINEAR")])
    animation = GltfAnimation(b.save(tmp_path / "two.glb"))
    assert animation.index("Run") == 1 and animation.index(1) == 1 and animation.index("1") == 1
    with pytest.raises(AnimationError, match="no animation 'Dance'.*0: 'Walk', 1: 'Run'"):
        animation.index("Dance")
    with pytest.raises(AnimationError, match="no animation 5; it has 2"):
        animation.index(5)


def test_keys_and_values_that_disagree_are_refused(tmp_path):
    b = GltfBuilder()
    node = static_plane(b)
    b.animation("broken", [(node, "translation", [0.0, 1.0, 2.0], [[0, 0, 0], [1, 0, 0]], "LINEAR")])
    animation = GltfAnimation(b.save(tmp_path / "broken.glb"))
    with pytest.raises(AnimationError, match="'broken' channel 0 .*3 key times need 3 outputs of 3 values"):
        animation.positions(0.5)


def test_morph_weights_of_a_node_without_mesh_are_refused(tmp_path):
    b = GltfBuilder()
    static_plane(b)
    empty = b.node(root=True)
    b.animation("weights", [(empty, "weights", [0.0, 1.0], [0.0, 1.0], "LINEAR")])
    with pytest.raises(AnimationError, match="morph weights of a node without a mesh"):
        GltfAnimation(b.save(tmp_path / "weights.glb")).positions(0.0)


def test_compressed_primitives_are_refused(tmp_path):
    b = GltfBuilder()
    primitive = b.primitive(*per_vertex_uvs(uvfeat.shapes.plane(1.0, 4)))
    primitive["extensions"] = {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}
    b.node(root=True, mesh=b.mesh([primitive]))
    with pytest.raises(AnimationError, match="compressed \\(KHR_draco_mesh_compression\\); animation needs"):
        GltfAnimation(b.save(tmp_path / "draco.glb"))
