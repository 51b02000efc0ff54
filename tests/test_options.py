"""One definition of each option: the core owns the names, choices and defaults; the Python
signatures and the command line take theirs from it (checked here), and bad options get the
core's named errors."""

import inspect

import pytest

import uvfeat
from uvfeat import _core
from uvfeat.cli import build_parser
from uvfeat.options import ARGUMENT_DEFAULTS, CHOICES, DEFAULT_OPTIONS, PAPER_OPTIONS


def test_the_python_options_are_the_cores():
    core = _core.default_options()
    assert {**ARGUMENT_DEFAULTS, **{k: v for k, v in DEFAULT_OPTIONS.items() if k != "query"}} == core
    assert ARGUMENT_DEFAULTS == {"samples": 256, "compute_resolution": 512, "adaptive": False, "seed": 0}
    assert DEFAULT_OPTIONS["margin"] == 1.25 and DEFAULT_OPTIONS["max_jumps"] == 32
    assert PAPER_OPTIONS["relocation"] == "per_chart" and PAPER_OPTIONS["margin"] == 1.0
    assert set(PAPER_OPTIONS) < set(DEFAULT_OPTIONS)
    for name, choices in CHOICES.items():
        if name in DEFAULT_OPTIONS:
            assert DEFAULT_OPTIONS[name] == choices[0], name
    assert uvfeat.FEATURES == tuple(_core.feature_names())


@pytest.mark.parametrize("function", [uvfeat.Atlas.compute, uvfeat.Atlas.neighbourhoods, uvfeat.Atlas.map_operator,
                                      uvfeat.compare.compare])
def test_python_signatures_default_to_the_core(function):
    parameters = inspect.signature(function).parameters
    shared = [name for name in ARGUMENT_DEFAULTS if name in parameters]
    assert "samples" in shared and "seed" in shared
    for name in shared:
        # compare's samples None: the pattern's 256 points or the sums' 160 surfels per ball.
        expected = None if (function, name) == (uvfeat.compare.compare, "samples") else ARGUMENT_DEFAULTS[name]
        assert parameters[name].default == expected, name
    for name in set(parameters) & set(DEFAULT_OPTIONS):
        # compare's quadrature and surface None: uvfeat.compute's per-vertex default, which the mesh's
        # atlas decides.
        per_vertex = function is uvfeat.compare.compare and name in ("quadrature", "surface")
        expected = None if per_vertex else DEFAULT_OPTIONS[name]
        assert parameters[name].default == expected, name


@pytest.mark.parametrize("command", ["compute", "compare", "animate"])
def test_the_command_line_defaults_to_the_core(command):
    parser = build_parser()
    args = parser.parse_args([command, "mesh.obj"])
    for name in ("compute_resolution", "seed"):
        assert getattr(args, name) == ARGUMENT_DEFAULTS[name], name
    # None: the pattern's 256 points per texel, or 160 surfels per ball for the sums at the vertices.
    assert args.samples is None
    for name in ("method", "sampling") + (("query",) if command != "animate" else ()):
        assert getattr(args, name) == DEFAULT_OPTIONS[name], name
    choices = {action.dest: list(action.choices) for action in parser._subparsers._group_actions[0].choices[command]
               ._actions if action.choices}
    for name in ("method", "sampling", "query"):
        if name in choices:
            assert choices[name] == CHOICES[name]


def test_bad_options_get_the_cores_named_errors():
    atlas = uvfeat.Atlas(uvfeat.shapes.uv_sphere(1.0, 16, 8), resolution=64)
    with pytest.raises(uvfeat.InvalidParameterError, match="unknown option"):
        atlas.compute("mean_curvature", 0.3, margins=2.0)
    with pytest.raises(uvfeat.InvalidParameterError, match="bilinear"):
        atlas.compute("mean_curvature", 0.3, lookup="nearest")
    with pytest.raises(uvfeat.InvalidParameterError, match="samples"):
        atlas.compute("mean_curvature", 0.3, samples=2)
    with pytest.raises(uvfeat.InvalidParameterError, match="true or false"):
        atlas.compute("mean_curvature", 0.3, grow_margin=1.0)
    with pytest.raises(uvfeat.InvalidParameterError, match="precision"):
        uvfeat.Atlas(uvfeat.shapes.uv_sphere(1.0, 16, 8), precision="f64")
