"""Animated and deformable meshes: features per frame.

``uvfeat.animate(source, features, radius, frames=None, fps=None, ...)`` plays an animation —
a glTF/GLB file's own (skins, morph targets, node animation), an ``(n_frames, V, 3)`` array, or
a sequence of mesh files — and yields per-vertex features frame by frame. :class:`GltfAnimation`
evaluates a glTF animation into positions on its own.
"""

from .animate import Animation, AnimationFrame, animate
from .gltf import GltfAnimation
from .interpolation import Channel, slerp
from .frame_rate import DEFAULT_FPS

__all__ = ["Animation", "AnimationFrame", "Channel", "DEFAULT_FPS", "GltfAnimation", "animate", "slerp"]
