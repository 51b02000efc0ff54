"""Pictures of parametric-space buffers (paper Fig. 1): PNG files, v up."""

from __future__ import annotations

import os

import numpy as np


def _to_image(rgba: np.ndarray) -> np.ndarray:
    """(R, R, 4) floats in [0, 1], row 0 = v = 0 -> uint8 picture with v up."""
    return (np.clip(np.flipud(rgba), 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)


def save_png(path: str | os.PathLike, rgba: np.ndarray) -> None:
    """Writes an (R, R, 3|4) float image in [0, 1] (buffer orientation) as PNG."""
    from PIL import Image

    from ..io import atomic_file

    with atomic_file(path) as partial:
        Image.fromarray(_to_image(rgba)).save(partial)


def _with_alpha(rgb: np.ndarray, mask: np.ndarray) -> np.ndarray:
    rgba = np.zeros(mask.shape + (4,), dtype=np.float64)
    rgba[mask, :3] = rgb[mask]
    rgba[mask, 3] = 1.0
    return rgba


def position_image(position: np.ndarray) -> np.ndarray:
    """Positions normalised to RGB by the bounding box (empty texels transparent)."""
    position = position.astype(np.float64)
    mask = np.isfinite(position).all(axis=-1)
    low = position[mask].min(axis=0)
    extent = np.maximum(position[mask].max(axis=0) - low, 1e-300)
    return _with_alpha(np.where(mask[..., None], (position - low) / extent, 0.0), mask)


def normal_image(normal: np.ndarray) -> np.ndarray:
    """Unit normals mapped to RGB as ``(n + 1) / 2``."""
    normal = normal.astype(np.float64)
    mask = np.isfinite(normal).all(axis=-1)
    return _with_alpha(np.where(mask[..., None], (normal + 1.0) / 2.0, 0.0), mask)


def chart_colours(n: int) -> np.ndarray:
    """(n, 3) distinct, deterministic colours (golden-ratio hue walk, matplotlib HSV->RGB)."""
    from matplotlib.colors import hsv_to_rgb

    k = np.arange(max(n, 1))
    hsv = np.stack([(k * 0.6180339887) % 1.0, 0.55 + 0.35 * ((k * 7) % 3) / 2, 0.75 + 0.2 * ((k * 5) % 2)], axis=1)
    return hsv_to_rgb(hsv)[:n]


def chart_image(chart: np.ndarray, border: np.ndarray, adjacent_chart: np.ndarray) -> np.ndarray:
    """Chart ids colourised; border texels in the colour of the chart across the seam (darkened),
    texels on a mesh border white (paper Fig. 1d)."""
    mask = chart >= 0
    colours = chart_colours(int(chart.max()) + 1 if mask.any() else 1)
    rgb = np.zeros(chart.shape + (3,))
    rgb[mask] = colours[chart[mask]]
    seam = border & (adjacent_chart >= 0)
    rgb[seam] = 0.6 * colours[adjacent_chart[seam]]
    rgb[border & (adjacent_chart < 0)] = 1.0
    return _with_alpha(rgb, mask)


def scalar_image(values: np.ndarray, cmap: str = "viridis", *, low: float | None = None, high: float | None = None,
                 percentiles: tuple[float, float] = (1.0, 99.0)) -> tuple[np.ndarray, float, float]:
    """A scalar map through a matplotlib colormap, clamped at robust percentiles unless
    ``low``/``high`` are given; NaN texels transparent. Returns ``(rgba, low, high)``."""
    import matplotlib

    mask = np.isfinite(values)
    finite = values[mask]
    if low is None or high is None:
        lo, hi = np.percentile(finite, percentiles) if finite.size else (0.0, 1.0)
        low = lo if low is None else low
        high = hi if high is None else high
    span = high - low if high > low else 1.0
    rgb = matplotlib.colormaps[cmap](np.clip((np.where(mask, values, low) - low) / span, 0.0, 1.0))[..., :3]
    return _with_alpha(rgb, mask), float(low), float(high)


def distortion_image(sigma: np.ndarray) -> np.ndarray:
    """Anisotropy ``sigma_1 / sigma_2`` (1 = conformal), log-scaled, viridis."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.log2(sigma[..., 0].astype(np.float64) / sigma[..., 1])
    ratio[~np.isfinite(ratio)] = np.nan
    rgba, _, _ = scalar_image(ratio, "viridis", percentiles=(0.0, 99.0))
    return rgba


def save_atlas_pictures(atlas, out_dir: str | os.PathLike) -> dict[str, str]:
    """Writes position, normal, chart and distortion pictures of an atlas; returns their paths."""
    os.makedirs(out_dir, exist_ok=True)
    pictures = {
        "position": position_image(atlas.position),
        "normal": normal_image(atlas.normal),
        "charts": chart_image(atlas.chart, atlas.border, atlas.adjacent_chart),
        "distortion": distortion_image(atlas.sigma),
    }
    paths = {}
    for name, rgba in pictures.items():
        paths[name] = os.path.join(os.fspath(out_dir), f"{name}.png")
        save_png(paths[name], rgba)
    return paths


def save_figure(fig, path: str | os.PathLike, **options) -> None:
    """Writes ``fig`` as a PNG cropped to what it draws, as ``bbox_inches="tight"`` does, at zlib
    level 1 (three to four times faster to encode than level 6, for 10-15 % larger files: a
    200K-face mesh's three views take 0.08 s less). The crop is measured without drawing:
    matplotlib's "tight" draws the whole figure once more to measure it, resampling every image
    twice (0.06 s of a feature map's 0.26 s), for the same pixels."""
    import matplotlib

    from ..io import atomic_file

    crop = fig.get_tightbbox(fig.canvas.get_renderer()).padded(matplotlib.rcParams["savefig.pad_inches"])
    with atomic_file(path) as partial:
        fig.savefig(partial, bbox_inches=crop, pil_kwargs={"compress_level": 1}, **options)

#: Features whose sign matters get a diverging colormap centred on 0.
SIGNED_FEATURES = {"mean_curvature", "gaussian_curvature", "k1", "k2", "shape_index"}

#: Units shown on colourbars.
FEATURE_UNITS = {
    "bending_energy": "1/length²", "open_volume": "length³", "volume_invariant": "length³",
    "mean_curvature": "1/length", "gaussian_curvature": "1/length²", "k1": "1/length", "k2": "1/length",
    "shape_index": "", "curvedness": "1/length",
}


def colour_range(name: str, values: np.ndarray, percentiles: tuple[float, float] = (2.0, 98.0)) -> tuple[str, float, float]:
    """Colormap and robust range of a feature: symmetric percentile clamp with a diverging map for
    signed features ([-1, 1] for the shape index), percentiles with viridis otherwise."""
    finite = values[np.isfinite(values)]
    if name == "shape_index":
        return "RdBu_r", -1.0, 1.0
    if finite.size == 0:
        return ("RdBu_r" if name in SIGNED_FEATURES else "viridis"), -1.0, 1.0
    if name in SIGNED_FEATURES:
        bound = float(np.percentile(np.abs(finite), percentiles[1])) or 1.0
        return "RdBu_r", -bound, bound
    low, high = (float(x) for x in np.percentile(finite, percentiles))
    return "viridis", low, high if high > low else low + 1.0


def colour_values(values: np.ndarray, cmap: str, low: float, high: float) -> np.ndarray:
    """(n, 3) float RGB of values through ``cmap`` clamped to ``[low, high]``, 0.5 grey where NaN."""
    import matplotlib

    span = high - low if high > low else 1.0
    rgb = matplotlib.colormaps[cmap](np.clip((np.nan_to_num(values, nan=low) - low) / span, 0.0, 1.0))[..., :3]
    rgb[~np.isfinite(values)] = 0.5
    return rgb


def vertex_colours(name: str, values: np.ndarray) -> np.ndarray:
    """(n, 4) uint8 colours of per-vertex values (grey where NaN), same mapping as the pictures."""
    rgba = np.full(values.shape + (4,), 255, dtype=np.uint8)
    rgba[..., :3] = np.round(colour_values(values, *colour_range(name, values)) * 255).astype(np.uint8)
    return rgba


def offscreen_figure(figsize: tuple[float, float], dpi: int):
    """A matplotlib Figure drawn by the Agg canvas, outside pyplot: writing pictures neither needs
    a display nor changes the caller's backend or open figures (``fig.canvas.buffer_rgba()`` gives
    the pixels)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, dpi=dpi)
    FigureCanvasAgg(fig)
    return fig


def save_feature_figure(path: str | os.PathLike, name: str, texture: np.ndarray, radius: float, mesh_name: str = "",
                        line_field: np.ndarray | None = None) -> None:
    """The feature map as a picture with a colourbar (v up, robust range, NaN transparent), with
    ``line_field`` (``(W, W, 2)`` UV directions, e.g. a principal direction) drawn as segments."""
    cmap, low, high = colour_range(name, texture)
    fig = offscreen_figure((6.4, 5.4), 120)
    ax = fig.subplots()
    image = ax.imshow(np.flipud(texture), cmap=cmap, vmin=low, vmax=high, interpolation="nearest")
    if line_field is not None:
        from .line_field import draw_line_field

        draw_line_field(ax, line_field)
    ax.set_axis_off()
    unit = FEATURE_UNITS.get(name, "")
    ax.set_title(f"{mesh_name} {name} (r = {radius:.4g})".strip())
    fig.colorbar(image, ax=ax, fraction=0.046, pad=0.04, label=unit)
    save_figure(fig, path, transparent=False)


def feature_picture(name: str, texture: np.ndarray, low: float, high: float) -> np.ndarray:
    """(R, R, 3) uint8 picture of a feature map (v up) in a fixed colour range (the feature's
    colormap, as :func:`colour_range` picks it), white off the charts: one frame of an animation."""
    cmap = colour_range(name, texture)[0]
    rgba, _, _ = scalar_image(texture, cmap, low=low, high=high)
    rgba[..., :3] += 1.0 - rgba[..., 3:]  # colours are 0 where transparent: this paints those white
    return _to_image(rgba[..., :3])


def save_gif(path: str | os.PathLike, pictures: list[np.ndarray], fps: float) -> None:
    """An endlessly looping animated GIF of uint8 RGB pictures at ``fps`` frames per second."""
    from PIL import Image

    frames = [Image.fromarray(p) for p in pictures]
    frames[0].save(os.fspath(path), save_all=True, append_images=frames[1:], duration=max(20, round(1000 / fps)),
                   loop=0)


def save_mp4(path: str | os.PathLike, pictures: list[np.ndarray], fps: float) -> None:
    """An H.264 MP4 of uint8 RGB pictures at ``fps`` frames per second, through the ffmpeg that
    the ``imageio-ffmpeg`` wheel ships (``pip install 'uvfeat[video]'``); pictures are padded
    white to even sizes, which the yuv420p pixel format players expect needs."""
    from ..extras import require

    imageio_ffmpeg = require("imageio_ffmpeg", "writing MP4")
    height, width = (n + n % 2 for n in pictures[0].shape[:2])
    writer = imageio_ffmpeg.write_frames(os.fspath(path), (width, height), fps=fps, codec="libx264",
                                         pix_fmt_out="yuv420p", macro_block_size=1, quality=7)
    writer.send(None)  # starts ffmpeg
    for picture in pictures:
        padded = np.full((height, width, 3), 255, dtype=np.uint8)
        padded[:picture.shape[0], :picture.shape[1]] = picture
        writer.send(np.ascontiguousarray(padded))
    writer.close()
