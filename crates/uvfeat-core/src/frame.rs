//! Per-frame mesh quantities (SPEC §1.9, animation): everything that depends on positions and is
//! recomputed for each frame, on top of the reused topology.

use crate::distortion::Distortion;
use crate::error::Result;
use crate::mesh::{seam_maps, vertex_normals, Jacobian, SeamMap, Topology};
use glam::DVec3;
use rayon::prelude::*;

/// Positions, normals, triangle metrics and seam maps of one frame.
#[derive(Debug, Clone)]
pub struct Frame {
    /// (n_geometric) welded vertex positions.
    pub positions: Vec<DVec3>,
    /// (n_geometric) unit vertex normals.
    pub normals: Vec<DVec3>,
    /// (n_faces) Jacobian of each face; `None` for a degenerate UV triangle.
    pub jacobians: Vec<Option<Jacobian>>,
    /// (n_faces) distortion of each face (zeros where the Jacobian is missing).
    pub distortion: Vec<Distortion>,
    /// (n_sides) transition map of each boundary side; `None` where nothing is across.
    pub seam_maps: Vec<Option<SeamMap>>,
}

impl Frame {
    /// Computes the frame from the input positions (one row per input vertex).
    ///
    /// # Errors
    /// Vertex count mismatch or non-finite positions (see [`Topology::geometric_positions`]).
    pub fn new(topology: &Topology, input_positions: &[DVec3]) -> Result<Self> {
        let positions = topology.geometric_positions(input_positions)?;
        let normals = vertex_normals(&positions, &topology.faces);
        let jacobians: Vec<Option<Jacobian>> = topology
            .faces
            .par_iter()
            .zip(&topology.corner_uvs)
            .zip(&topology.face_chart)
            .map(|((tri, uv), &chart)| {
                if chart < 0 {
                    return None;
                }
                Jacobian::of_triangle(tri.map(|v| positions[v as usize]), *uv)
            })
            .collect();
        let zero = Distortion { sigma1: 0.0, sigma2: 0.0, theta: 0.0 };
        let distortion =
            jacobians.par_iter().map(|j| j.map_or(zero, |j| Distortion::from_metric(j.metric()))).collect();
        let seam_maps = seam_maps(topology, &positions);
        Ok(Self { positions, normals, jacobians, distortion, seam_maps })
    }
}
