//! What a feature computation is asked to do: the settings with their defaults (DESIGN.md §1.10)
//! and the public names of the options, which the binding and the command line read from here.

mod compute;
mod options;
mod vertex_query;

pub use compute::ComputeSettings;
pub use options::{named_options, option_choices, Choice, GivenValue, OptionValue};
pub use vertex_query::VertexQuery;
