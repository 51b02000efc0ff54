//! Seam transition maps (DESIGN.md §1.2.5, decision A6): the affine map that carries a parametric
//! point of one chart across a seam into the chart on the other side.

use super::edges::SideKind;
use super::{uv_signed_area2, Topology};
use glam::{DMat2, DVec2};
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
/// `M_AB = [eps_B, w_B] [eps_A, w_A]^-1`: it carries the A-side UV edge `eps_A` onto the B-side
/// edge `eps_B` and the A-side perpendicular `w_A` (pointing out of `T_A`) onto the B-side one
/// `w_B` (pointing into `T_B`), where "perpendicular" and "length" are measured in each side's
/// metric, so `w` has the metric length of the edge. With the faces' own metrics this is exactly
/// the hinge unfolding of `T_B` into the plane of `T_A` (DESIGN.md §1.2.5): rotation, anisotropic scale,
/// shear and mirroring. The metric used on each side is the smoothed metric of the edge's two
/// atlas corners (see `distortion::corner_metrics`), so that a sliver UV triangle at the seam does
/// not skew what lies beyond it. Where a metric is singular the map falls back to the similarity
/// (with mirroring) that carries one UV edge onto the other.
///
/// `metric(face, corner)` is the frame's metric `[E, F, G]` at a face corner; maps are O(#seams)
/// per frame.
pub fn seam_maps(topology: &Topology, metric: impl Fn(u32, usize) -> [f64; 3] + Sync) -> Vec<Option<SeamMap>> {
    topology
        .sides
        .par_iter()
        .map(|side| {
            let SideKind::Seam { other_face, .. } = side.kind else {
                return None;
            };
            let ([a, b], [ua_a, ua_b]) = topology.side_endpoints(side);
            let ub_a = topology.uv_of_vertex(other_face, a);
            let ub_b = topology.uv_of_vertex(other_face, b);
            let m = hinge_map(topology, &metric, side.face, other_face, a, b)
                .unwrap_or_else(|| similarity_map(topology, side.face, other_face, ub_b - ub_a, ua_b - ua_a));
            Some(SeamMap { origin_from: ua_a, origin_to: ub_a, m })
        })
        .collect()
}

fn hinge_map(
    topology: &Topology,
    metric: &impl Fn(u32, usize) -> [f64; 3],
    face_a: u32,
    face_b: u32,
    a: u32,
    b: u32,
) -> Option<DMat2> {
    // The edge and the metric-perpendicular of the given length, on the side of the third corner
    // (`inwards`) or away from it.
    let frame = |face: u32, inwards: bool| -> Option<(DVec2, DVec2)> {
        let tri = topology.faces[face as usize];
        let uv = topology.corner_uvs(face as usize);
        let corner = |v: u32| tri.iter().position(|&x| x == v);
        let (ka, kb) = (corner(a)?, corner(b)?);
        let third = 3 - ka - kb;
        let [ma, mb] = [metric(face, ka), metric(face, kb)];
        let [e, f, g] = std::array::from_fn(|i| 0.5 * (ma[i] + mb[i]));
        let apply = |x: DVec2| DVec2::new(e * x.x + f * x.y, f * x.x + g * x.y);
        let edge = uv[kb] - uv[ka];
        let length2 = edge.dot(apply(edge));
        let mut w = apply(edge).perp();
        let w_length2 = w.dot(apply(w));
        if !(length2 > 0.0 && w_length2 > 1e-24 * length2 * length2) {
            return None;
        }
        w *= (length2 / w_length2).sqrt();
        let towards_third = edge.perp_dot(w).signum() == edge.perp_dot(uv[third] - uv[ka]).signum();
        if towards_third != inwards {
            w = -w;
        }
        Some((edge, w))
    };
    let (ea, wa) = frame(face_a, false)?;
    let (eb, wb) = frame(face_b, true)?;
    let from = DMat2::from_cols(ea, wa);
    if from.determinant().abs() < 1e-300 {
        return None;
    }
    let m = DMat2::from_cols(eb, wb) * from.inverse();
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
    let (c, s) =
        ((edge_b.x * edge_a.x + edge_b.y * edge_a.y) / len2, (edge_b.y * edge_a.x - edge_b.x * edge_a.y) / len2);
    let rotate_scale = DMat2::from_cols(DVec2::new(c, s), DVec2::new(-s, c));
    let orientation = |f: u32| uv_signed_area2(&topology.corner_uvs(f as usize)).signum();
    if orientation(face_a) == orientation(face_b) {
        return rotate_scale;
    }
    let d = edge_a / len2.sqrt();
    let reflect = DMat2::from_cols(
        DVec2::new(2.0 * d.x * d.x - 1.0, 2.0 * d.x * d.y),
        DVec2::new(2.0 * d.x * d.y, 2.0 * d.y * d.y - 1.0),
    );
    rotate_scale * reflect
}
