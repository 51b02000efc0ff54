//! The sides of the chart boundaries: each face edge on a seam, a mesh border or a non-manifold
//! edge, with what lies across it.

use super::edges::{FaceSide, SideKind};
use std::collections::HashMap;

/// One face's side of a chart-boundary edge (a seam side, a mesh border or a non-manifold edge).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundarySide {
    /// The face whose edge this is.
    pub face: u32,
    /// The edge runs from corner `local` to corner `local + 1` of `face`.
    pub local: u8,
    /// Chart of `face`.
    pub chart: i32,
    /// What lies across.
    pub kind: SideKind,
    /// Index (into [`Topology::sides`](super::Topology::sides)) of the same seam seen from the other face; `-1` otherwise.
    pub reverse: i32,
    /// Chart across the seam (may equal `chart` for a self-adjacent seam); `-1` where the surface ends.
    pub adjacent_chart: i32,
}

/// The boundary sides of `boundary` (each with its kind), linked to their reverse sides.
pub(crate) fn boundary_sides(boundary: &[(FaceSide, SideKind)], face_chart: &[i32]) -> Vec<BoundarySide> {
    let index: HashMap<(u32, u8), usize> =
        boundary.iter().enumerate().map(|(i, (s, _))| ((s.face, s.local), i)).collect();
    boundary
        .iter()
        .map(|&(side, kind)| {
            let (reverse, adjacent_chart) = match kind {
                SideKind::Seam { other_face, other_local } => {
                    (index[&(other_face, other_local)] as i32, face_chart[other_face as usize])
                }
                _ => (-1, -1),
            };
            BoundarySide {
                face: side.face,
                local: side.local,
                chart: face_chart[side.face as usize],
                kind,
                reverse,
                adjacent_chart,
            }
        })
        .collect()
}
