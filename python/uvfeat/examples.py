"""Built-in meshes that ship with the package (no download needed)."""

from __future__ import annotations

from importlib import resources

from .io import load
from .mesh import Mesh


def spot_path() -> str:
    """Path of the bundled Spot cow (Keenan Crane, CC0 1.0; 5,856 triangles, 13 UV charts)."""
    return str(resources.files("uvfeat").joinpath("data", "spot.obj"))


def spot() -> Mesh:
    """Spot the cow, loaded with its own UV atlas (its UVs reach slightly outside [0, 1] and are
    normalised with a warning)."""
    import warnings

    from .errors import UVWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UVWarning)
        return load(spot_path(), uv="require")
