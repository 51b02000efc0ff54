//! Geodesic distance estimates from the centre `p` to a sample `q` (DESIGN.md §2.5a), used by the
//! geodesic-disk area of K and the geodesic neighbourhood criterion.

use super::centre::Centre;
use crate::atlas::Atlas;
use crate::lookup::Lookup;
use glam::DVec2;

/// Which geodesic distance estimate the samples carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Geodesic {
    /// Length of the circle arc tangent to the surface at `p` through `q` (default; exact on
    /// spheres, consistent elsewhere, and it works across charts).
    #[default]
    Arc,
    /// The paper's: the length of the surface polyline over `CHORD_SEGMENTS` equal steps of the
    /// parametric segment from the sample back to the centre, for samples whose segment stays in
    /// the centre's chart (others fall back to [`Geodesic::Arc`]). It follows the
    /// parameterisation's straight line, not a geodesic, so it is not consistent in general
    /// (DESIGN.md §3.3); for reproduction only.
    ChordSum,
}

/// Segments of the chord sum (DESIGN.md §1.10, `N_s`).
pub const CHORD_SEGMENTS: usize = 16;

/// Arc-length geodesic estimate (DESIGN.md §2.5a, `geodesic = "arc"`): the length of the circle arc
/// tangent to the surface at `p` through `q`, `d = rho asin(y)/y`, `y = min(1, |sin alpha|)`.
pub fn arc_distance(distance: f64, sin_alpha: f64) -> f64 {
    let y = sin_alpha.abs().min(1.0);
    if y < 1e-4 {
        distance * (1.0 + y * y / 6.0)
    } else {
        distance * y.asin() / y
    }
}

/// Chord-sum estimate (DESIGN.md §2.5a, `geodesic = "chord_sum"`) for a sample at `uv` in the centre's
/// own chart: `sum_j |P(s_{j+1}) - P(s_j)|`, `s_j = uv + j (s - uv) / N_s`. `None` when a point of
/// the segment is off the centre's chart.
pub fn chord_sum_distance(atlas: &Atlas, centre: &Centre, uv: DVec2, lookup: Lookup) -> Option<f64> {
    let step = (centre.uv - uv) / CHORD_SEGMENTS as f64;
    let mut previous: Option<glam::DVec3> = None;
    let mut length = 0.0;
    for j in 0..=CHORD_SEGMENTS {
        let s = uv + step * j as f64;
        if atlas.chart_at(s) != centre.chart {
            return None;
        }
        let point =
            if j == CHORD_SEGMENTS { centre.position } else { lookup.surface_point(atlas, s, centre.chart)?.position };
        if let Some(previous) = previous {
            length += (point - previous).length();
        }
        previous = Some(point);
    }
    Some(length)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_arc_distance_is_exact_on_a_circle() {
        // A point at angle t on the unit circle tangent at p: chord 2 sin(t/2), elevation angle t/2.
        for t in [1e-6, 0.1, 0.5, 1.0, 2.0] {
            let chord = 2.0 * (t / 2.0_f64).sin();
            assert!((arc_distance(chord, (t / 2.0_f64).sin()) - t).abs() < 1e-9 * t.max(1.0), "{t}");
        }
    }
}
