//! Stage 2 of the pipeline: the atlas, a mesh's topology, its rasterised coverage and the current
//! frame's geometry buffers (DESIGN.md §1.2–§1.3), rebuilt per frame by [`Atlas::update`] without
//! redoing the pre-processing.

use crate::cancel;
use crate::error::{Result, UvfeatError};
use crate::frame::Frame;
use crate::mesh::{SeamMap, Topology};
use crate::raster::{Coverage, FacePatches, GeometryBuffers, Precision, Surface, Surfels};
use glam::{DVec2, DVec3};
use std::sync::{Arc, OnceLock};

/// Largest accepted buffer resolution (texels per side).
pub const MAX_RESOLUTION: usize = 32768;

/// How to build an [`Atlas`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtlasOptions {
    /// Geometry-buffer resolution `W_g` (texels per side; default 1024).
    pub resolution: usize,
    /// Storage precision of positions and normals.
    pub precision: Precision,
    /// Largest number of bytes the buffers may take.
    pub memory_budget: u64,
    /// Rasterise the coverage, and build the faces' patches and seam maps, on their first use
    /// instead of beside the frame (an atlas for the values at the vertices, which read only the
    /// surfels).
    pub coverage_on_first_use: bool,
}

impl Default for AtlasOptions {
    fn default() -> Self {
        Self { resolution: 1024, precision: Precision::F32, memory_budget: 8 << 30, coverage_on_first_use: false }
    }
}

/// Parametric-space representation of a mesh at one resolution.
#[derive(Debug, Clone)]
pub struct Atlas {
    /// Pre-processing shared by all frames (and by atlases of other resolutions).
    pub topology: Arc<Topology>,
    /// Texels per side.
    resolution: usize,
    /// Which surface point each texel shows (UV-only, reused by all frames; see
    /// [`Atlas::coverage`]).
    coverage: OnceLock<Coverage>,
    /// What [`Atlas::coverage`] gives while a stop request cuts its rasterisation short.
    stopped_coverage: OnceLock<Coverage>,
    /// Per-frame mesh quantities.
    pub frame: Frame,
    /// Per-frame geometry buffers, evaluated on first use (see [`Atlas::buffers`]).
    buffers: OnceLock<GeometryBuffers>,
    /// Per-frame surfel pyramids on the smooth surface and on the facets, built on first use (see
    /// [`Atlas::surfels`]).
    surfels: [OnceLock<Surfels>; 2],
    /// Per-frame compact surface patches of the faces (see [`Atlas::patches`]).
    patches: OnceLock<FacePatches>,
    /// Per-frame transition maps of the boundary sides (see [`Atlas::seam_maps`]).
    seam_maps: OnceLock<Vec<Option<SeamMap>>>,
    /// Storage precision of positions and normals.
    pub precision: Precision,
}

impl Atlas {
    /// Rasterises `topology` and evaluates the buffers for `positions` (one row per input vertex).
    ///
    /// # Errors
    /// [`UvfeatError::InvalidResolution`], [`UvfeatError::ResolutionTooLarge`] (with the memory it
    /// would take), and the position errors of [`Frame::new`].
    pub fn new(topology: Arc<Topology>, positions: &[DVec3], options: &AtlasOptions) -> Result<Self> {
        check_resolution(options)?;
        // The pattern's maps read the faces' patches and seam maps besides the coverage, which
        // depends on the UVs only: it is rasterised while the frame and those tables are
        // evaluated, so that the one-thread parts of each overlap (the patches built after the
        // join left one core idle for 20-30 ms of a 200K-face mesh's atlas). The values at the
        // vertices read none of the three: such an atlas builds each on first use (the dragon's
        // seam maps and patches: 25-35 ms of its 35-50 ms frame).
        let eager = !options.coverage_on_first_use;
        let frame_and_tables = || {
            let frame = Frame::new(&topology, positions)?;
            cancel::check()?;
            let tables = eager.then(|| (FacePatches::new(&topology, &frame), frame.seam_maps(&topology)));
            Ok((frame, tables))
        };
        let ((frame, tables), coverage) = if eager {
            let (frame, coverage) = rayon::join(frame_and_tables, || Coverage::build(&topology, options.resolution));
            (frame?, OnceLock::from(coverage))
        } else {
            (frame_and_tables()?, OnceLock::new())
        };
        let (patches, seam_maps) = match tables {
            Some((patches, seam_maps)) => (OnceLock::from(patches), OnceLock::from(seam_maps)),
            None => (OnceLock::new(), OnceLock::new()),
        };
        cancel::check()?;
        Ok(Self {
            topology,
            resolution: options.resolution,
            coverage,
            stopped_coverage: OnceLock::new(),
            frame,
            buffers: OnceLock::new(),
            surfels: Default::default(),
            patches,
            seam_maps,
            precision: options.precision,
        })
    }

    /// Which surface point each texel shows (DESIGN.md §1.2). With
    /// [`AtlasOptions::coverage_on_first_use`] it is rasterised here, when first asked for: the
    /// values at the vertices read the surfels only (Spot's atlas for them at r = 4 %: 3.5 -> 2.2
    /// ms, Bob's 4.7 -> 1.7). While a stop request cuts that short it is not kept (the next use
    /// rasterises again) and the stopped caller sees empty texels.
    pub fn coverage(&self) -> &Coverage {
        built_once(
            &self.coverage,
            || Coverage::build(&self.topology, self.resolution),
            || self.stopped_coverage.get_or_init(|| Coverage::empty(self.resolution)),
        )
    }

    /// The geometry buffers of the frame (DESIGN.md §1.3: position, normal, metric per texel). The
    /// default triangle lookup reads the faces and their patches, not these, so they are
    /// evaluated on first use (the bilinear lookup, the buffer getters): an animation frame
    /// computed with the defaults never pays for them (~20 ms and 36 MB at 1024²).
    pub fn buffers(&self) -> &GeometryBuffers {
        // The coverage first, outside the cell (see `built_once`).
        let coverage = self.coverage();
        self.buffers.get_or_init(|| GeometryBuffers::evaluate(&self.topology, coverage, &self.frame, self.precision))
    }

    /// The surfel pyramid of the frame on `surface` (DESIGN.md §1.4.8), built on first use by
    /// `quadrature = "surfels"`. A build stopped part way ([`cancel`]) is not kept: the call gives
    /// an empty pyramid, and the next builds it whole.
    pub fn surfels(&self, surface: Surface) -> &Surfels {
        static NONE: Surfels = Surfels::empty();
        let cell = &self.surfels[usize::from(surface == Surface::Smooth)];
        // Asked per point: once stopped, no point starts a build of its own.
        if cell.get().is_none() && cancel::requested() {
            return &NONE;
        }
        built_once(cell, || Surfels::build(&self.topology, &self.frame, self.resolution(), surface), || &NONE)
    }

    /// The compact surface patches of the faces (the pattern's fast path), built with the frame,
    /// or on first use with [`AtlasOptions::coverage_on_first_use`].
    pub fn patches(&self) -> &FacePatches {
        kept_once(&self.patches, || FacePatches::new(&self.topology, &self.frame))
    }

    /// The transition map of each boundary side (`None` where nothing is across), which the
    /// pattern's samples cross seams by; built with the frame, or on first use with
    /// [`AtlasOptions::coverage_on_first_use`].
    pub fn seam_maps(&self) -> &[Option<SeamMap>] {
        kept_once::<Vec<_>>(&self.seam_maps, || self.frame.seam_maps(&self.topology))
    }

    /// Re-evaluates the per-frame quantities (normals, metrics, and the seam maps and patches
    /// where built; the buffers and surfels on their next use) for new positions; charts,
    /// coverage, border texels and edge tables are reused.
    ///
    /// # Errors
    /// Vertex count mismatch or non-finite positions; the atlas is unchanged then.
    pub fn update(&mut self, positions: &[DVec3]) -> Result<()> {
        self.frame.refresh(&self.topology, positions)?;
        self.buffers = OnceLock::new();
        self.surfels = Default::default();
        if let Some(patches) = self.patches.get_mut() {
            patches.refresh(&self.topology, &self.frame);
        }
        if let Some(seam_maps) = self.seam_maps.get_mut() {
            *seam_maps = self.frame.seam_maps(&self.topology);
        }
        Ok(())
    }

    /// Texels per side.
    pub fn resolution(&self) -> usize {
        self.resolution
    }

    /// Index of the texel containing the parametric point `uv`; `None` outside `[0, 1)^2`.
    pub fn texel_at(&self, uv: DVec2) -> Option<usize> {
        self.texel_coordinates(uv).map(|(i, j)| j * self.resolution() + i)
    }

    /// Column and row `(i, j)` of the texel containing `uv`; `None` outside the unit square.
    #[inline]
    pub fn texel_coordinates(&self, uv: DVec2) -> Option<(usize, usize)> {
        let r = self.resolution() as f64;
        let (x, y) = (uv.x * r, uv.y * r);
        if !(x >= 0.0 && y >= 0.0 && x < r && y < r) {
            return None;
        }
        Some((x as usize, y as usize))
    }

    /// Chart id at `uv` (-1 for empty texels and points outside the domain).
    pub fn chart_at(&self, uv: DVec2) -> i32 {
        self.texel_at(uv).map_or(-1, |t| self.coverage().chart[t])
    }

    /// The texel containing `uv` if `accept` takes it, else the accepted texel of the 3x3
    /// neighbourhood whose centre is closest to `uv` (the fallback of DESIGN.md §1.3.6 for points in gutters).
    pub fn nearest_texel(&self, uv: DVec2, accept: impl Fn(usize) -> bool) -> Option<usize> {
        if let Some(t) = self.texel_at(uv).filter(|&t| accept(t)) {
            return Some(t);
        }
        let n = self.resolution() as i64;
        let (ci, cj) = ((uv.x * n as f64).floor() as i64, (uv.y * n as f64).floor() as i64);
        let mut best: Option<(f64, usize)> = None;
        for j in (cj - 1).max(0)..=(cj + 1).min(n - 1) {
            for i in (ci - 1).max(0)..=(ci + 1).min(n - 1) {
                let t = (j * n + i) as usize;
                if !accept(t) {
                    continue;
                }
                let d = self.texel_centre(t).distance_squared(uv);
                if best.is_none_or(|(bd, _)| d < bd) {
                    best = Some((d, t));
                }
            }
        }
        best.map(|(_, t)| t)
    }

    /// Centre of texel `t` in parametric coordinates.
    pub fn texel_centre(&self, t: usize) -> DVec2 {
        crate::raster::texel_centre(t, self.resolution)
    }
}

/// `cell`'s value, built on first use by `build`; a build that a stop request cut short is not
/// kept, and the caller gets `stopped()` instead. Built outside the cell: a build's parallel loops
/// may take on other work meanwhile that asks for this same value, and initialising a cell from
/// within its own initialisation deadlocks (two threads asking at once may both build; one is
/// kept).
fn built_once<'a, T>(cell: &'a OnceLock<T>, build: impl FnOnce() -> T, stopped: impl FnOnce() -> &'a T) -> &'a T {
    if let Some(value) = cell.get() {
        return value;
    }
    let value = build();
    if cancel::requested() {
        return stopped();
    }
    cell.get_or_init(|| value)
}

/// The value of `cell`, built by `build` on its first use, outside the cell (as [`built_once`],
/// for a value no stop request cuts short).
fn kept_once<T>(cell: &OnceLock<T>, build: impl FnOnce() -> T) -> &T {
    if let Some(value) = cell.get() {
        return value;
    }
    let value = build();
    cell.get_or_init(|| value)
}

/// Bytes the coverage and one frame of buffers take at `resolution`.
pub fn buffer_bytes(resolution: usize) -> u64 {
    (resolution as u64).pow(2) * Coverage::BYTES_PER_TEXEL
}

/// Bytes per face of the topology, one frame and the face patches: measured on a 1M-face torus
/// (topology 95, patches 128, frame 60; docs/RELIABILITY.md), rounded up.
pub const BYTES_PER_FACE: u64 = 320;

/// Bytes an atlas of a mesh of `n_faces` faces takes at `resolution`: its buffers and its
/// per-face tables.
pub fn atlas_bytes(resolution: usize, n_faces: usize) -> u64 {
    buffer_bytes(resolution) + n_faces as u64 * BYTES_PER_FACE
}

fn check_resolution(options: &AtlasOptions) -> Result<()> {
    if options.resolution == 0 || options.resolution > MAX_RESOLUTION {
        return Err(UvfeatError::InvalidResolution { resolution: options.resolution, max: MAX_RESOLUTION });
    }
    let needed = buffer_bytes(options.resolution);
    if needed > options.memory_budget {
        return Err(UvfeatError::ResolutionTooLarge {
            resolution: options.resolution,
            needed_mib: needed >> 20,
            budget_mib: options.memory_budget >> 20,
        });
    }
    Ok(())
}
