//! UV-space triangle rasterisation (DESIGN.md §1.3.1): a texel is covered when its centre lies inside
//! the UV triangle, with the top-left fill rule deciding centres exactly on an edge.

use glam::DVec2;

use std::ops::Range;

/// An edge function of one triangle edge, set up once per triangle: `sign * direction.perp_dot(c -
/// origin)`, with the edge's endpoints in a canonical order so that the two triangles sharing an
/// edge get exactly opposite values (no texel is covered twice or missed through rounding).
#[derive(Clone, Copy)]
struct EdgeFunction {
    origin: DVec2,
    direction: DVec2,
    sign: f64,
}

impl EdgeFunction {
    fn new(p: DVec2, q: DVec2) -> Self {
        if (p.x, p.y) <= (q.x, q.y) {
            Self { origin: p, direction: q - p, sign: 1.0 }
        } else {
            Self { origin: q, direction: p - q, sign: -1.0 }
        }
    }

    /// Twice the signed area of `(p, q, c)` (the sign flip is exact).
    #[inline(always)]
    fn at(&self, c: DVec2) -> f64 {
        self.sign * self.direction.perp_dot(c - self.origin)
    }
}

/// Top-left rule for a counter-clockwise edge direction `d` (v up): left edges (going down) and
/// top edges (horizontal, going left) own the centres that lie exactly on them.
fn owns_boundary(d: DVec2) -> bool {
    d.y < 0.0 || (d.y == 0.0 && d.x < 0.0)
}

/// The triangle `uv` in texel units, counter-clockwise, and the box of texel centres it may hold
/// (columns, rows; empty for a degenerate triangle).
fn texel_box(uv: [DVec2; 3], resolution: usize) -> ([DVec2; 3], Range<usize>, Range<usize>) {
    let scale = resolution as f64;
    let mut v = uv.map(|t| t * scale);
    let area2 = (v[1] - v[0]).perp_dot(v[2] - v[0]);
    if area2 == 0.0 || !area2.is_finite() {
        return (v, 0..0, 0..0);
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
        return (v, 0..0, 0..0);
    }
    (v, i0 as usize..i1 as usize + 1, j0 as usize..j1 as usize + 1)
}

/// The rows of a `resolution`² grid that may hold texel centres inside the UV triangle `uv`.
pub(crate) fn triangle_rows(uv: [DVec2; 3], resolution: usize) -> Range<usize> {
    texel_box(uv, resolution).2
}

/// Visits, row by row, every texel `j * resolution + i` of rows `rows` of a `resolution`² grid
/// whose centre is inside the UV triangle `uv`. Works for both orientations (mirrored charts are
/// clockwise in UV).
pub(crate) fn rasterise_triangle(uv: [DVec2; 3], resolution: usize, rows: Range<usize>, mut visit: impl FnMut(usize)) {
    let (v, columns, own_rows) = texel_box(uv, resolution);
    let edges = [0, 1, 2].map(|k| EdgeFunction::new(v[k], v[(k + 1) % 3]));
    let owned = [0, 1, 2].map(|k| owns_boundary(v[(k + 1) % 3] - v[k]));
    for j in own_rows.start.max(rows.start)..own_rows.end.min(rows.end) {
        for i in columns.clone() {
            let c = DVec2::new(i as f64 + 0.5, j as f64 + 0.5);
            let w = edges.map(|edge| edge.at(c));
            if (0..3).any(|k| w[k] < 0.0 || (w[k] == 0.0 && !owned[k])) {
                continue;
            }
            visit(j * resolution + i);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hits(uv: [DVec2; 3], res: usize) -> Vec<usize> {
        let mut out = Vec::new();
        rasterise_triangle(uv, res, 0..res, |t| out.push(t));
        out
    }

    #[test]
    fn two_triangles_of_a_square_cover_every_texel_once() {
        let res = 16;
        let (a, b, c, d) = (DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y);
        let mut all = hits([a, b, c], res);
        all.extend(hits([a, c, d], res)); // diagonal passes exactly through texel centres
        all.sort_unstable();
        assert_eq!(all, (0..res * res).collect::<Vec<_>>());
    }

    #[test]
    fn a_mirrored_triangle_covers_the_same_texels() {
        let uv = [DVec2::new(0.1, 0.1), DVec2::new(0.9, 0.2), DVec2::new(0.3, 0.8)];
        let ccw = hits(uv, 32);
        let cw = hits([uv[0], uv[2], uv[1]], 32);
        assert!(ccw.len() > 50);
        assert_eq!(ccw, cw);
    }
}
