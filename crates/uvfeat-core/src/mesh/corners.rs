//! Atlas corners: the face corners that are one point of the atlas (same geometric vertex, same
//! UV, hence same chart). Per-corner averages of per-face quantities live on these groups.

use super::vertex_sort::compressed_rows;
use glam::DVec2;
use rayon::prelude::*;

/// Group id of a corner of a face without a chart.
pub const NO_CORNER: u32 = u32::MAX;

/// Groups the corners of the faces not `excluded` (those charted): `(group of each face corner,
/// number of groups)`. Groups are numbered in order of their vertex, then of their UV's bits.
///
/// The corners are bucketed by vertex as 4-byte corner ids, and each vertex's handful sorted by
/// UV: sorting 24-byte `(vertex, u, v, corner)` records of every corner took 33-43 ms of a
/// 200K-face mesh's pre-processing.
pub(crate) fn corner_groups(
    faces: &[[u32; 3]],
    corner_uvs: &[[DVec2; 3]],
    excluded: &[bool],
    n_vertices: usize,
) -> (Vec<[u32; 3]>, usize) {
    let charted = faces.iter().enumerate().filter(|&(f, _)| !excluded[f]);
    let corners = charted.flat_map(|(f, tri)| (0..3).map(move |k| (tri[k], (3 * f + k) as u32)));
    let (start, mut by_vertex) = compressed_rows(n_vertices, corners);
    let row = |v: usize| start[v] as usize..start[v + 1] as usize;
    let uv_bits = |corner: u32| {
        let uv = corner_uvs[corner as usize / 3][corner as usize % 3];
        (uv.x.to_bits(), uv.y.to_bits())
    };
    let mut rows = Vec::with_capacity(n_vertices);
    let mut rest = by_vertex.as_mut_slice();
    for v in 0..n_vertices {
        let (own, after) = rest.split_at_mut(row(v).len());
        rows.push(own);
        rest = after;
    }
    rows.into_par_iter().for_each(|corners| corners.sort_unstable_by_key(|&corner| (uv_bits(corner), corner)));
    let mut groups = vec![[NO_CORNER; 3]; faces.len()];
    let mut n_groups = 0;
    for v in 0..n_vertices {
        for group in by_vertex[row(v)].chunk_by(|&a, &b| uv_bits(a) == uv_bits(b)) {
            for &corner in group {
                groups[corner as usize / 3][corner as usize % 3] = n_groups as u32;
            }
            n_groups += 1;
        }
    }
    (groups, n_groups)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The groups equal those of a full sort of `(vertex, u bits, v bits)` over every charted
    /// corner, numbered in that order: 400 random faces over 60 vertices whose UVs repeat per
    /// vertex but not always (seams), every 37th face excluded.
    #[test]
    fn groups_follow_vertex_then_uv_order() {
        let mut state = 5u32;
        let mut next = |n: u32| {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) % n
        };
        let faces: Vec<[u32; 3]> = (0..400).map(|_| [next(60), next(60), next(60)]).collect();
        let corner_uvs: Vec<[DVec2; 3]> = faces
            .iter()
            .map(|tri| tri.map(|v| DVec2::new(f64::from(v % 7) / 7.0, f64::from(next(2) + v % 3) / 4.0)))
            .collect();
        let excluded: Vec<bool> = (0..faces.len()).map(|f| f % 37 == 0).collect();
        let (groups, n) = corner_groups(&faces, &corner_uvs, &excluded, 60);
        let mut keys: Vec<(u32, u64, u64)> = (0..faces.len())
            .filter(|&f| !excluded[f])
            .flat_map(|f| (0..3).map(move |k| (f, k)))
            .map(|(f, k)| (faces[f][k], corner_uvs[f][k].x.to_bits(), corner_uvs[f][k].y.to_bits()))
            .collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(n, keys.len());
        for f in 0..faces.len() {
            for k in 0..3 {
                let expected = if excluded[f] {
                    NO_CORNER
                } else {
                    let key = (faces[f][k], corner_uvs[f][k].x.to_bits(), corner_uvs[f][k].y.to_bits());
                    keys.binary_search(&key).unwrap() as u32
                };
                assert_eq!(groups[f][k], expected, "face {f} corner {k}");
            }
        }
    }
}
