"""Optional dependencies, imported when first needed so that the core install stays light."""

from __future__ import annotations

import importlib

from .errors import MissingDependencyError

#: The pip extra that installs each optional module.
EXTRAS = {"imageio_ffmpeg": "video", "polyscope": "view", "tifffile": "bake"}


def require(module: str, purpose: str):
    """Imports ``module``, or raises :class:`MissingDependencyError` naming the extra to install."""
    try:
        return importlib.import_module(module)
    except ImportError:
        raise MissingDependencyError(f"{purpose} needs the optional package {module.replace('_', '-')}: "
                                     f"pip install 'uvfeat[{EXTRAS[module]}]'") from None
