//! Stage 4 of the pipeline (DESIGN.md §1.4–§1.8): Monte Carlo sampling of the neighbourhood of every
//! point in parametric space. From the bottom up: the sampler's settings, the centre, the pattern
//! and its per-direction reach, the sampling domain, the samples and their acceptance, located
//! points turned into samples, then the gatherings (exact loop, fast path, per-chart repetition)
//! and the domain growth that repeats a gathering where the ball reached past the domain.

mod centre;
mod domain;
mod domain_growth;
mod fast_path;
mod gather;
mod geodesic;
mod lattice;
mod lattice_builder;
mod located;
mod pattern;
mod per_chart;
mod reach;
mod sample;
mod secant_metric;
mod settings;
mod sheets;
mod surfel_grid;
mod surfels;

pub use centre::{centre_at, texel_point, Centre, TexelPoint};
pub use domain_growth::{gather_covering, grow_marked, probed_reach, EDGE_RADIUS, MAX_MARGIN};
pub use fast_path::applies as fast_path_applies;
pub use gather::gather;
pub use geodesic::{arc_distance, Geodesic, CHORD_SEGMENTS};
pub use lattice::{LatticeDomain, LatticeTexel, LostPoint, TileLattice, TilePlane};
pub use pattern::{
    concentric_disk, disk_pattern, grid_shape, pcg_hash, pixel_angle, stratified_disk, Placement, TURNS,
};
pub use reach::{Reach, DIRECTIONS};
pub use sample::{moment_ramp_area, moment_ramp_centre, ramp_centre, Sample, SampleCounts};
pub use secant_metric::secant_distortion;
pub use settings::{Criterion, Overlaps, Quadrature, SamplerSettings, SamplingPath};
pub use surfel_grid::surfel_grid_width;
pub use surfels::{gather_surfels, levels_to_build, surfel_centre, SurfelBall, SurfelCount};
