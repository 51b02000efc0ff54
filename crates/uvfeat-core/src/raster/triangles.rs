//! UV-space triangle rasterisation (DESIGN.md §1.3.1): a texel is covered when its centre lies inside
//! the UV triangle, with the top-left fill rule deciding centres exactly on an edge.

use glam::DVec2;

/// A texel whose centre lies in a triangle (its barycentrics are recomputed where needed:
/// [`super::Coverage::anchor`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TriangleHit {
    pub texel: u32,
    pub face: u32,
}

/// Twice the signed area of `(p, q, c)`, computed with the edge's endpoints in a canonical order
/// so that the two triangles sharing an edge get exactly opposite values (no texel is covered
/// twice or missed through rounding).
fn edge_function(p: DVec2, q: DVec2, c: DVec2) -> f64 {
    if (p.x, p.y) <= (q.x, q.y) {
        (q - p).perp_dot(c - p)
    } else {
        -(p - q).perp_dot(c - q)
    }
}

/// Top-left rule for a counter-clockwise edge direction `d` (v up): left edges (going down) and
/// top edges (horizontal, going left) own the centres that lie exactly on them.
fn owns_boundary(d: DVec2) -> bool {
    d.y < 0.0 || (d.y == 0.0 && d.x < 0.0)
}

/// Appends every texel of a `resolution`² grid whose centre is inside the UV triangle `uv`.
/// Works for both orientations (mirrored charts are clockwise in UV).
pub(crate) fn rasterise_triangle(face: u32, uv: [DVec2; 3], resolution: usize, out: &mut Vec<TriangleHit>) {
    let scale = resolution as f64;
    let mut v = uv.map(|t| t * scale);
    let area2 = (v[1] - v[0]).perp_dot(v[2] - v[0]);
    if area2 == 0.0 || !area2.is_finite() {
        return;
    }
    // Work in counter-clockwise order.
    if area2 < 0.0 {
        v.swap(1, 2);
    }
    let lo = v[0].min(v[1]).min(v[2]);
    let hi = v[0].max(v[1]).max(v[2]);
    let last = resolution as f64 - 1.0;
    let (i0, i1) = ((lo.x - 0.5).ceil().max(0.0), (hi.x - 0.5).floor().min(last));
    let (j0, j1) = ((lo.y - 0.5).ceil().max(0.0), (hi.y - 0.5).floor().min(last));
    if i0 > i1 || j0 > j1 {
        return;
    }
    let owned = [0, 1, 2].map(|k| owns_boundary(v[(k + 1) % 3] - v[k]));
    for j in j0 as usize..=j1 as usize {
        for i in i0 as usize..=i1 as usize {
            let c = DVec2::new(i as f64 + 0.5, j as f64 + 0.5);
            let w = [0, 1, 2].map(|k| edge_function(v[k], v[(k + 1) % 3], c));
            if (0..3).any(|k| w[k] < 0.0 || (w[k] == 0.0 && !owned[k])) {
                continue;
            }
            out.push(TriangleHit { texel: (j * resolution + i) as u32, face });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hits(uv: [DVec2; 3], res: usize) -> Vec<TriangleHit> {
        let mut out = Vec::new();
        rasterise_triangle(0, uv, res, &mut out);
        out
    }

    #[test]
    fn two_triangles_of_a_square_cover_every_texel_once() {
        let res = 16;
        let (a, b, c, d) = (DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y);
        let mut all = hits([a, b, c], res);
        all.extend(hits([a, c, d], res)); // diagonal passes exactly through texel centres
        let mut texels: Vec<u32> = all.iter().map(|h| h.texel).collect();
        texels.sort_unstable();
        assert_eq!(texels, (0..(res * res) as u32).collect::<Vec<_>>());
    }

    #[test]
    fn a_mirrored_triangle_covers_the_same_texels() {
        let uv = [DVec2::new(0.1, 0.1), DVec2::new(0.9, 0.2), DVec2::new(0.3, 0.8)];
        let ccw = hits(uv, 32);
        let cw = hits([uv[0], uv[2], uv[1]], 32);
        assert!(ccw.len() > 50);
        assert_eq!(ccw.iter().map(|h| h.texel).collect::<Vec<_>>(), cw.iter().map(|h| h.texel).collect::<Vec<_>>());
    }
}
