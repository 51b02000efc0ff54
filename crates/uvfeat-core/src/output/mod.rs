//! Stage 6 of the pipeline (DESIGN.md §1.9): feature maps over the computation texture and
//! per-vertex values.

mod feature_map;
mod options;
mod per_vertex;
mod pixel;
mod settings;

pub use feature_map::{FeatureMaps, MapSummary};
pub use options::{named_options, option_choices, Choice, GivenValue, OptionValue};
pub use per_vertex::{per_vertex, per_vertex_directions, VertexQuery};
pub use pixel::{evaluate_point, Patterns, PixelResult};
pub use settings::ComputeSettings;
