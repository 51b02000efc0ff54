//! Which side of a mesh's faces a picture shows: both for an open mesh (its inside shows through
//! the borders), the outside for a closed one, whichever way its faces are wound.
//!
//! It was NumPy (a sort of the edges through `np.unique`), 80-100 ms for 200K faces, once per
//! 3D picture: here a parallel sort of packed edge keys.

use super::shaded_view::Front;
use crate::error::Result;
use crate::mesh::checked_indices;
use rayon::prelude::*;

/// Faces per partial sum of the volume: fixed, so the sum is the same on any number of threads.
const VOLUME_CHUNK: usize = 4096;

/// The side of `faces` (corners indexing `positions`) a viewer outside the mesh sees:
/// [`Front::Both`] unless every edge is shared by exactly two faces, then
/// [`Front::CounterClockwise`] when the enclosed signed volume is positive or zero (faces wound
/// counter-clockwise seen from outside) and [`Front::Clockwise`] when it is negative.
///
/// # Errors
/// [`crate::error::UvfeatError::IndexOutOfRange`] for a corner not in `positions`.
pub fn front_side(positions: &[[f64; 3]], faces: &[[i64; 3]]) -> Result<Front> {
    let corners = checked_indices(faces, positions.len(), "vertex")?;
    if !is_closed(&corners) {
        return Ok(Front::Both);
    }
    Ok(if signed_volume(positions, &corners) >= 0.0 { Front::CounterClockwise } else { Front::Clockwise })
}

/// Whether every undirected edge is shared by exactly two faces (no border, nothing non-manifold).
fn is_closed(faces: &[[u32; 3]]) -> bool {
    let mut edges: Vec<u64> = faces
        .par_iter()
        .flat_map_iter(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .map(|(a, b)| (u64::from(a.min(b)) << 32) | u64::from(a.max(b)))
        .collect();
    edges.par_sort_unstable();
    !edges.is_empty() && edges.chunk_by(|a, b| a == b).all(|run| run.len() == 2)
}

/// Six times the volume the faces enclose, positive when they turn counter-clockwise seen from outside.
fn signed_volume(positions: &[[f64; 3]], faces: &[[u32; 3]]) -> f64 {
    let partial: Vec<f64> = faces
        .par_chunks(VOLUME_CHUNK)
        .map(|chunk| {
            chunk
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|v| glam::DVec3::from_array(positions[v as usize]));
                    a.dot(b.cross(c))
                })
                .sum::<f64>()
        })
        .collect();
    partial.iter().sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tetrahedron wound counter-clockwise seen from outside.
    const TETRAHEDRON: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    const OUTWARD: [[i64; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];

    #[test]
    fn a_closed_mesh_shows_the_side_its_winding_puts_outside() {
        assert_eq!(front_side(&TETRAHEDRON, &OUTWARD).unwrap(), Front::CounterClockwise);
        let inward = OUTWARD.map(|[a, b, c]| [a, c, b]);
        assert_eq!(front_side(&TETRAHEDRON, &inward).unwrap(), Front::Clockwise);
    }

    #[test]
    fn an_open_or_non_manifold_mesh_shows_both_sides() {
        assert_eq!(front_side(&TETRAHEDRON, &OUTWARD[..3]).unwrap(), Front::Both);
        let fin = [OUTWARD[0], OUTWARD[1], OUTWARD[2], OUTWARD[3], [0, 1, 2]];
        assert_eq!(front_side(&TETRAHEDRON, &fin).unwrap(), Front::Both);
        assert_eq!(front_side(&TETRAHEDRON, &[]).unwrap(), Front::Both);
    }

    #[test]
    fn a_corner_outside_the_positions_is_an_error() {
        let error = front_side(&TETRAHEDRON, &[[0, 1, 4]]).unwrap_err().to_string();
        assert!(error.contains("vertex"), "{error}");
    }
}
