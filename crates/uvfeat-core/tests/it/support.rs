//! Shared fixtures: analytic meshes turned into atlases.

use glam::{DVec2, DVec3};
use std::sync::Arc;
use uvfeat_core::mesh::{Topology, TriangleMesh};
use uvfeat_core::shapes::{uv_sphere, ShapeMesh};
use uvfeat_core::{Atlas, AtlasOptions};

pub fn triangle_mesh(shape: &ShapeMesh) -> TriangleMesh {
    TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).expect("valid analytic mesh")
}

pub fn atlas(shape: &ShapeMesh, resolution: usize) -> Atlas {
    let mesh = triangle_mesh(shape);
    let topology = Arc::new(Topology::build(&mesh, 0.0).expect("topology"));
    let options = AtlasOptions { resolution, ..AtlasOptions::default() };
    Atlas::new(topology, &mesh.positions, &options).expect("atlas")
}

/// Barycentric coordinates of `p` in the UV triangle `uv`.
pub fn barycentric(uv: [DVec2; 3], p: DVec2) -> [f64; 3] {
    let area2 = (uv[1] - uv[0]).perp_dot(uv[2] - uv[0]);
    let b1 = (p - uv[0]).perp_dot(uv[2] - uv[0]) / area2;
    let b2 = (uv[1] - uv[0]).perp_dot(p - uv[0]) / area2;
    [1.0 - b1 - b2, b1, b2]
}

/// Exact interpolation of the face's geometric positions with barycentric weights `b`.
pub fn interpolate(atlas: &Atlas, face: usize, b: [f64; 3]) -> DVec3 {
    let tri = atlas.topology.faces[face];
    (0..3).map(|k| atlas.frame.positions[tri[k] as usize] * b[k]).sum()
}

/// Median of the finite values (panics when there is none).
pub fn median(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    assert!(!v.is_empty());
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v[v.len() / 2]
}

/// The lat-long sphere cut into `blocks` x `blocks` charts, each turned by a quarter turn per
/// block (so every seam has a rotating transition map) and shrunk into its own slot of the atlas.
pub fn patchwork_sphere(blocks: usize) -> ShapeMesh {
    let mut mesh = uv_sphere(1.0, 96, 48);
    let mut uvs = Vec::with_capacity(3 * mesh.faces.len());
    for uv_face in mesh.uv_faces.iter_mut() {
        let corners = uv_face.map(|k| DVec2::from_array(mesh.uvs[k as usize]));
        let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
        let slot = (centroid * blocks as f64).floor().min(DVec2::splat(blocks as f64 - 1.0));
        let turn = DVec2::from_angle(std::f64::consts::FRAC_PI_2 * ((slot.x + slot.y) as i32 % 4) as f64);
        let base = uvs.len() as i64;
        uvs.extend(corners.map(|c| {
            let local = c * blocks as f64 - slot - DVec2::splat(0.5);
            ((slot + DVec2::splat(0.5) + 0.8 * turn.rotate(local)) / blocks as f64).to_array()
        }));
        *uv_face = [base, base + 1, base + 2];
    }
    mesh.uvs = uvs;
    mesh
}
