//! The atlas corners of every vertex, which the per-vertex values read (DESIGN.md §1.9).

use crate::atlas::Atlas;
use glam::DVec2;
use rayon::prelude::*;

/// One atlas corner of a vertex: its UV, chart and the first face round it.
#[derive(Debug, Clone, Copy)]
pub struct Corner {
    pub uv: DVec2,
    pub chart: i32,
    pub face: u32,
}

/// The distinct corners of every geometric vertex: the atlas corners, which are numbered in order
/// of their vertex, so vertex `g` has corners `offsets[g]..offsets[g + 1]`. (Flat, not a list per
/// vertex: those lists took 140 bytes per vertex, the peak of a 5M-face run.)
pub fn corners(atlas: &Atlas) -> (Vec<usize>, Vec<Corner>) {
    let topology = &atlas.topology;
    // Corner by corner in parallel, from the first of the faces round each (they are listed in face
    // order), where one thread went over the faces: the 200K-face sphere's and torus's lookups of
    // two features 4.5-4.8 -> 4.1 ms.
    let (corners, vertices): (Vec<Corner>, Vec<u32>) = (0..topology.n_corners)
        .into_par_iter()
        .map(|corner| {
            let face = topology.corner_faces[topology.corner_face_start[corner] as usize] as usize;
            // The face lists the corner among its own (it is round it).
            let k = topology.corner_groups[face].iter().position(|&c| c == corner as u32).unwrap_or(0);
            let corner = Corner {
                uv: topology.walk_faces[face].corners[k],
                chart: topology.face_chart[face],
                face: face as u32,
            };
            (corner, topology.faces[face][k])
        })
        .unzip();
    let mut offsets = vec![0usize; topology.n_geometric() + 1];
    for &vertex in &vertices {
        offsets[vertex as usize + 1] += 1;
    }
    for g in 1..offsets.len() {
        offsets[g] += offsets[g - 1];
    }
    (offsets, corners)
}
