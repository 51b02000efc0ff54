//! The atlas corners of every vertex, which the per-vertex values read (DESIGN.md §1.9).

use crate::atlas::Atlas;
use crate::mesh::Topology;
use glam::DVec2;
use rayon::prelude::*;
use std::ops::Range;

/// One atlas corner of a vertex: its UV, chart and the first face round it.
#[derive(Debug, Clone, Copy)]
pub struct Corner {
    pub uv: DVec2,
    pub chart: i32,
    pub face: u32,
}

/// The distinct corners of every geometric vertex. The atlas corners are numbered in order of
/// their vertex, so vertex `g` has corners `offsets[g]..offsets[g + 1]`; each [`Corner`] is read
/// from the topology when asked for. (Flat, not a list per vertex: those lists took 140 bytes per
/// vertex, the peak of a 5M-face run; nor a table of corners, 24 bytes a corner.)
pub struct VertexCorners<'a> {
    topology: &'a Topology,
    offsets: Vec<u32>,
}

impl<'a> VertexCorners<'a> {
    /// The corners of `atlas`'s vertices.
    pub fn new(atlas: &'a Atlas) -> Self {
        let topology = &atlas.topology;
        let vertices: Vec<u32> = (0..topology.n_corners)
            .into_par_iter()
            .map(|corner| {
                let (face, k) = face_slot(topology, corner);
                topology.faces[face][k]
            })
            .collect();
        let mut offsets = vec![0u32; topology.n_geometric() + 1];
        for &vertex in &vertices {
            offsets[vertex as usize + 1] += 1;
        }
        for g in 1..offsets.len() {
            offsets[g] += offsets[g - 1];
        }
        Self { topology, offsets }
    }

    /// Number of geometric vertices.
    pub fn n_vertices(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Number of corners.
    pub fn n_corners(&self) -> usize {
        self.topology.n_corners
    }

    /// The corners of vertex `g`.
    pub fn range(&self, g: usize) -> Range<usize> {
        self.offsets[g] as usize..self.offsets[g + 1] as usize
    }

    /// Corner `c`.
    #[inline]
    pub fn corner(&self, c: usize) -> Corner {
        let (face, k) = face_slot(self.topology, c);
        Corner {
            uv: self.topology.walk_faces[face].corners[k],
            chart: self.topology.face_chart[face],
            face: face as u32,
        }
    }

    /// The corners of vertex `g`.
    pub fn of(&self, g: usize) -> impl Iterator<Item = Corner> + '_ {
        self.range(g).map(|c| self.corner(c))
    }

    /// The first corner of vertex `g`, if it has any.
    pub fn first(&self, g: usize) -> Option<Corner> {
        self.of(g).next()
    }
}

/// The first face round `corner` and the corner's slot in it (the face lists the corner among
/// its own).
#[inline]
fn face_slot(topology: &Topology, corner: usize) -> (usize, usize) {
    let face = topology.corner_faces[topology.corner_face_start[corner] as usize] as usize;
    let k = topology.corner_groups[face].iter().position(|&c| c == corner as u32).unwrap_or(0);
    (face, k)
}
