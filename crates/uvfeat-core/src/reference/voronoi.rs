//! Mixed Voronoi vertex areas (Meyer, Desbrun, Schröder & Barr 2003, "Discrete differential-geometry
//! operators for triangulated 2-manifolds", Fig. 4): the reference's sample weights (DESIGN.md §5.1).

use glam::DVec3;

/// The share of triangle `p` that belongs to each of its corners.
///
/// Non-obtuse triangle: the Voronoi region of corner `i`,
/// `(|x_i - x_k|^2 cot(angle_j) + |x_i - x_j|^2 cot(angle_k)) / 8`; obtuse triangle (where the
/// Voronoi region would leave the triangle): half the area to the obtuse corner, a quarter to
/// each other corner. The three shares always sum to the triangle's area, so the vertex areas of a
/// mesh tile its surface exactly. Zero-area triangles give nothing. Units length^2.
pub fn mixed_voronoi_corners(p: [DVec3; 3]) -> [f64; 3] {
    let twice_area = (p[1] - p[0]).cross(p[2] - p[0]).length();
    if !(twice_area > 0.0) {
        return [0.0; 3];
    }
    let area = twice_area / 2.0;
    // dot of the two edges leaving each corner: negative at an obtuse corner.
    let dots: [f64; 3] = std::array::from_fn(|i| (p[(i + 1) % 3] - p[i]).dot(p[(i + 2) % 3] - p[i]));
    if let Some(obtuse) = dots.iter().position(|&d| d < 0.0) {
        return std::array::from_fn(|i| if i == obtuse { area / 2.0 } else { area / 4.0 });
    }
    // cot(angle_i) = dot / |cross|, and |cross| = 2 area at every corner.
    let cot = dots.map(|d| d / twice_area);
    std::array::from_fn(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        (p[i].distance_squared(p[k]) * cot[j] + p[i].distance_squared(p[j]) * cot[k]) / 8.0
    })
}

/// Mixed Voronoi area of every vertex: the sum of its corners' shares.
pub fn mixed_voronoi_areas(positions: &[DVec3], faces: &[[u32; 3]]) -> Vec<f64> {
    let mut areas = vec![0.0; positions.len()];
    for tri in faces {
        let shares = mixed_voronoi_corners(tri.map(|v| positions[v as usize]));
        for (&v, share) in tri.iter().zip(shares) {
            areas[v as usize] += share;
        }
    }
    areas
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equilateral_triangle_splits_into_thirds() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(0.5, 3f64.sqrt() / 2.0, 0.0)];
        let area = 3f64.sqrt() / 4.0;
        for share in mixed_voronoi_corners(p) {
            assert!((share - area / 3.0).abs() < 1e-15);
        }
    }

    #[test]
    fn right_triangle_gives_the_circumcentre_split() {
        // Circumcentre at the hypotenuse midpoint (0.5, 0.5): the right corner owns the square
        // [0, 0.5]^2 (area 1/4), each acute corner a quarter-square triangle of area 1/8.
        let s = mixed_voronoi_corners([DVec3::ZERO, DVec3::X, DVec3::Y]);
        assert!((s[0] - 0.25).abs() < 1e-15 && (s[1] - 0.125).abs() < 1e-15 && (s[2] - 0.125).abs() < 1e-15);
    }

    #[test]
    fn obtuse_triangle_gives_half_to_the_obtuse_corner() {
        let p = [DVec3::ZERO, DVec3::new(4.0, 0.0, 0.0), DVec3::new(2.0, 0.5, 0.0)];
        let s = mixed_voronoi_corners(p);
        assert_eq!(s, [0.25, 0.25, 0.5]);
        assert_eq!(mixed_voronoi_corners([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]), [0.0; 3]);
    }
}
