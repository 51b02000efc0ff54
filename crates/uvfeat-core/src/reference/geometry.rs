//! The position-dependent quantities of the reference: welded positions, vertex normals, vertex
//! and face areas, and where geodesics may bend. Computed per call, so they count in its timing.

use super::connectivity::Connectivity;
use super::voronoi::mixed_voronoi_areas;
use crate::mesh::vertex_normals;
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// A vertex whose angle sum exceeds `2 pi` by more than this is a saddle (radians).
const SADDLE_EXCESS: f64 = 1e-9;

/// Per-vertex and per-face geometry of the welded mesh.
#[derive(Debug, Clone)]
pub struct Geometry {
    /// (n_vertices) welded positions.
    pub positions: Vec<DVec3>,
    /// (n_vertices) unit area-weighted normals (DESIGN.md §0), the same as the parametric side's.
    pub normals: Vec<DVec3>,
    /// (n_vertices) mixed Voronoi areas `A_v` (length^2): the sample weights.
    pub areas: Vec<f64>,
    /// (n_faces) triangle areas (length^2).
    pub face_areas: Vec<f64>,
    /// (n_vertices) saddle (angle sum above `2 pi`) or border vertex: a shortest path may bend
    /// there, so exact geodesics restart from it as a pseudo-source.
    pub pseudo_source: Vec<bool>,
    /// (n_vertices) length of the longest edge at the vertex.
    pub longest_edge: Vec<f64>,
}

impl Geometry {
    /// The geometry of `connectivity` at the input `positions` (one row per input vertex).
    pub fn new(connectivity: &Connectivity, positions: &[DVec3]) -> Self {
        let n = connectivity.n_vertices();
        let mut welded = vec![DVec3::ZERO; n];
        for (v, &g) in connectivity.vertex_ids.iter().enumerate() {
            welded[g as usize] = positions[v];
        }
        let faces = &connectivity.faces;
        let face_areas: Vec<f64> = faces.iter().map(|t| triangle_area(t.map(|v| welded[v as usize]))).collect();
        let mut angle_sum = vec![0.0; n];
        let mut longest_edge = vec![0.0f64; n];
        for tri in faces {
            let p = tri.map(|v| welded[v as usize]);
            for k in 0..3 {
                let (e1, e2) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
                angle_sum[tri[k] as usize] += e1.cross(e2).length().atan2(e1.dot(e2));
                let v = tri[k] as usize;
                longest_edge[v] = longest_edge[v].max(e1.length()).max(e2.length());
            }
        }
        let pseudo_source = angle_sum
            .iter()
            .zip(&connectivity.boundary)
            .map(|(&a, &border)| border || a > TAU + SADDLE_EXCESS)
            .collect();
        Self {
            normals: vertex_normals(&welded, faces),
            areas: mixed_voronoi_areas(&welded, faces),
            positions: welded,
            face_areas,
            pseudo_source,
            longest_edge,
        }
    }
}

/// Area of the triangle with corners `p`.
pub fn triangle_area(p: [DVec3; 3]) -> f64 {
    (p[1] - p[0]).cross(p[2] - p[0]).length() / 2.0
}

/// Triangle `p` laid flat isometrically: `p[0]` at the origin, `p[1]` on +x, `p[2]` at y >= 0.
pub fn flat_triangle(p: [DVec3; 3]) -> [DVec2; 3] {
    let length = p[0].distance(p[1]);
    let axis = (p[1] - p[0]) / length;
    let along = (p[2] - p[0]).dot(axis);
    let across = ((p[2] - p[0]) - axis * along).length();
    [DVec2::ZERO, DVec2::new(length, 0.0), DVec2::new(along, across)]
}
