//! Shared fixtures: analytic meshes turned into atlases.

use glam::{DVec2, DVec3};
use std::sync::Arc;
use uvfeat_core::lookup::Lookup;
use uvfeat_core::mesh::{Topology, TriangleMesh};
use uvfeat_core::output::FeatureMaps;
use uvfeat_core::sampling::centre_at;
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

/// The analytic `(H, K)` at a surface point.
pub type Truth = fn(DVec3) -> (f64, f64);

pub fn unit_sphere(_: DVec3) -> (f64, f64) {
    (1.0, 1.0)
}

/// Median relative errors of H and K over the texels, against `truth` at each texel's centre.
pub fn errors(atlas: &Atlas, maps: &FeatureMaps, truth: Truth) -> [f64; 2] {
    let w = maps.resolution;
    let mut out = [0.0; 2];
    for (k, slot) in out.iter_mut().enumerate() {
        let pairs: Vec<(f64, f64)> = (0..w * w)
            .filter(|&t| maps.n_valid[t] > 0)
            .filter_map(|t| {
                let uv = DVec2::new(((t % w) as f64 + 0.5) / w as f64, ((t / w) as f64 + 0.5) / w as f64);
                let centre = centre_at(atlas, uv, Lookup::Triangle)?;
                let exact = if k == 0 { truth(centre.position).0 } else { truth(centre.position).1 };
                Some((f64::from(maps.values[k][t]) - exact, exact.abs()))
            })
            .collect();
        let scale = median(pairs.iter().map(|p| p.1).collect());
        *slot = median(pairs.iter().map(|p| p.0.abs()).collect()) / scale;
    }
    out
}
