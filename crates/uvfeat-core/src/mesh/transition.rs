//! Seam transition maps (SPEC §1.2.5, decision A6): the affine map that carries a parametric
//! point of one chart across a seam into the chart on the other side.

use super::edges::{uv_of_vertex, SideKind};
use super::{uv_signed_area2, Jacobian, Topology};
use glam::{DMat2, DVec2, DVec3};
use rayon::prelude::*;

/// `T(x) = origin_to + m (x - origin_from)` from the frame of a side's chart to the chart across.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeamMap {
    /// UV of the edge's first endpoint on this side (`uA_a`).
    pub origin_from: DVec2,
    /// UV of the same endpoint on the other side (`uB_a`).
    pub origin_to: DVec2,
    /// Linear part `M_AB`; `det < 0` for a mirrored chart.
    pub m: DMat2,
}

impl SeamMap {
    /// Maps a parametric point across the seam.
    pub fn apply(&self, x: DVec2) -> DVec2 {
        self.origin_to + self.m * (x - self.origin_from)
    }
}

/// Transition map of every boundary side (`None` for sides with nothing across).
///
/// `M_AB = [J_B^+ e, J_B^+ m_B] [J_A^+ e, J_A^+ m_A]^-1` with `e` the unit edge direction, `m_A` the
/// in-plane perpendicular pointing out of `T_A` and `m_B` the one pointing into `T_B`: the hinge
/// unfolding of `T_B` into the plane of `T_A`. It maps the A-side edge exactly onto the B-side edge
/// and expresses rotation, anisotropic scale, shear and mirroring. Where a triangle is degenerate in
/// 3D the metric is singular and the map falls back to the similarity (with mirroring) that carries
/// one UV edge onto the other.
///
/// `positions` are the geometric vertex positions of the frame and `jacobian(face)` the frame's
/// Jacobian of a face (computed once per frame by the caller); maps are O(#seams) per frame.
pub fn seam_maps(
    topology: &Topology,
    positions: &[DVec3],
    jacobian: impl Fn(u32) -> Option<Jacobian> + Sync,
) -> Vec<Option<SeamMap>> {
    topology
        .sides
        .par_iter()
        .map(|side| {
            let SideKind::Seam { other_face, .. } = side.kind else { return None };
            let ([a, b], [ua_a, ua_b]) = topology.side_endpoints(side);
            let ub_a = uv_of_vertex(&topology.faces, &topology.corner_uvs, other_face, a);
            let ub_b = uv_of_vertex(&topology.faces, &topology.corner_uvs, other_face, b);
            let m = hinge_map(topology, positions, &jacobian, side.face, other_face, a, b)
                .unwrap_or_else(|| similarity_map(topology, side.face, other_face, ub_b - ub_a, ua_b - ua_a));
            Some(SeamMap { origin_from: ua_a, origin_to: ub_a, m })
        })
        .collect()
}

fn hinge_map(
    topology: &Topology,
    positions: &[DVec3],
    jacobian: &impl Fn(u32) -> Option<Jacobian>,
    face_a: u32,
    face_b: u32,
    a: u32,
    b: u32,
) -> Option<DMat2> {
    let xa = positions[a as usize];
    let e = (positions[b as usize] - xa).try_normalize()?;
    let frame = |face: u32, outward: bool| -> Option<(DVec2, DVec2)> {
        let tri = topology.faces[face as usize];
        let x = tri.map(|v| positions[v as usize]);
        let jac = jacobian(face)?;
        let third = tri.iter().find(|&&v| v != a && v != b).map(|&v| positions[v as usize])?;
        let normal = (x[1] - x[0]).cross(x[2] - x[0]);
        let mut m = e.cross(normal).try_normalize()?;
        let points_inwards = m.dot(third - xa) > 0.0;
        if points_inwards == outward {
            m = -m;
        }
        Some((jac.pseudo_inverse(e)?, jac.pseudo_inverse(m)?))
    };
    let (ea, ma) = frame(face_a, true)?;
    let (eb, mb) = frame(face_b, false)?;
    let from = DMat2::from_cols(ea, ma);
    if from.determinant().abs() < 1e-300 {
        return None;
    }
    let m = DMat2::from_cols(eb, mb) * from.inverse();
    m.is_finite().then_some(m)
}

/// Rotation-and-scale taking the A-side UV edge onto the B-side edge, composed with a reflection
/// about the edge when the two UV triangles have opposite orientation.
fn similarity_map(topology: &Topology, face_a: u32, face_b: u32, edge_b: DVec2, edge_a: DVec2) -> DMat2 {
    let len2 = edge_a.length_squared();
    if len2 == 0.0 {
        return DMat2::IDENTITY;
    }
    // Complex division edge_b / edge_a as a 2x2 matrix.
    let (c, s) = ((edge_b.x * edge_a.x + edge_b.y * edge_a.y) / len2, (edge_b.y * edge_a.x - edge_b.x * edge_a.y) / len2);
    let rotate_scale = DMat2::from_cols(DVec2::new(c, s), DVec2::new(-s, c));
    let orientation = |f: u32| uv_signed_area2(&topology.corner_uvs[f as usize]).signum();
    if orientation(face_a) == orientation(face_b) {
        return rotate_scale;
    }
    let d = edge_a / len2.sqrt();
    let reflect = DMat2::from_cols(DVec2::new(2.0 * d.x * d.x - 1.0, 2.0 * d.x * d.y), DVec2::new(2.0 * d.x * d.y, 2.0 * d.y * d.y - 1.0));
    rotate_scale * reflect
}
