//! Stage 6 of the pipeline (DESIGN.md §1.9): feature maps over the computation texture,
//! per-vertex values, the neighbourhood samples of texel tiles for user-defined operators, and the
//! shaded pictures of per-vertex values on the mesh (the 3D pictures).

mod corners;
mod feature_map;
mod front_side;
mod neighbourhood_tiles;
mod per_vertex;
mod screen;
mod shaded_view;
mod sheet_area;
mod vertex_values;

pub use feature_map::{FeatureMaps, MapSummary, SEVERAL_SHEETS};
pub use front_side::front_side;
pub use neighbourhood_tiles::{neighbourhood_tile, NeighbourhoodTile};
pub use per_vertex::{per_corner, per_vertex, per_vertex_directions};
pub use screen::{rasterise_screen, ScreenFragments, NO_FACE};
pub use shaded_view::{shaded_view, ColourScale, Front, ViewFrame, AMBIENT};
pub use vertex_values::{sums_apply, vertex_values, vertex_values_at_radii, VertexValues};
