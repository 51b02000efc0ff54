//! Stage 4 of the pipeline (SPEC §1.4–§1.8): Monte Carlo sampling of the neighbourhood of every
//! point in parametric space.

mod neighbourhood;
mod pattern;
mod tile;

pub use neighbourhood::{
    arc_distance, centre_at, ellipse_area, gather, Centre, Criterion, Sample, SampleCounts, SamplerSettings,
};
pub use tile::{neighbourhood_tile, NeighbourhoodTile};
pub use pattern::{concentric_disk, disk_pattern, grid_shape, pcg_hash, pixel_angle, stratified_disk, TURNS};
