//! How per-vertex values are read from a computation (DESIGN.md §1.9).

/// How per-vertex values are obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum VertexQuery {
    /// Bilinear lookup in the feature maps (the paper's; falls back to `Direct` per vertex).
    #[default]
    Texture,
    /// Evaluate the estimators at each corner UV.
    Direct,
}
