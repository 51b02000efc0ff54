//! Area of the geodesic disk `GA(r)` of a vertex from per-vertex distances, in the two forms of
//! DESIGN.md §5.1, returned as the `geodesic_disk` sums the geodesic-area K estimator reads
//! (`GA = sum w g`, DESIGN.md §2.5a): the paper's sum of vertex areas, and the accurate sum of
//! clipped triangle areas.

use super::connectivity::Connectivity;
use super::disk_clip::triangle_disk_area;
use super::exact_geodesic::{ExactGeodesic, FieldSample};
use super::geometry::{flat_triangle, Geometry};
use super::stamped::StampedValues;
use crate::features::WeightedSums;
use glam::DVec2;

/// Paper: `GA = sum A_v` over the vertices with `d_v < r` (the centre included).
pub fn vertex_disk(distances: &StampedValues, vertex_areas: &[f64], radius: f64) -> WeightedSums {
    let mut disk = WeightedSums::default();
    for &v in distances.touched() {
        if distances.get(v) < radius {
            disk.add(vertex_areas[v as usize], 1.0);
        }
    }
    disk
}

/// Accurate: `GA = sum_T area(T ∩ {d < r})` with the exact distance field `d` of a search run up
/// to `bound`, over the faces around the vertices within `bound` (so that caps the circle cuts
/// out of faces with no corner inside count too). `faces_seen` is scratch.
///
/// Where one (pseudo-)source lights a whole face, `{d < r}` is an exact disk of the unfolded
/// source ([`triangle_disk_area`]); faces where several unfoldings meet (shadows of saddles and
/// cone vertices) are split in four, up to [`MAX_DEPTH`] times, until each piece has one source,
/// and the last pieces interpolate `d` linearly. Interpolating the corner distances of whole
/// faces (as the original contract had it; DESIGN.md §4.2 D14) moves the circle inwards by
/// about `h^2 / (8 r)` (`h` the edge length): a disk-area loss of about `h^2 / (8 r^2)`, which `K = 12 (pi r^2 - GA) / (pi r^4)`
/// turns into a K bias of about `1.5 h^2 / r^4` (K = 19.8 instead of 0.8 at the outer equator of
/// a 384 x 192 torus at r = 0.1; 0.88 with the exact circles). What remains is the polyhedron's own departure from the
/// smooth surface (exact on flat and developable meshes).
pub fn clipped_disk(
    search: &ExactGeodesic,
    connectivity: &Connectivity,
    geometry: &Geometry,
    radius: f64,
    bound: f64,
    faces_seen: &mut StampedValues,
) -> WeightedSums {
    let distances = &search.distances;
    faces_seen.reset();
    let mut disk = WeightedSums::default();
    for &v in distances.touched() {
        if distances.get(v) > bound {
            continue;
        }
        for &corner in connectivity.corners(v) {
            let f = corner / 3;
            if faces_seen.contains(f) {
                continue;
            }
            faces_seen.set(f, 0.0);
            let tri = connectivity.faces[f as usize];
            let area = geometry.face_areas[f as usize];
            let fraction = if tri.iter().all(|&u| distances.get(u) < radius) {
                1.0
            } else {
                let flat = flat_triangle(tri.map(|u| geometry.positions[u as usize]));
                let field = |x: DVec2| search.distance_in_face(connectivity, f, &flat, x);
                let inside = Piece { corners: flat, samples: flat.map(field) }.inside_area(radius, MAX_DEPTH, &field);
                inside / area.max(f64::MIN_POSITIVE)
            };
            disk.add(area, fraction);
        }
    }
    disk
}

/// How often a face whose distance field has several sources is split in four (16^3 pieces at
/// most, but only along the circle).
pub const MAX_DEPTH: u32 = 3;

/// A triangle of a face's layout with the distance field sampled at its corners.
struct Piece {
    corners: [DVec2; 3],
    samples: [FieldSample; 3],
}

impl Piece {
    /// Area of the piece where the distance is below `r`.
    fn inside_area(&self, r: f64, depth: u32, field: &impl Fn(DVec2) -> FieldSample) -> f64 {
        let p = self.corners;
        let area = (p[1] - p[0]).perp_dot(p[2] - p[0]).abs() / 2.0;
        let d = self.samples.map(|s| s.distance);
        let span = (0..3).map(|k| p[k].distance(p[(k + 1) % 3])).fold(0.0, f64::max);
        if d.iter().all(|&x| x < r) {
            return area;
        }
        // Inside a cone of apex distance >= r the field dips at most span^2 / (8 r) below the
        // corners' minimum; the margin is eight times that.
        if d.iter().all(|&x| x >= r + span * span / r) {
            return 0.0;
        }
        let [a, b, c] = self.samples;
        if a.same_source(&b, r) && b.same_source(&c, r) {
            return triangle_disk_area(p, a.centre, r - a.sigma);
        }
        if depth == 0 {
            return area * sublevel_fraction(d, r);
        }
        let mid = [(p[0] + p[1]) / 2.0, (p[1] + p[2]) / 2.0, (p[2] + p[0]) / 2.0];
        let m = mid.map(field);
        let [s0, s1, s2] = self.samples;
        [
            Piece { corners: [p[0], mid[0], mid[2]], samples: [s0, m[0], m[2]] },
            Piece { corners: [mid[0], p[1], mid[1]], samples: [m[0], s1, m[1]] },
            Piece { corners: [mid[2], mid[1], p[2]], samples: [m[2], m[1], s2] },
            Piece { corners: mid, samples: m },
        ]
        .iter()
        .map(|piece| piece.inside_area(r, depth - 1, field))
        .sum()
    }
}

/// Fraction of a triangle's area where the linear interpolant of the corner values `d` is below
/// `r` (unknown values, `+inf`, count as far outside).
pub fn sublevel_fraction(d: [f64; 3], r: f64) -> f64 {
    let mut d = d.map(|x| x.min(f64::MAX / 4.0));
    d.sort_by(f64::total_cmp);
    match d.iter().filter(|&&x| x < r).count() {
        0 => 0.0,
        // The corner triangle at d0, cut where the edges to d1 and d2 reach r.
        1 => (r - d[0]) / (d[1] - d[0]) * (r - d[0]) / (d[2] - d[0]),
        // Everything but the corner triangle at d2.
        2 => 1.0 - (d[2] - r) / (d[2] - d[0]) * (d[2] - r) / (d[2] - d[1]),
        _ => 1.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sublevel_fraction_of_linear_ramps() {
        assert_eq!(sublevel_fraction([0.0, 0.0, 0.0], 1.0), 1.0);
        assert_eq!(sublevel_fraction([2.0, 3.0, 4.0], 1.0), 0.0);
        // One corner at 0, the others at 2: cut at half of both edges -> a quarter of the area.
        assert!((sublevel_fraction([2.0, 0.0, 2.0], 1.0) - 0.25).abs() < 1e-15);
        // Two corners at 0, one at 2: all but the corner quarter.
        assert!((sublevel_fraction([0.0, 2.0, 0.0], 1.0) - 0.75).abs() < 1e-15);
        assert_eq!(sublevel_fraction([0.0, f64::INFINITY, f64::INFINITY], 1.0), 0.0);
    }
}
