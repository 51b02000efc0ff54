//! Stage 6 of the pipeline (DESIGN.md §1.9): feature maps over the computation texture,
//! per-vertex values, the neighbourhood samples of texel tiles for user-defined operators, and the
//! screen rasterisation behind the 3D pictures of per-vertex values.

mod feature_map;
mod neighbourhood_tiles;
mod per_vertex;
mod screen;

pub use feature_map::{FeatureMaps, MapSummary, SEVERAL_SHEETS};
pub use neighbourhood_tiles::{neighbourhood_tile, NeighbourhoodTile};
pub use per_vertex::{per_corner, per_vertex, per_vertex_directions};
pub use screen::{rasterise_screen, ScreenFragments, NO_FACE};
