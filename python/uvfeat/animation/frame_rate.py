"""Frame rates: the default, and the check every frame source applies."""

from __future__ import annotations

import numpy as np

from ..errors import AnimationError

#: Frame rate used when none is given (frame times, and sampling a glTF animation).
DEFAULT_FPS = 24.0


def check_fps(fps) -> float:
    if fps is None:
        return DEFAULT_FPS
    if isinstance(fps, bool) or not isinstance(fps, (int, float, np.integer, np.floating)) or not np.isfinite(fps) \
            or fps <= 0:
        raise AnimationError(f"fps must be a positive number, got {fps!r}")
    return float(fps)
