//! Stage 6 of the pipeline (DESIGN.md §1.9): feature maps over the computation texture,
//! per-vertex values and the neighbourhood samples of texel tiles for user-defined operators.

mod corners;
mod feature_map;
mod neighbourhood_tiles;
mod per_vertex;
mod sheet_area;
mod vertex_values;

pub use feature_map::{FeatureMaps, MapSummary, SEVERAL_SHEETS};
pub use neighbourhood_tiles::{neighbourhood_tile, NeighbourhoodTile};
pub use per_vertex::{per_corner, per_vertex, per_vertex_directions};
pub use vertex_values::{sums_apply, vertex_values, vertex_values_at_radii, VertexValues};
