//! # uvfeat-core
//!
//! Multi-scale geometric features of triangle meshes computed in the mesh's UV parameter space
//! (Andreadis, Papaioannou, Mavridis, GRAPP 2015). The modules follow the six stages of the
//! pipeline (DESIGN.md §1), numbered as there and in each module's documentation:
//!
//! 1. mesh and charts: [`mesh`] (validated input, welding, charts, edge classes, seam transition
//!    maps) and [`unwrap`] (an automatic UV atlas for a mesh that has none);
//! 2. rasterised buffers: [`raster`] (coverage, per-frame geometry buffers, surfels) and
//!    [`atlas`], the object tying the stages together, rebuilt per frame;
//! 3. metric distortion and adjacency: [`distortion`] and [`frame`] (the per-frame quantities);
//! 4. neighbourhood sampling: [`sampling`], with [`relocation`] of parametric points across seams
//!    and [`lookup`] of the surface at a parametric point;
//! 5. feature estimators: [`features`], evaluated at one point and on a tile of texels by
//!    [`evaluation`];
//! 6. outputs: [`output`] (feature maps, per-vertex values, neighbourhood tiles).
//!
//! Beside them: [`settings`] (what a computation is asked), [`reference`](mod@reference) (the object-space
//! reference the parametric values are checked against), [`cancel`] (stopping a computation part
//! way), [`render`] (the 3D pictures of the outputs), [`shapes`] (analytic meshes) and [`stamps`] (the searches' scratch sets). No two modules
//! import each other, directly or through others (checked by the test suite).
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
pub mod render;
pub mod sampling;
pub mod settings;
pub mod shapes;
pub mod stamps;
pub mod unwrap;

pub use atlas::{Atlas, AtlasOptions};
pub use error::{Result, UvfeatError};
pub use raster::Precision;
