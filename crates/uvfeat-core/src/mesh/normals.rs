//! Vertex normals (DESIGN.md §0, A26): area-weighted average of incident face normals per geometric
//! vertex, so both sides of a seam agree.

use glam::DVec3;
use rayon::prelude::*;

/// Unit normal of every geometric vertex; zero for a vertex with no face of positive area.
///
/// Face normals follow the right-hand rule on counter-clockwise corners,
/// `n = (x1 - x0) x (x2 - x0)`, whose length is twice the face area (hence the area weighting).
pub fn vertex_normals(positions: &[DVec3], faces: &[[u32; 3]]) -> Vec<DVec3> {
    let mut sums = vec![DVec3::ZERO; positions.len()];
    for tri in faces {
        let [a, b, c] = tri.map(|v| positions[v as usize]);
        let n = (b - a).cross(c - a);
        for &v in tri {
            sums[v as usize] += n;
        }
    }
    sums.par_iter_mut().for_each(|n| *n = n.normalize_or_zero());
    sums
}

/// Unit normal of the triangle `[a, b, c]` by the right-hand rule, zero for a triangle without
/// area.
pub fn unit_face_normal([a, b, c]: [DVec3; 3]) -> DVec3 {
    let (e1, e2) = (b - a, c - a);
    let cross = e1.cross(e2);
    if cross.length() <= 1e-12 * e1.length() * e2.length() {
        DVec3::ZERO
    } else {
        cross.normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tetrahedron_normals_point_outwards() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let n = vertex_normals(&p, &faces);
        let centre = DVec3::splat(0.25);
        for (v, normal) in n.iter().enumerate() {
            assert!((normal.length() - 1.0).abs() < 1e-12);
            assert!(normal.dot(p[v] - centre) > 0.0, "vertex {v} normal points inwards");
        }
    }
}
