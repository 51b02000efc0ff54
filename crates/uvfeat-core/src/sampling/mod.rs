//! Stage 4 of the pipeline (SPEC §1.4–§1.8): Monte Carlo sampling of the neighbourhood of every
//! point in parametric space.

mod coverage;
mod gather;
mod geodesic;
mod neighbourhood;
mod pattern;
mod per_chart;
mod reach;
mod tile;

pub use coverage::{gather_covering, MAX_MARGIN};
pub use gather::{distance_inside, gather};
pub use geodesic::{arc_distance, chord_sum_distance, Geodesic, CHORD_SEGMENTS};
pub use neighbourhood::{
    accept, centre_at, is_inside, unit_ellipse, unit_ellipse_area, Candidate, Centre, Criterion, Sample, SampleCounts,
    SamplerSettings,
};
pub use pattern::{
    concentric_disk, disk_pattern, grid_shape, pcg_hash, pixel_angle, stratified_disk, Placement, TURNS,
};
pub use per_chart::gather_per_chart;
pub use reach::{Reach, DIRECTIONS};
pub use tile::{neighbourhood_tile, NeighbourhoodTile};
