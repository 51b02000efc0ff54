//! The part of a flat triangle inside a disk, in closed form: where one (pseudo-)source lights a
//! face, its exact polyhedral distance field is `sigma + |x - s|` (`s` the source unfolded into
//! the face's plane), so the part of the face within geodesic distance `r` is the face's
//! intersection with the disk of radius `r - sigma` around `s`.

use glam::DVec2;

/// Area of the intersection of triangle `p` with the disk of `radius` around `centre`.
pub fn triangle_disk_area(p: [DVec2; 3], centre: DVec2, radius: f64) -> f64 {
    if !(radius > 0.0) {
        return 0.0;
    }
    let q = p.map(|x| x - centre);
    (0..3).map(|k| sector_triangle_area(q[k], q[(k + 1) % 3], radius)).sum::<f64>().abs()
}

/// Signed area of the intersection of the disk of `radius` around the origin with the triangle
/// `(0, a, b)`: triangles where the edge `a -> b` runs inside the disk, circular sectors where
/// it runs outside.
fn sector_triangle_area(a: DVec2, b: DVec2, radius: f64) -> f64 {
    let r2 = radius * radius;
    let e = b - a;
    // |a + t e|^2 = r^2  <=>  t^2 |e|^2 + 2 t a.e + |a|^2 - r^2 = 0.
    let (qa, qb, qc) = (e.length_squared(), a.dot(e), a.length_squared() - r2);
    let mut cuts = [0.0, 1.0, 1.0, 1.0];
    let mut n = 1;
    let disc = qb * qb - qa * qc;
    if qa > 0.0 && disc > 0.0 {
        for t in [(-qb - disc.sqrt()) / qa, (-qb + disc.sqrt()) / qa] {
            if t > 0.0 && t < 1.0 {
                cuts[n] = t;
                n += 1;
            }
        }
    }
    cuts[n] = 1.0;
    let mut area = 0.0;
    for w in cuts[..=n].windows(2) {
        let (u, v) = (a + e * w[0], a + e * w[1]);
        let middle = a + e * ((w[0] + w[1]) / 2.0);
        area +=
            if middle.length_squared() <= r2 { u.perp_dot(v) / 2.0 } else { r2 * u.perp_dot(v).atan2(u.dot(v)) / 2.0 };
    }
    area
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn disk_areas_of_known_configurations() {
        let big = [DVec2::new(-10.0, -10.0), DVec2::new(10.0, -10.0), DVec2::new(0.0, 10.0)];
        // A unit disk well inside the triangle, and the triangle well inside a large disk.
        assert!((triangle_disk_area(big, DVec2::ZERO, 1.0) - PI).abs() < 1e-12);
        assert!((triangle_disk_area(big, DVec2::ZERO, 100.0) - 200.0).abs() < 1e-9);
        // A quarter disk: right angle at the centre, legs longer than the radius.
        let corner = [DVec2::ZERO, DVec2::new(5.0, 0.0), DVec2::new(0.0, 5.0)];
        assert!((triangle_disk_area(corner, DVec2::ZERO, 1.0) - PI / 4.0).abs() < 1e-12);
        // Half of the unit disk is on each side of a long edge through its centre.
        let half = [DVec2::new(-5.0, 0.0), DVec2::new(5.0, 0.0), DVec2::new(0.0, 5.0)];
        assert!((triangle_disk_area(half, DVec2::ZERO, 1.0) - PI / 2.0).abs() < 1e-12);
        // A disk away from the triangle.
        assert_eq!(triangle_disk_area(corner, DVec2::new(-3.0, -3.0), 1.0), 0.0);
        assert_eq!(triangle_disk_area(corner, DVec2::ZERO, -1.0), 0.0);
    }
}
