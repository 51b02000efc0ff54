//! Typed errors of the core. Every variant names the problem and, where there is one, the fix.

use thiserror::Error;

/// Everything that can go wrong in the core. Front ends map each variant to their own error types
/// (the Python binding maps them in one place); nothing in the core panics on bad input.
// Variant fields are the values quoted by each message.
#[allow(missing_docs)]
#[derive(Debug, Error, Clone, PartialEq)]
pub enum UvfeatError {
    /// The mesh has no vertices or no faces.
    #[error("empty mesh: {vertices} vertices and {faces} faces (need at least one triangle)")]
    EmptyMesh { vertices: usize, faces: usize },

    /// A position coordinate is NaN or infinite.
    #[error("vertex {index} has a non-finite position {value:?} (NaN or Inf); clean the mesh first")]
    NonFinitePosition { index: usize, value: [f64; 3] },

    /// A UV coordinate is NaN or infinite.
    #[error("UV {index} is not finite {value:?} (NaN or Inf); fix the UV map or drop it to get an automatic atlas")]
    NonFiniteUv { index: usize, value: [f64; 2] },

    /// A face refers to a vertex (or UV) that does not exist.
    #[error("face {face} refers to {what} {index}, but there are only {count}")]
    IndexOutOfRange { face: usize, what: &'static str, index: i64, count: usize },

    /// Arrays whose lengths must agree do not.
    #[error("{what}: expected {expected}, got {got}")]
    ShapeMismatch { what: &'static str, expected: usize, got: usize },

    /// The mesh has no UV coordinates.
    #[error("the mesh has no UV coordinates; give `uvs`, or let uvfeat build an atlas (xatlas)")]
    NoUvs,

    /// UVs lie outside the unit square.
    #[error("UV {index} = {value:?} lies outside [0, 1]^2; normalise the UVs (uvfeat.Mesh does this with a warning)")]
    UvOutOfRange { index: usize, value: [f64; 2] },

    /// Every face has a zero-area UV triangle, so nothing can be rasterised.
    #[error("all {faces} faces have zero-area UV triangles: the UV map is degenerate")]
    AllUvDegenerate { faces: usize },

    /// Every face has repeated corners or zero area, so the surface has nothing to measure.
    #[error("all {faces} faces are degenerate (repeated corners or zero area): the mesh has no surface to measure")]
    DegenerateMesh { faces: usize },

    /// A buffer resolution is zero or absurdly large.
    #[error("resolution {resolution} is not valid: it must be a positive integer of at most {max}")]
    InvalidResolution { resolution: usize, max: usize },

    /// The requested buffers do not fit in the memory budget.
    #[error(
        "resolution {resolution} needs about {needed_mib} MiB of buffers, more than the {budget_mib} MiB \
         allowed; choose a smaller resolution"
    )]
    ResolutionTooLarge { resolution: usize, needed_mib: u64, budget_mib: u64 },

    /// A new frame's positions do not match the mesh.
    #[error("new positions have {got} vertices, the mesh has {expected}")]
    FrameVertexCount { expected: usize, got: usize },

    /// A parameter is outside its valid range.
    #[error("invalid {name}: {reason}")]
    InvalidParameter { name: &'static str, reason: String },

    /// A texel or parametric point is outside the buffers.
    #[error("point {point:?} is outside the parametric domain [0, 1]^2")]
    PointOutOfDomain { point: [f64; 2] },

    /// The caller asked the computation to stop ([`crate::cancel`]).
    #[error("interrupted")]
    Cancelled,
}

/// Result alias of the core.
pub type Result<T> = std::result::Result<T, UvfeatError>;
