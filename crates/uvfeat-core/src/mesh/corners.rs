//! Atlas corners: the face corners that are one point of the atlas (same geometric vertex, same
//! UV, hence same chart). Per-corner averages of per-face quantities live on these groups.

use super::vertex_sort::sort_by_vertex;
use glam::DVec2;
use rayon::prelude::*;

/// Group id of a corner of a face without a chart.
pub const NO_CORNER: u32 = u32::MAX;

/// Groups the corners of the faces not `excluded` (those charted): `(group of each face corner,
/// number of groups)`.
pub(crate) fn corner_groups(
    faces: &[[u32; 3]],
    corner_uvs: &[[DVec2; 3]],
    excluded: &[bool],
) -> (Vec<[u32; 3]>, usize) {
    let corners: Vec<(u32, u64, u64, u32)> = faces
        .par_iter()
        .zip(corner_uvs)
        .enumerate()
        .filter(|&(f, _)| !excluded[f])
        .flat_map_iter(|(f, (tri, uv))| {
            (0..3).map(move |k| (tri[k], uv[k].x.to_bits(), uv[k].y.to_bits(), (f * 3 + k) as u32))
        })
        .collect();
    let corners = sort_by_vertex(&corners, |corner| corner.0);
    let mut groups = vec![[NO_CORNER; 3]; faces.len()];
    let mut n_groups = 0;
    for group in corners.chunk_by(|x, y| (x.0, x.1, x.2) == (y.0, y.1, y.2)) {
        for &(_, _, _, corner) in group {
            groups[corner as usize / 3][corner as usize % 3] = n_groups as u32;
        }
        n_groups += 1;
    }
    (groups, n_groups)
}
