//! Stage 2 of the pipeline (DESIGN.md §1.3): rasterisation of the charts into parametric-space buffers.

mod blocked;
mod boundary;
mod buffers;
mod coverage;
mod morton;
mod patches;
mod surfel_fragments;
mod surfels;
mod triangles;

pub use blocked::Blocked;
pub(crate) use boundary::closest_on_segment;
pub use buffers::{GeometryBuffers, Precision};
pub use coverage::{texel_centre, Coverage, CoverageDiagnostics};
pub use morton::morton;
pub use patches::{FacePatch, FacePatches};
pub use surfels::{Surface, SurfelLevel, SurfelPoint, Surfels};
