//! Integration tests of the core, one module per pipeline stage.

mod support;

mod errors;
mod features;
mod metric;
mod rasterisation;
mod seams;
