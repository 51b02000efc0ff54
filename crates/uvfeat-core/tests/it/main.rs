//! Integration tests of the core, one module per pipeline stage.

mod support;

mod coverage;
mod errors;
mod fast_path;
mod features;
mod fit;
mod geodesics;
mod metric;
mod rasterisation;
mod reference;
mod seams;
mod shared_lattice;
mod surfels;
mod unwrap;
