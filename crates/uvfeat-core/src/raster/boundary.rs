//! Conservative rasterisation of chart-boundary edges (DESIGN.md §1.3.2, as Sander et al. 2003 do):
//! every texel whose square touches a boundary edge of a chart becomes a border texel of that
//! chart, so charts have no gaps and the sampler always finds a border texel where it leaves one.

use glam::DVec2;

/// A texel touched by a boundary side, with the closest point of the side to the texel centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EdgeHit {
    pub texel: u32,
    /// Index of the boundary side (into `Topology::sides`).
    pub side: u32,
    /// Distance from the texel centre to the edge, in texels.
    pub distance: f32,
    /// Position of the closest point along the edge, 0 at its first endpoint, 1 at its second.
    pub along: f32,
}

/// Appends every texel of a `resolution`² grid whose closed square intersects the segment `a -> b`
/// (UV coordinates), walking the segment column by column (O(length) texels).
pub(crate) fn rasterise_edge(side: u32, a: DVec2, b: DVec2, resolution: usize, out: &mut Vec<EdgeHit>) {
    let scale = resolution as f64;
    let (p, q) = (a * scale, b * scale);
    let last = resolution as i64 - 1;
    let (x0, x1) = (p.x.min(q.x), p.x.max(q.x));
    let y_at = |x: f64| {
        if q.x == p.x {
            p.y
        } else {
            p.y + (x - p.x) * (q.y - p.y) / (q.x - p.x)
        }
    };
    for i in (x0.floor() as i64).max(0)..=(x1.floor() as i64).min(last) {
        let (xa, xb) = (x0.max(i as f64), x1.min(i as f64 + 1.0));
        let (ya, yb) = if q.x == p.x { (p.y, q.y) } else { (y_at(xa), y_at(xb)) };
        let (y0, y1) = (ya.min(yb), ya.max(yb));
        for j in (y0.floor() as i64).max(0)..=(y1.floor() as i64).min(last) {
            let centre = DVec2::new(i as f64 + 0.5, j as f64 + 0.5);
            let (distance, along) = closest_on_segment(p, q, centre);
            out.push(EdgeHit {
                texel: (j as usize * resolution + i as usize) as u32,
                side,
                distance: distance as f32,
                along: along as f32,
            });
        }
    }
}

/// Distance from `c` to segment `p -> q` and the clamped parameter of the closest point.
pub(crate) fn closest_on_segment(p: DVec2, q: DVec2, c: DVec2) -> (f64, f64) {
    let d = q - p;
    let len2 = d.length_squared();
    let t = if len2 > 0.0 { ((c - p).dot(d) / len2).clamp(0.0, 1.0) } else { 0.0 };
    ((p + d * t - c).length(), t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texels(a: DVec2, b: DVec2, res: usize) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        rasterise_edge(0, a, b, res, &mut out);
        let mut t: Vec<_> = out.iter().map(|h| (h.texel as usize % res, h.texel as usize / res)).collect();
        t.sort_unstable();
        t.dedup();
        t
    }

    #[test]
    fn diagonal_edge_touches_a_four_connected_staircase() {
        let t = texels(DVec2::new(0.05, 0.05), DVec2::new(0.95, 0.55), 10);
        // Every texel the segment passes through, and each consecutive pair shares a side.
        assert!(t.contains(&(0, 0)) && t.contains(&(9, 5)));
        let mut sorted = t.clone();
        sorted.sort_by_key(|&(i, j)| (i, j));
        for w in sorted.windows(2) {
            let (a, b) = (w[0], w[1]);
            assert!(a.0.abs_diff(b.0) + a.1.abs_diff(b.1) <= 1 || a.0 == b.0, "gap between {a:?} and {b:?}");
        }
    }

    #[test]
    fn vertical_and_tiny_edges_are_found() {
        assert_eq!(texels(DVec2::new(0.25, 0.1), DVec2::new(0.25, 0.35), 4), vec![(1, 0), (1, 1)]);
        assert_eq!(texels(DVec2::new(0.6, 0.6), DVec2::new(0.61, 0.6), 4), vec![(2, 2)]);
    }

    #[test]
    fn closest_point_is_clamped_to_the_segment() {
        let (d, t) = closest_on_segment(DVec2::ZERO, DVec2::X, DVec2::new(2.0, 1.0));
        assert!((d - 2f64.sqrt()).abs() < 1e-12 && t == 1.0);
    }
}
