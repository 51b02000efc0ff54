//! Stage 6 of the pipeline (DESIGN.md §1.9): feature maps over the computation texture,
//! per-vertex values, and the neighbourhood samples of texel tiles for user-defined operators.

mod feature_map;
mod neighbourhood_tiles;
mod per_vertex;

pub use feature_map::{FeatureMaps, MapSummary, SEVERAL_SHEETS};
pub use neighbourhood_tiles::{neighbourhood_tile, NeighbourhoodTile};
pub use per_vertex::{per_vertex, per_vertex_directions};
