//! The once-per-topology pre-processing (DESIGN.md §1.2): everything here depends on connectivity and
//! UVs only, so every animation frame reuses it.

use super::adjacency::{face_links, walk_faces, WalkFace};
use super::charts::chart_ids;
use super::corners::{corner_groups, NO_CORNER};
use super::edges::{classify_edges, uv_of_vertex, EdgeCounts};
use super::sides::{boundary_sides, BoundarySide};
use super::vertex_sort::compressed_rows;
use super::weld::weld_positions;
use super::{has_repeated_corner, uv_is_degenerate, uv_signed_area2, TriangleMesh};
use crate::cancel;
use crate::error::{Result, UvfeatError};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// Counts that describe the pre-processing.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TopologyDiagnostics {
    /// Vertices as given (before welding).
    pub input_vertices: usize,
    /// Geometric vertices after welding.
    pub geometric_vertices: usize,
    /// Faces with a zero-area UV triangle (or corners that weld together): skipped, their edges
    /// become borders.
    pub degenerate_uv_faces: usize,
    /// Faces whose UV triangle is clockwise (mirrored charts).
    pub mirrored_uv_faces: usize,
    /// Geometric edges per class.
    pub edges: EdgeCounts,
}

/// Welded connectivity, charts and chart-boundary sides of a UV-mapped mesh.
#[derive(Debug, Clone)]
pub struct Topology {
    /// (n_input_vertices) geometric id of every input vertex.
    pub vertex_ids: Vec<u32>,
    /// (n_geometric) the input vertex whose position stands for each geometric vertex.
    pub representative: Vec<u32>,
    /// (n_faces) faces as geometric vertex ids.
    pub faces: Vec<[u32; 3]>,
    /// (n_faces) chart id, `-1` for faces with a degenerate UV triangle.
    pub face_chart: Vec<i32>,
    /// Number of charts.
    pub n_charts: usize,
    /// Every chart-boundary side.
    pub sides: Vec<BoundarySide>,
    /// (n_faces) corner UVs and what lies across each edge of each face (for the exact triangle
    /// walk): the one home of the corner UVs (see [`Topology::corner_uvs`]).
    pub walk_faces: Vec<WalkFace>,
    /// (n_faces) atlas corner of each face corner (`NO_CORNER` for faces without a chart).
    pub corner_groups: Vec<[u32; 3]>,
    /// Number of atlas corners.
    pub n_corners: usize,
    /// The faces around each atlas corner, as compressed rows: those of corner `c` are
    /// `corner_faces[corner_face_start[c]..corner_face_start[c + 1]]`.
    pub corner_face_start: Vec<u32>,
    /// See [`Topology::corner_face_start`].
    pub corner_faces: Vec<u32>,
    /// Counts for reports.
    pub diagnostics: TopologyDiagnostics,
}

impl Topology {
    /// Runs the pre-processing of DESIGN.md §1.2 (welding, charts, edge classes).
    ///
    /// `weld_tolerance` is in object units (0 = exact equality).
    ///
    /// # Errors
    /// [`UvfeatError::AllUvDegenerate`] when no face has a usable UV triangle.
    pub fn build(mesh: &TriangleMesh, weld_tolerance: f64) -> Result<Self> {
        let (vertex_ids, n_geometric) = weld_positions(&mesh.positions, weld_tolerance);
        cancel::check()?;
        let mut representative = vec![u32::MAX; n_geometric];
        for (v, &g) in vertex_ids.iter().enumerate() {
            if representative[g as usize] == u32::MAX {
                representative[g as usize] = v as u32;
            }
        }
        // Face by face in parallel: one thread took 4-12 ms of a 200K-face mesh's pre-processing here.
        let faces: Vec<[u32; 3]> = mesh.faces.par_iter().map(|t| t.map(|v| vertex_ids[v as usize])).collect();
        let corner_uvs: Vec<[DVec2; 3]> = (0..faces.len()).into_par_iter().map(|f| mesh.corner_uvs(f)).collect();
        // A face whose corners weld together is degenerate in 3D and in the edge graph alike.
        let excluded: Vec<bool> =
            faces.par_iter().zip(&corner_uvs).map(|(t, uv)| uv_is_degenerate(uv) || has_repeated_corner(*t)).collect();
        let degenerate_uv_faces = excluded.par_iter().filter(|&&x| x).count();
        if degenerate_uv_faces == faces.len() {
            return Err(UvfeatError::AllUvDegenerate { faces: faces.len() });
        }
        cancel::check()?;
        // The corners' groups need neither the edges nor the charts (a face has a chart unless it
        // is excluded): built beside them (the 200K ellipsoid's topology: 66-100 -> 45-70 ms).
        // Each side checks for a stop between its steps, which take tenths of a second at 2M faces.
        let (edges_and_charts, corners) = rayon::join(
            || -> Result<_> {
                let classes = classify_edges(&faces, &corner_uvs, &excluded);
                cancel::check()?;
                let pairs = classes.interior_pairs.iter().map(|(x, y)| (x.face, y.face));
                let (face_chart, n_charts) = chart_ids(faces.len(), pairs, &excluded);
                cancel::check()?;
                let sides = boundary_sides(&classes.boundary, &face_chart);
                let walk_faces = walk_faces(&corner_uvs, &face_links(faces.len(), &classes.interior_pairs, &sides));
                Ok((classes, face_chart, n_charts, sides, walk_faces))
            },
            || -> Result<_> {
                let (groups, n_corners) = corner_groups(&faces, &corner_uvs, &excluded, n_geometric);
                cancel::check()?;
                let around = groups
                    .iter()
                    .enumerate()
                    .flat_map(|(f, corners)| corners.iter().filter(|&&c| c != NO_CORNER).map(move |&c| (c, f as u32)));
                let (start, faces_around) = compressed_rows(n_corners, around);
                Ok((groups, n_corners, start, faces_around))
            },
        );
        let (classes, face_chart, n_charts, sides, walk_faces) = edges_and_charts?;
        let (corner_groups, n_corners, corner_face_start, corner_faces) = corners?;
        cancel::check()?;
        let mirrored_uv_faces =
            corner_uvs.par_iter().zip(&excluded).filter(|(uv, &skip)| !skip && uv_signed_area2(uv) < 0.0).count();
        let diagnostics = TopologyDiagnostics {
            input_vertices: mesh.positions.len(),
            geometric_vertices: n_geometric,
            degenerate_uv_faces,
            mirrored_uv_faces,
            edges: classes.counts,
        };
        Ok(Self {
            vertex_ids,
            representative,
            faces,
            face_chart,
            n_charts,
            sides,
            walk_faces,
            corner_groups,
            n_corners,
            corner_face_start,
            corner_faces,
            diagnostics,
        })
    }

    /// Number of geometric (welded) vertices.
    pub fn n_geometric(&self) -> usize {
        self.representative.len()
    }

    /// Positions of the geometric vertices, taken from a frame's input positions.
    ///
    /// # Errors
    /// [`UvfeatError::FrameVertexCount`] when `positions` does not have one row per input vertex;
    /// [`UvfeatError::NonFinitePosition`] for NaN or Inf.
    pub fn geometric_positions(&self, positions: &[DVec3]) -> Result<Vec<DVec3>> {
        if positions.len() != self.vertex_ids.len() {
            return Err(UvfeatError::FrameVertexCount { expected: self.vertex_ids.len(), got: positions.len() });
        }
        if let Some((index, p)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(UvfeatError::NonFinitePosition { index, value: p.to_array() });
        }
        Ok(self.representative.iter().map(|&v| positions[v as usize]).collect())
    }

    /// The two geometric vertex ids and corner UVs of a boundary side, in the side's order.
    pub fn side_endpoints(&self, side: &BoundarySide) -> ([u32; 2], [DVec2; 2]) {
        let (f, k) = (side.face as usize, side.local as usize);
        let tri = self.faces[f];
        let uv = self.corner_uvs(f);
        ([tri[k], tri[(k + 1) % 3]], [uv[k], uv[(k + 1) % 3]])
    }

    /// The UV of each corner of face `f` (kept once, in the walk records: 48 bytes per face).
    #[inline]
    pub fn corner_uvs(&self, f: usize) -> [DVec2; 3] {
        self.walk_faces[f].corners
    }

    /// UV of geometric vertex `vertex` in `face` (the vertex must be a corner of the face).
    pub(crate) fn uv_of_vertex(&self, face: u32, vertex: u32) -> DVec2 {
        uv_of_vertex(self.faces[face as usize], self.corner_uvs(face as usize), vertex)
    }
}
