//! Face-to-face links in parameter space: what lies across each edge of each face. The exact
//! triangle walk of the relocation follows them (inside a chart to the neighbouring face, at a
//! chart boundary to the side whose transition map carries the walk on).

use super::topology::BoundarySide;
use rayon::prelude::*;

/// What lies across edge `k` (corners `k`, `k + 1`) of a face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeLink {
    /// A UV-continuous edge: the walk continues in `face` (same chart), entering through its
    /// edge `local`.
    #[allow(missing_docs)]
    Face { face: u32, local: u8 },
    /// A chart-boundary side (index into `Topology::sides`): a seam, a mesh border or a
    /// non-manifold edge.
    Side(u32),
    /// Nothing usable (a face with a degenerate UV triangle).
    Closed,
}

/// The links of every face, from its geometric vertex ids, its chart (`-1` = degenerate, no links)
/// and the boundary sides; every other edge of a charted face is shared by exactly two faces of
/// the same chart (that is what made it interior).
pub(crate) fn face_links(faces: &[[u32; 3]], face_chart: &[i32], sides: &[BoundarySide]) -> Vec<[EdgeLink; 3]> {
    let mut links = vec![[EdgeLink::Closed; 3]; faces.len()];
    for (i, side) in sides.iter().enumerate() {
        links[side.face as usize][side.local as usize] = EdgeLink::Side(i as u32);
    }
    // Interior edges: sort the half-edges by their undirected key and pair the neighbours.
    let mut half_edges: Vec<(u64, u32, u8)> = faces
        .par_iter()
        .enumerate()
        .filter(|&(f, _)| face_chart[f] >= 0)
        .flat_map_iter(|(f, tri)| {
            let side_edges = links[f];
            (0..3u8).filter(move |&k| side_edges[k as usize] == EdgeLink::Closed).map(move |k| {
                let (a, b) = (tri[k as usize], tri[(k as usize + 1) % 3]);
                ((u64::from(a.min(b)) << 32) | u64::from(a.max(b)), f as u32, k)
            })
        })
        .collect();
    half_edges.par_sort_unstable();
    for pair in half_edges.chunk_by(|x, y| x.0 == y.0) {
        if let [(_, f, k), (_, g, l)] = *pair {
            links[f as usize][k as usize] = EdgeLink::Face { face: g, local: l };
            links[g as usize][l as usize] = EdgeLink::Face { face: f, local: k };
        }
    }
    links
}
