"""Optional dependencies, imported when first needed so that the core install stays light."""

from __future__ import annotations

import importlib

from .errors import MissingDependencyError

#: The pip package and the uvfeat extra that install each optional module.
EXTRAS = {"imageio_ffmpeg": ("imageio-ffmpeg", "video"), "polyscope": ("polyscope", "view"),
          "tifffile": ("tifffile", "bake"), "scipy.ndimage": ("scipy", "bake")}


def require(module: str, purpose: str):
    """Imports ``module``, or raises :class:`MissingDependencyError` naming the extra to install."""
    try:
        return importlib.import_module(module)
    except ImportError:
        package, extra = EXTRAS[module]
        raise MissingDependencyError(f"{purpose} needs the optional package {package}: "
                                     f"pip install 'uvfeat[{extra}]'") from None
