//! Edge classes (DESIGN.md §1.2.4): every geometric edge is interior, seam, border or non-manifold.

use super::vertex_sort::sort_by_vertex;
use crate::cancel;
use glam::DVec2;
use rayon::prelude::*;

/// One face's side of a geometric edge: corners `local` and `local + 1` of `face`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct FaceSide {
    pub face: u32,
    pub local: u8,
}

/// What lies across a chart-boundary side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SideKind {
    /// Two faces, UV-discontinuous: the sample continues in `other_face` (maybe the same chart).
    #[allow(missing_docs)]
    Seam { other_face: u32, other_local: u8 },
    /// One face: the mesh ends here.
    Border,
    /// More than two faces share the edge: treated as a border (DESIGN.md §1.1), counted.
    NonManifold,
    /// The face across has a zero-area UV triangle, so there is nowhere to continue.
    DegenerateNeighbour,
}

/// How many geometric edges fall in each class.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EdgeCounts {
    /// Two faces, UV-continuous.
    pub interior: usize,
    /// Two faces, UV-discontinuous.
    pub seam: usize,
    /// One face (or the face across has a degenerate UV triangle).
    pub border: usize,
    /// More than two faces.
    pub non_manifold: usize,
}

impl EdgeCounts {
    /// Adds `other`'s counts to these.
    fn merge(&mut self, other: EdgeCounts) {
        self.interior += other.interior;
        self.seam += other.seam;
        self.border += other.border;
        self.non_manifold += other.non_manifold;
    }
}

/// The result of classifying every edge of the mesh.
pub(crate) struct EdgeClasses {
    /// The two sides of every UV-continuous (interior) edge; their faces belong to the same chart.
    pub interior_pairs: Vec<(FaceSide, FaceSide)>,
    /// Chart-boundary sides and what lies across each.
    pub boundary: Vec<(FaceSide, SideKind)>,
    pub counts: EdgeCounts,
}

/// Every half-edge `(k, k + 1)` of every face as `(key, 3 f + k)`, sorted: the key is the edge's
/// two vertices, lower first, so the half-edges of one edge come together.
pub(crate) fn sorted_half_edges(faces: &[[u32; 3]]) -> Vec<(u64, u32)> {
    let keyed: Vec<(u64, u32)> = faces
        .par_iter()
        .enumerate()
        .flat_map_iter(|(f, t)| {
            (0..3).map(move |k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                ((u64::from(a.min(b)) << 32) | u64::from(a.max(b)), (3 * f + k) as u32)
            })
        })
        .collect();
    sort_by_vertex(&keyed, |&(key, _)| (key >> 32) as u32)
}

/// Classifies the edges of `faces` (geometric vertex ids), skipping `degenerate` faces.
///
/// Two faces are UV-continuous across an edge when both endpoints carry the same UV (compared
/// exactly) on both sides (DESIGN.md §1.2.2–§1.2.3).
pub(crate) fn classify_edges(faces: &[[u32; 3]], corner_uvs: &[[DVec2; 3]], degenerate: &[bool]) -> EdgeClasses {
    let side = |half_edge: u32| FaceSide { face: half_edge / 3, local: (half_edge % 3) as u8 };
    let half_edges = sorted_half_edges(faces);
    let empty = || EdgeClasses { interior_pairs: Vec::new(), boundary: Vec::new(), counts: EdgeCounts::default() };
    // Edge by edge in parallel, the pieces joined in order (one thread took 15-20 ms of a
    // 200K-face mesh's pre-processing here).
    let classify = |mut classes: EdgeClasses, group: &[(u64, u32)]| {
        if cancel::requested() {
            return classes; // the caller checks for the stop before using them
        }
        let live = || group.iter().map(|&(_, h)| side(h)).filter(|s| !degenerate[s.face as usize]);
        let n_live = live().count();
        let mut sides = live();
        match (n_live, n_live < group.len()) {
            (0, _) => {}
            (1, had_degenerate) => {
                let kind = if had_degenerate { SideKind::DegenerateNeighbour } else { SideKind::Border };
                classes.counts.border += 1;
                classes.boundary.extend(sides.map(|only| (only, kind)));
            }
            (2, false) => {
                let (Some(x), Some(y)) = (sides.next(), sides.next()) else { return classes };
                if uv_continuous(faces, corner_uvs, x, y) {
                    classes.counts.interior += 1;
                    classes.interior_pairs.push((x, y));
                } else {
                    classes.counts.seam += 1;
                    classes.boundary.push((x, SideKind::Seam { other_face: y.face, other_local: y.local }));
                    classes.boundary.push((y, SideKind::Seam { other_face: x.face, other_local: x.local }));
                }
            }
            _ => {
                classes.counts.non_manifold += 1;
                classes.boundary.extend(sides.map(|s| (s, SideKind::NonManifold)));
            }
        }
        classes
    };
    half_edges.par_chunk_by(|x, y| x.0 == y.0).fold(empty, classify).reduce(empty, |mut first, second| {
        first.interior_pairs.extend(second.interior_pairs);
        first.boundary.extend(second.boundary);
        first.counts.merge(second.counts);
        first
    })
}

/// UV of geometric vertex `vertex` in the face `tri` with corner UVs `corners` (the vertex must be
/// a corner of the face).
pub(crate) fn uv_of_vertex(tri: [u32; 3], corners: [DVec2; 3], vertex: u32) -> DVec2 {
    corners[tri.iter().position(|&v| v == vertex).unwrap_or(0)]
}

fn uv_continuous(faces: &[[u32; 3]], corner_uvs: &[[DVec2; 3]], x: FaceSide, y: FaceSide) -> bool {
    let (fx, fy) = (x.face as usize, y.face as usize);
    let (a, b) = (faces[fx][x.local as usize], faces[fx][(x.local as usize + 1) % 3]);
    [a, b].iter().all(|&v| uv_of_vertex(faces[fx], corner_uvs[fx], v) == uv_of_vertex(faces[fy], corner_uvs[fy], v))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles sharing edge (1, 2) of the unit square.
    fn square(uv_split: bool) -> (Vec<[u32; 3]>, Vec<[DVec2; 3]>) {
        let faces = vec![[0, 1, 2], [2, 1, 3]];
        let shift = if uv_split { 0.5 } else { 0.0 };
        let uv = |x: f64, y: f64| DVec2::new(x, y);
        let corner = vec![
            [uv(0.0, 0.0), uv(0.5, 0.0), uv(0.0, 0.5)],
            [uv(0.0 + shift, 0.5), uv(0.5 + shift, 0.0), uv(0.5 + shift, 0.5)],
        ];
        (faces, corner)
    }

    #[test]
    fn shared_uv_edge_is_interior_and_split_edge_is_seam() {
        let (faces, uv) = square(false);
        let classes = classify_edges(&faces, &uv, &[false, false]);
        assert_eq!(classes.counts, EdgeCounts { interior: 1, seam: 0, border: 4, non_manifold: 0 });
        let (faces, uv) = square(true);
        let classes = classify_edges(&faces, &uv, &[false, false]);
        assert_eq!(classes.counts, EdgeCounts { interior: 0, seam: 1, border: 4, non_manifold: 0 });
        assert_eq!(classes.boundary.len(), 6);
    }

    /// Edges classified in parallel come out in the order of one thread: the sides and pairs in
    /// the order of their edges, on a torus with a seam and a few non-manifold fins.
    #[test]
    fn classes_do_not_depend_on_the_thread_count() {
        let torus = crate::shapes::torus(2.0, 0.5, 96, 48);
        let mut faces: Vec<[u32; 3]> = torus.faces.iter().map(|t| t.map(|v| v as u32)).collect();
        let mut corner_uvs: Vec<[DVec2; 3]> =
            torus.uv_faces.iter().map(|t| t.map(|k| DVec2::from_array(torus.uvs[k as usize]))).collect();
        for f in (0..faces.len()).step_by(97) {
            let [a, b, _] = faces[f];
            faces.push([b, a, (a + 7) % torus.positions.len() as u32]);
            corner_uvs.push([DVec2::ZERO, DVec2::X, DVec2::Y]);
        }
        let degenerate: Vec<bool> = (0..faces.len()).map(|f| f % 211 == 0).collect();
        let with = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| classify_edges(&faces, &corner_uvs, &degenerate))
        };
        let (one, four) = (with(1), with(4));
        assert!(one.counts.non_manifold > 0 && one.counts.seam > 0 && one.counts.border > 0, "{:?}", one.counts);
        assert_eq!(one.counts, four.counts);
        assert_eq!(one.interior_pairs, four.interior_pairs);
        assert_eq!(one.boundary, four.boundary);
    }

    #[test]
    fn three_faces_on_an_edge_are_non_manifold() {
        let faces = vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]];
        let z = DVec2::ZERO;
        let uv = vec![[z, DVec2::X, DVec2::Y]; 3];
        let classes = classify_edges(&faces, &uv, &[false; 3]);
        assert_eq!(classes.counts.non_manifold, 1);
        assert_eq!(classes.boundary.iter().filter(|(_, k)| *k == SideKind::NonManifold).count(), 3);
    }
}
