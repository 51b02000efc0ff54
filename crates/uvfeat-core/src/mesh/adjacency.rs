//! Face-to-face links in parameter space: what lies across each edge of each face. The exact
//! triangle walk of the relocation follows them (inside a chart to the neighbouring face, at a
//! chart boundary to the side whose transition map carries the walk on).

use super::edges::FaceSide;
use super::sides::BoundarySide;
use glam::DVec2;
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

/// What the walk reads of one face, in one 64-byte cache line: the corner UVs, the orientation of
/// the UV triangle and the three links (packed). With the UVs and the links in two tables a walk
/// step missed the cache twice; on atlases of many small charts (the Stanford dragon's 2,050)
/// the walks are most of the sampling time.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub struct WalkFace {
    /// UV of each corner.
    pub corners: [DVec2; 3],
    links: [u32; 3],
    /// `+1` for a counter-clockwise UV triangle, `-1` for a clockwise (mirrored) one.
    pub orientation: f32,
}

/// Packing of [`EdgeLink`] in a `u32`: a face `f` entered through edge `l` as `4 f + l`, a side
/// `s` as `4 s + 3`, closed as `u32::MAX`.
const SIDE_TAG: u32 = 3;

impl WalkFace {
    fn new(corners: [DVec2; 3], links: [EdgeLink; 3]) -> Self {
        let orientation = (corners[1] - corners[0]).perp_dot(corners[2] - corners[0]).signum() as f32;
        let pack = |link: EdgeLink| match link {
            EdgeLink::Face { face, local } => face << 2 | u32::from(local),
            EdgeLink::Side(side) => side << 2 | SIDE_TAG,
            EdgeLink::Closed => u32::MAX,
        };
        Self { corners, links: links.map(pack), orientation }
    }

    /// What lies across edge `k`.
    #[inline]
    pub fn link(&self, k: usize) -> EdgeLink {
        match self.links[k] {
            u32::MAX => EdgeLink::Closed,
            packed if packed & 3 == SIDE_TAG => EdgeLink::Side(packed >> 2),
            packed => EdgeLink::Face { face: packed >> 2, local: (packed & 3) as u8 },
        }
    }
}

/// The walk records of every face (see [`WalkFace`]).
///
/// # Panics
/// With 2^30 faces or sides or more (the packing's limit; far beyond any buffer's reach).
pub(crate) fn walk_faces(corner_uvs: &[[DVec2; 3]], links: &[[EdgeLink; 3]]) -> Vec<WalkFace> {
    assert!(corner_uvs.len() < 1 << 30, "too many faces for the walk records");
    corner_uvs.par_iter().zip(links).map(|(&corners, &links)| WalkFace::new(corners, links)).collect()
}

/// The links of every face: across its interior edges (the two sides of each, from the edge
/// classes) to the face on the other side, across its boundary sides to the side; closed where
/// the face has no chart.
pub(crate) fn face_links(
    n_faces: usize,
    interior_pairs: &[(FaceSide, FaceSide)],
    sides: &[BoundarySide],
) -> Vec<[EdgeLink; 3]> {
    let mut links = vec![[EdgeLink::Closed; 3]; n_faces];
    for (i, side) in sides.iter().enumerate() {
        links[side.face as usize][side.local as usize] = EdgeLink::Side(i as u32);
    }
    for &(x, y) in interior_pairs {
        links[x.face as usize][x.local as usize] = EdgeLink::Face { face: y.face, local: y.local };
        links[y.face as usize][y.local as usize] = EdgeLink::Face { face: x.face, local: x.local };
    }
    links
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walk_records_keep_every_link_and_fill_one_cache_line() {
        assert_eq!(std::mem::size_of::<WalkFace>(), 64);
        let corners = [DVec2::ZERO, DVec2::X, DVec2::Y];
        let links = [EdgeLink::Face { face: (1 << 30) - 1, local: 2 }, EdgeLink::Side(12_345), EdgeLink::Closed];
        let record = WalkFace::new(corners, links);
        assert_eq!([0, 1, 2].map(|k| record.link(k)), links);
        assert_eq!(record.orientation, 1.0);
        assert_eq!(WalkFace::new([DVec2::ZERO, DVec2::Y, DVec2::X], links).orientation, -1.0);
    }
}
