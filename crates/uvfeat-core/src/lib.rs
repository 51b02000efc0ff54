//! # uvfeat-core
//!
//! Multi-scale geometric features of triangle meshes computed in the mesh's UV parameter space
//! (Andreadis, Papaioannou, Mavridis, GRAPP 2015). The modules follow the pipeline, each using
//! only the ones above it (checked by the test suite):
//!
//! 1. [`mesh`]: validated input, welding, charts, edge classes, seam transition maps; and
//!    [`unwrap`], an automatic UV atlas for a mesh that has none;
//! 2. [`distortion`] and [`frame`]: the local metric and the per-frame quantities;
//! 3. [`raster`]: rasterised coverage and per-frame geometry buffers;
//! 4. [`atlas`]: the object tying them together, rebuilt per frame;
//! 5. [`relocation`] and [`lookup`]: seam crossing of parametric points, and the surface there;
//! 6. [`sampling`]: the Monte Carlo neighbourhood of a parametric point;
//! 7. [`features`]: the estimators over a neighbourhood's samples;
//! 8. [`settings`], [`evaluation`], [`tile_evaluation`] and [`output`]: what is asked, the
//!    features at one point and on a tile of texels, and the maps, per-vertex values and neighbourhood tiles;
//! 9. [`reference`]: the object-space reference the parametric values are checked against.
//!
//! Conventions (DESIGN.md §0): UV in `[0, 1]^2`, u right, v up; texel `(i, j)` of an `R x R` buffer is
//! at index `j * R + i`, centred at `((i + 0.5)/R, (j + 0.5)/R)`; normals outward by the
//! right-hand rule on counter-clockwise corners.
#![warn(missing_docs)]
// Validations write `!(x >= 0.0)` on purpose: unlike `x < 0.0`, it rejects NaN too.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod atlas;
pub mod cancel;
pub mod distortion;
pub mod error;
pub mod evaluation;
pub mod features;
pub mod frame;
pub mod lookup;
pub mod mesh;
pub mod output;
pub mod raster;
pub mod reference;
pub mod relocation;
pub mod sampling;
pub mod settings;
pub mod shapes;
pub mod stamps;
pub mod tile_evaluation;
pub mod unwrap;

pub use atlas::{Atlas, AtlasOptions};
pub use error::{Result, UvfeatError};
pub use raster::Precision;
