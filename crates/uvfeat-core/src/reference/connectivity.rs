//! Half-edge connectivity of the welded mesh (the paper's "HE data structure"; built once per
//! topology and, as in the paper, left out of the reference timings).

use crate::error::{Result, UvfeatError};
use crate::mesh::{compressed_rows, sorted_half_edges, weld_positions};
use glam::DVec3;

/// Marks a half-edge without a twin (mesh border or non-manifold edge).
pub const NO_TWIN: u32 = u32::MAX;

/// Welded faces, half-edge twins and vertex adjacency in compressed rows.
///
/// Half-edge `3 f + k` runs from corner `k` to corner `k + 1` of face `f` and belongs to `f`.
#[derive(Debug, Clone)]
pub struct Connectivity {
    /// (n_input_vertices) welded vertex of every input vertex (exact position equality, as the
    /// parametric side welds, so both see through seam splits alike).
    pub vertex_ids: Vec<u32>,
    /// (n_faces) faces as welded vertex ids; faces whose corners weld together are dropped.
    pub faces: Vec<[u32; 3]>,
    /// (3 n_faces) the half-edge of the neighbouring face on the same edge, or [`NO_TWIN`] on
    /// borders and on edges with more than two faces (treated as borders, DESIGN.md §1.1).
    pub twin: Vec<u32>,
    /// (n_vertices) the vertex lies on a border or non-manifold edge.
    pub boundary: Vec<bool>,
    neighbour_start: Vec<u32>,
    neighbours: Vec<u32>,
    corner_start: Vec<u32>,
    corners: Vec<u32>,
}

impl Connectivity {
    /// Welds `positions` and builds the connectivity of `faces` (indices already checked).
    ///
    /// # Errors
    /// [`UvfeatError::DegenerateMesh`] when every face has repeated corners after welding.
    pub fn build(positions: &[DVec3], faces: &[[u32; 3]]) -> Result<Self> {
        let (vertex_ids, n_vertices) = weld_positions(positions, 0.0);
        let n_input_faces = faces.len();
        let faces: Vec<[u32; 3]> = faces
            .iter()
            .map(|t| t.map(|v| vertex_ids[v as usize]))
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect();
        if faces.is_empty() {
            return Err(UvfeatError::DegenerateMesh { faces: n_input_faces });
        }
        let (twin, boundary, edges) = twins(&faces, n_vertices);
        let (neighbour_start, neighbours) =
            compressed_rows(n_vertices, edges.iter().flat_map(|&(a, b)| [(a, b), (b, a)]));
        let corner_list = faces.iter().enumerate().flat_map(|(f, t)| (0..3).map(move |k| (t[k], (3 * f + k) as u32)));
        let (corner_start, corners) = compressed_rows(n_vertices, corner_list);
        Ok(Self { vertex_ids, faces, twin, boundary, neighbour_start, neighbours, corner_start, corners })
    }

    /// Number of welded vertices.
    pub fn n_vertices(&self) -> usize {
        self.boundary.len()
    }

    /// Vertices joined to `v` by an edge.
    pub fn neighbours(&self, v: u32) -> &[u32] {
        let v = v as usize;
        &self.neighbours[self.neighbour_start[v] as usize..self.neighbour_start[v + 1] as usize]
    }

    /// Corners `3 f + k` of the faces around `v` (corner `k` of face `f` is `v`).
    pub fn corners(&self, v: u32) -> &[u32] {
        let v = v as usize;
        &self.corners[self.corner_start[v] as usize..self.corner_start[v + 1] as usize]
    }

    /// Start vertex of half-edge `h`.
    pub fn origin(&self, h: u32) -> u32 {
        self.faces[h as usize / 3][h as usize % 3]
    }

    /// End vertex of half-edge `h`.
    pub fn target(&self, h: u32) -> u32 {
        self.faces[h as usize / 3][(h as usize + 1) % 3]
    }
}

/// Twins of every half-edge, border flags, and the distinct edges as `(low, high)` vertex pairs.
fn twins(faces: &[[u32; 3]], n_vertices: usize) -> (Vec<u32>, Vec<bool>, Vec<(u32, u32)>) {
    let keyed = sorted_half_edges(faces);
    let mut twin = vec![NO_TWIN; 3 * faces.len()];
    let mut boundary = vec![false; n_vertices];
    let mut edges = Vec::with_capacity(keyed.len() / 2 + 1);
    for group in keyed.chunk_by(|x, y| x.0 == y.0) {
        let (a, b) = ((group[0].0 >> 32) as u32, group[0].0 as u32);
        edges.push((a, b));
        if let [(_, x), (_, y)] = group {
            twin[*x as usize] = *y;
            twin[*y as usize] = *x;
        } else {
            boundary[a as usize] = true;
            boundary[b as usize] = true;
        }
    }
    (twin, boundary, edges)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_of_two_triangles_has_one_twin_pair_and_welds_duplicates() {
        // Vertex 4 duplicates vertex 2 (a seam split): welded, the diagonal becomes interior.
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::new(1.0, 1.0, 0.0)];
        let c = Connectivity::build(&p, &[[0, 1, 2], [0, 4, 3]]).unwrap();
        assert_eq!(c.n_vertices(), 4);
        assert_eq!(c.twin[2], 3);
        assert_eq!(c.twin[3], 2);
        assert_eq!(c.twin.iter().filter(|&&t| t == NO_TWIN).count(), 4);
        let mut around_0 = c.neighbours(0).to_vec();
        around_0.sort_unstable();
        assert_eq!(around_0, [1, 2, 3]);
        assert_eq!(c.corners(0).len(), 2);
        assert!(c.boundary.iter().all(|&b| b));
        assert_eq!((c.origin(2), c.target(2)), (2, 0));
    }

    #[test]
    fn faces_that_weld_into_lines_are_an_error() {
        let p = [DVec3::ZERO, DVec3::ZERO, DVec3::X];
        let err = Connectivity::build(&p, &[[0, 1, 2]]).unwrap_err();
        assert!(matches!(err, UvfeatError::DegenerateMesh { .. }), "{err}");
    }
}
