//! Settings of the sampler: the neighbourhood criterion, the relocation and lookup choices and
//! which path runs.

use super::geodesic::Geodesic;
use crate::lookup::Lookup;
use crate::raster::Surface;
use crate::relocation::Relocation;

/// Which samples belong to the neighbourhood `S(p, r)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Criterion {
    /// `|q - p| < r` (default; the paper's).
    #[default]
    Euclidean,
    /// Geodesic estimate `d(p, q) < r` (DESIGN.md §2.5; see [`Geodesic`]).
    Geodesic,
}

/// Settings of the sampler.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SamplerSettings {
    /// Neighbourhood radius `r` (object units).
    pub radius: f64,
    /// Ellipse coverage margin `m` (DESIGN.md §3.2; 1.25 default, 1 = paper).
    pub margin: f64,
    /// Seams a sample may cross (DESIGN.md §1.5; 32 default, 1 = paper).
    pub max_jumps: u32,
    /// How samples that leave the chart are relocated.
    pub relocation: Relocation,
    /// Neighbourhood criterion.
    pub criterion: Criterion,
    /// Surface lookup of the centre and the samples.
    pub lookup: Lookup,
    /// Geodesic distance estimate the samples carry.
    pub geodesic: Geodesic,
    /// Fast path for interior samples, or the exact path everywhere.
    pub path: SamplingPath,
    /// The samples' normals are used (bending energy, user operators); the fast path leaves them
    /// NaN otherwise (the exact path has them from its lookup anyway).
    pub with_normals: bool,
    /// The samples' geodesic distances are used (geodesic criterion or geodesic-area K); they are
    /// NaN otherwise (the estimate costs an `asin`, or a chord sum, per sample).
    pub with_geodesic: bool,
    /// What happens to surface reached along two routes through seams.
    pub overlaps: Overlaps,
    /// The surface the surfels lie on.
    pub surface: Surface,
    /// Surfels a plane's ball is summed over (`quadrature = "surfels"`: the `samples` option).
    pub surfels_per_ball: f64,
}

/// Surface that the sampling domain reaches twice. Across seams the domain is carried by the
/// seams' hinge maps, which develop the surface into the centre's plane: around convex regions
/// the developed domain overlaps itself, so part of the surface is sampled along two routes and
/// counts twice (on a 266-chart armadillo at r = 6 %, a fifth of the neighbourhoods hold over
/// 1.1x the ball's area, which biases H up by 7 %).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Overlaps {
    /// Keep every sample (default for now; the paper's behaviour).
    #[default]
    Keep,
    /// Keep a sample only when no route into its chart with fewer seam crossings reaches the
    /// same point (`sampling/sheets.rs`). Costs a second walk per crossing sample and a check
    /// walk per competing route (3.5x the time on the armadillo at 6 %).
    Drop,
}

/// How a neighbourhood is summed (DESIGN.md §1.4.8).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Quadrature {
    /// The paper's Monte Carlo pattern over a disk of the centre's parametric plane, carried
    /// across seams by hinge maps (default).
    #[default]
    Pattern,
    /// The atlas's surfels connected to the centre inside the ball, each counted once with its
    /// exact area (`sampling/surfels.rs`): no surface counted twice where the development overlaps
    /// itself, no gaps behind saddles; deterministic, so no adaptive stages or standard errors.
    Surfels,
}

/// Which sampler runs: one lattice of samples shared by a tile of texels, the fast path where it
/// keeps the exact path's answers, or the exact path everywhere (the reference of both).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SamplingPath {
    /// Feature maps sample one jittered lattice per tile of texels, located once and shared by
    /// every texel whose sampling domain it covers (see `sampling/lattice.rs`); texels and
    /// settings it does not serve take the fast path (default).
    #[default]
    Shared,
    /// Interior samples straight from the face-id buffer and the f32 patches.
    Fast,
    /// Every sample located and evaluated on its own, in f64.
    Exact,
}
