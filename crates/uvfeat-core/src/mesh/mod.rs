//! Stage 1 of the pipeline (DESIGN.md §1.1–§1.2): the validated input mesh and its UV-only
//! pre-processing (welding, charts, edge classes), plus the per-frame quantities that depend on
//! positions (vertex normals, triangle metrics, seam transition maps).

mod adjacency;
mod charts;
mod corners;
mod edges;
mod jacobian;
mod normals;
mod sides;
mod topology;
mod transition;
mod vertex_sort;
mod weld;

pub use adjacency::{EdgeLink, WalkFace};
pub use corners::NO_CORNER;
pub(crate) use edges::sorted_half_edges;
pub use edges::{EdgeCounts, SideKind};
pub use jacobian::{linear_gradient, uv_inverse, Jacobian};
pub use normals::{unit_face_normal, vertex_normals};
pub use sides::BoundarySide;
pub use topology::{Topology, TopologyDiagnostics};
pub use transition::{seam_maps, SeamMap};
pub(crate) use vertex_sort::compressed_rows;
pub use weld::weld_positions;
pub(crate) use weld::{find, union};

use crate::error::{Result, UvfeatError};
use glam::{DVec2, DVec3};

/// A triangle mesh with per-corner UVs, validated (DESIGN.md §1.1).
///
/// `uv_faces[f][k]` indexes `uvs` for corner `k` of face `f` (OBJ style); for per-vertex UVs pass
/// `uv_faces = faces`. Corners are counter-clockwise seen from outside (outward normals).
#[derive(Debug, Clone)]
pub struct TriangleMesh {
    /// (n_vertices) positions in object units.
    pub positions: Vec<DVec3>,
    /// (n_faces) vertex indices per face.
    pub faces: Vec<[u32; 3]>,
    /// (n_uvs) parametric coordinates in `[0, 1]^2`, u right, v up.
    pub uvs: Vec<DVec2>,
    /// (n_faces) UV indices per face corner.
    pub uv_faces: Vec<[u32; 3]>,
}

impl TriangleMesh {
    /// Validates and builds a mesh from flat arrays.
    ///
    /// # Errors
    /// [`UvfeatError::EmptyMesh`], [`UvfeatError::NonFinitePosition`], [`UvfeatError::NonFiniteUv`],
    /// [`UvfeatError::UvOutOfRange`], [`UvfeatError::IndexOutOfRange`], [`UvfeatError::NoUvs`].
    pub fn new(positions: &[[f64; 3]], faces: &[[i64; 3]], uvs: &[[f64; 2]], uv_faces: &[[i64; 3]]) -> Result<Self> {
        if positions.is_empty() || faces.is_empty() {
            return Err(UvfeatError::EmptyMesh { vertices: positions.len(), faces: faces.len() });
        }
        if uvs.is_empty() {
            return Err(UvfeatError::NoUvs);
        }
        if uv_faces.len() != faces.len() {
            return Err(UvfeatError::ShapeMismatch {
                what: "uv_faces must have one row per face",
                expected: faces.len(),
                got: uv_faces.len(),
            });
        }
        let positions = checked_positions(positions)?;
        if let Some((index, uv)) = uvs.iter().enumerate().find(|(_, uv)| !uv.iter().all(|c| c.is_finite())) {
            return Err(UvfeatError::NonFiniteUv { index, value: *uv });
        }
        if let Some((index, uv)) = uvs.iter().enumerate().find(|(_, uv)| uv.iter().any(|c| !(0.0..=1.0).contains(c))) {
            return Err(UvfeatError::UvOutOfRange { index, value: *uv });
        }
        Ok(Self {
            faces: checked_indices(faces, positions.len(), "vertex")?,
            positions,
            uvs: uvs.iter().map(|uv| DVec2::from_array(*uv)).collect(),
            uv_faces: checked_indices(uv_faces, uvs.len(), "uv")?,
        })
    }

    /// UVs of the three corners of face `f`.
    pub fn corner_uvs(&self, f: usize) -> [DVec2; 3] {
        self.uv_faces[f].map(|k| self.uvs[k as usize])
    }
}

/// Positions as vectors, once every coordinate is known to be finite.
///
/// # Errors
/// [`UvfeatError::NonFinitePosition`] naming the first bad vertex.
pub(crate) fn checked_positions(positions: &[[f64; 3]]) -> Result<Vec<DVec3>> {
    if let Some((index, p)) = positions.iter().enumerate().find(|(_, p)| !p.iter().all(|c| c.is_finite())) {
        return Err(UvfeatError::NonFinitePosition { index, value: *p });
    }
    Ok(positions.iter().map(|p| DVec3::from_array(*p)).collect())
}

/// Face rows as `u32` indices, once every index is known to be in `0..count`.
///
/// # Errors
/// [`UvfeatError::IndexOutOfRange`] naming the first bad face.
pub(crate) fn checked_indices(rows: &[[i64; 3]], count: usize, what: &'static str) -> Result<Vec<[u32; 3]>> {
    rows.iter()
        .enumerate()
        .map(|(face, row)| {
            let mut out = [0u32; 3];
            for (slot, &index) in out.iter_mut().zip(row) {
                if index < 0 || index as usize >= count {
                    return Err(UvfeatError::IndexOutOfRange { face, what, index, count });
                }
                *slot = index as u32;
            }
            Ok(out)
        })
        .collect()
}

/// Whether two corners of a face are one (welded) vertex: the face has no area and no third edge.
pub(crate) fn has_repeated_corner(t: [u32; 3]) -> bool {
    t[0] == t[1] || t[1] == t[2] || t[0] == t[2]
}

/// Barycentric coordinates of `p` in the UV triangle `uv` (negative outside it).
pub(crate) fn uv_barycentric(uv: &[DVec2; 3], p: DVec2) -> [f64; 3] {
    let area2 = uv_signed_area2(uv);
    let b1 = (p - uv[0]).perp_dot(uv[2] - uv[0]) / area2;
    let b2 = (uv[1] - uv[0]).perp_dot(p - uv[0]) / area2;
    [1.0 - b1 - b2, b1, b2]
}

/// Twice the signed area of a UV triangle.
pub(crate) fn uv_signed_area2(uv: &[DVec2; 3]) -> f64 {
    (uv[1] - uv[0]).perp_dot(uv[2] - uv[0])
}

/// A UV triangle is degenerate when its area is negligible against its edge lengths, so its
/// Jacobian `J_T` is undefined (DESIGN.md §1.1: skipped and counted).
pub(crate) fn uv_is_degenerate(uv: &[DVec2; 3]) -> bool {
    let e1 = uv[1] - uv[0];
    let e2 = uv[2] - uv[0];
    uv_signed_area2(uv).abs() <= 1e-12 * e1.length() * e2.length() || e1.length() == 0.0 || e2.length() == 0.0
}
