"""Keyframe channels of glTF animations and their interpolation (glTF 2.0 §3.11, Appendix C):
STEP, LINEAR (spherical for rotations) and CUBICSPLINE (Hermite with in/out tangents)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import AnimationError

#: Interpolation modes of a glTF animation sampler.
INTERPOLATIONS = ("STEP", "LINEAR", "CUBICSPLINE")


def slerp(q0: np.ndarray, q1: np.ndarray, s: float) -> np.ndarray:
    """Spherical linear interpolation of unit quaternions (any component order) along the shorter
    arc; ``s`` in [0, 1]."""
    q0 = q0 / np.linalg.norm(q0)
    q1 = q1 / np.linalg.norm(q1)
    dot = float(np.dot(q0, q1))
    if dot < 0.0:  # q and -q are the same rotation: take the shorter way round
        q1, dot = -q1, -dot
    if dot > 0.9995:  # nearly equal: sin(angle) ~ 0, and the chord is the arc to 1e-7
        out = q0 + s * (q1 - q0)
        return out / np.linalg.norm(out)
    angle = np.arccos(dot)
    return (np.sin((1.0 - s) * angle) * q0 + np.sin(s * angle) * q1) / np.sin(angle)


@dataclass(frozen=True)
class Channel:
    """One animated property: key times ``(K,)`` seconds (strictly increasing) and values ``(K, C)``
    (STEP, LINEAR) or ``(K, 3, C)`` (CUBICSPLINE: in-tangent, value, out-tangent per key, tangents
    in units per second). ``rotation`` marks unit quaternions (x, y, z, w)."""

    times: np.ndarray
    values: np.ndarray
    interpolation: str = "LINEAR"
    rotation: bool = False

    @classmethod
    def from_sampler(cls, times, output, interpolation: str | None, width: int, rotation: bool = False,
                     what: str = "channel") -> Channel:
        """Checks a glTF sampler (``input`` times, flat ``output`` values of ``width`` numbers per key)
        and builds the channel; ``what`` names it in errors."""
        interpolation = interpolation or "LINEAR"
        if interpolation not in INTERPOLATIONS:
            raise AnimationError(f"{what}: unknown interpolation {interpolation!r}; glTF has {', '.join(INTERPOLATIONS)}")
        times = np.asarray(times, dtype=np.float64).reshape(-1)
        if len(times) == 0 or not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0):
            raise AnimationError(f"{what}: key times must be finite and strictly increasing, got {len(times)} keys")
        per_key = 3 if interpolation == "CUBICSPLINE" else 1
        output = np.asarray(output, dtype=np.float64)
        if output.size != len(times) * per_key * width:
            raise AnimationError(f"{what}: {len(times)} key times need {len(times) * per_key} outputs of {width} "
                                 f"values ({interpolation}), got {output.size} values")
        values = output.reshape((len(times), 3, width) if per_key == 3 else (len(times), width))
        return cls(times, values, interpolation, rotation)

    @property
    def start(self) -> float:
        return float(self.times[0])

    @property
    def end(self) -> float:
        return float(self.times[-1])

    def key_value(self, k: int) -> np.ndarray:
        return self.values[k, 1] if self.interpolation == "CUBICSPLINE" else self.values[k]

    def at(self, t: float) -> np.ndarray:
        """The value at time ``t``; before the first key the first value, after the last the last."""
        times = self.times
        if t <= times[0] or len(times) == 1:
            return self.key_value(0).copy()
        if t >= times[-1]:
            return self.key_value(len(times) - 1).copy()
        k = int(np.searchsorted(times, t, side="right")) - 1
        span = times[k + 1] - times[k]
        s = (t - times[k]) / span
        if self.interpolation == "STEP":
            return self.key_value(k).copy()
        if self.interpolation == "LINEAR":
            if self.rotation:
                return slerp(self.values[k], self.values[k + 1], s)
            return (1.0 - s) * self.values[k] + s * self.values[k + 1]
        # Cubic Hermite spline (glTF Appendix C): p = h00 v_k + h10 td b_k + h01 v_k+1 + h11 td a_k+1
        s2, s3 = s * s, s * s * s
        value = ((2 * s3 - 3 * s2 + 1) * self.values[k, 1] + span * (s3 - 2 * s2 + s) * self.values[k, 2]
                 + (-2 * s3 + 3 * s2) * self.values[k + 1, 1] + span * (s3 - s2) * self.values[k + 1, 0])
        return value / np.linalg.norm(value) if self.rotation else value
