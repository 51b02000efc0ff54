//! Stage 4 of the pipeline (SPEC §1.4–§1.8): Monte Carlo sampling of the neighbourhood of every
//! point in parametric space.

mod coverage;
mod neighbourhood;
mod pattern;
mod reach;
mod tile;

pub use coverage::{gather_covering, MAX_MARGIN};
pub use neighbourhood::{
    arc_distance, centre_at, distance_inside, gather, unit_ellipse, Centre, Criterion, Sample, SampleCounts, SamplerSettings,
};
pub use pattern::{concentric_disk, disk_pattern, grid_shape, pcg_hash, pixel_angle, stratified_disk, TURNS};
pub use reach::{Reach, DIRECTIONS};
pub use tile::{neighbourhood_tile, NeighbourhoodTile};
