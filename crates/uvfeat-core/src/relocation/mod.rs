//! Stage 4 of the pipeline: relocation of parametric points that leave their chart (DESIGN.md §1.5,
//! paper §3.4): where does an offset of a point end up on the surface, in which chart, and through
//! which seams.
//!
//! Two methods: the exact triangle walk ([`walk`], default) and the texel march of DESIGN.md §1.5.2
//! ([`march`]). Both take the paper's fast path first: a target well inside the start chart (see
//! [`interior_face`]) is returned as it is.

mod march;
mod walk;

pub use march::{border_texel, cross_seam, last_inside, march, Crossing};
pub use walk::{home, walk, walk_across, Home, Seams};

use crate::atlas::Atlas;
use glam::{DMat2, DVec2};

/// Where a parametric point ends up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Located {
    /// The point lies in `chart` at `uv`; `m_path` is the product of the crossed seams' linear
    /// maps (identity when none was crossed), so `|det m_path|` rescales parametric areas. `face`
    /// is the face containing `uv` when the method found it (the walk), else `None` (the lookup
    /// then uses the face of the texel).
    #[allow(missing_docs)]
    Inside { chart: i32, uv: DVec2, m_path: DMat2, jumps: u32, face: Option<u32> },
    /// The path reached the mesh border: the point is off the surface.
    Border,
    /// No way across was found, or more than `max_jumps` seams were needed.
    Missing,
}

/// How samples that leave their chart are relocated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Relocation {
    /// Exact triangle walk across face adjacency and seams (default).
    #[default]
    Walk,
    /// The texel march of DESIGN.md §1.5, through border texels.
    March,
    /// The paper's per-chart pattern repetition (DESIGN.md §1.6): the whole pattern is evaluated again
    /// around the centre carried into each neighbouring chart (see `sampling::gather_per_chart`).
    /// A single point located on its own is marched.
    PerChart,
}

/// The face of the texel of `target` when that texel belongs to `chart`, its 3x3 neighbourhood is
/// all `chart` and no chart boundary touches it: the point is in the chart, reached without
/// crossing anything (up to the known limitation of DESIGN.md §1.5.3, a target in its own chart across a gap of
/// a non-convex chart; the Euclidean rejection removes those samples, and checking the whole
/// segment instead tripled the time on a 692-chart torus without changing its per-vertex values
/// beyond noise). It is the face the triangle lookup evaluates for that point. `None` otherwise.
#[inline]
pub fn interior_face(atlas: &Atlas, target: DVec2, chart: i32) -> Option<u32> {
    let (i, j) = atlas.texel_coordinates(target)?;
    interior_of_chart(atlas, atlas.coverage().interior_face.at(i, j), chart)
}

/// `face`, a value of the interior table ([`interior_face`]), when it is a face of `chart`.
#[inline]
pub fn interior_of_chart(atlas: &Atlas, face: u32, chart: i32) -> Option<u32> {
    (face != u32::MAX && atlas.topology.face_chart[face as usize] == chart).then_some(face)
}

/// Locates `target`, an offset of `start` in `chart`, with `method` (DESIGN.md §1.5 `locate`).
/// `home` is the walk's start, `home(atlas, start, chart)`, when the caller has it already.
pub fn locate_with(
    atlas: &Atlas,
    method: Relocation,
    start: DVec2,
    home: Option<&Home>,
    chart: i32,
    target: DVec2,
    max_jumps: u32,
) -> Located {
    if let Some(face) = interior_face(atlas, target, chart) {
        return Located::Inside { chart, uv: target, m_path: DMat2::IDENTITY, jumps: 0, face: Some(face) };
    }
    match method {
        Relocation::March | Relocation::PerChart => march(atlas, start, chart, target, max_jumps),
        Relocation::Walk => match home.copied().or_else(|| walk::home(atlas, start, chart)) {
            Some(home) => walk(atlas, &home, target, max_jumps),
            None => Located::Missing,
        },
    }
}

/// Locates `target`, an offset of `start` in `chart`, with the default method (the exact walk).
pub fn locate(atlas: &Atlas, start: DVec2, chart: i32, target: DVec2, max_jumps: u32) -> Located {
    locate_with(atlas, Relocation::Walk, start, None, chart, target, max_jumps)
}
