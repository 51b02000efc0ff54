//! Stage 4 of the pipeline (DESIGN.md §1.4–§1.8): Monte Carlo sampling of the neighbourhood of every
//! point in parametric space.

mod coverage;
mod fast_path;
mod gather;
mod geodesic;
mod neighbourhood;
mod pattern;
mod per_chart;
mod reach;
mod tile;

pub use coverage::{gather_covering, MAX_MARGIN};
pub use fast_path::SamplingPath;
pub use gather::gather;
pub use geodesic::{arc_distance, Geodesic, CHORD_SEGMENTS};
pub use neighbourhood::{centre_at, Centre, Criterion, Sample, SampleCounts, SamplerSettings};
pub use pattern::{
    concentric_disk, disk_pattern, grid_shape, pcg_hash, pixel_angle, stratified_disk, Placement, TURNS,
};
pub use reach::Reach;
pub use tile::{neighbourhood_tile, NeighbourhoodTile};
