//! Analytic UV-mapped meshes with known geometry, for tests, benchmarks and demos.
//!
//! Every shape is a regular grid over a parameter rectangle, mapped into `[m, 1-m]^2` of UV space
//! (`m` = gutter margin) and triangulated with counter-clockwise corners seen from outside.
//! Periodic directions share positions but not UVs, so they become (self-adjacent) seams.

use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// Flat arrays of a UV-mapped triangle mesh (the input form of [`crate::mesh::TriangleMesh`]).
#[derive(Debug, Clone, Default)]
pub struct ShapeMesh {
    /// (n_vertices) positions.
    pub positions: Vec<[f64; 3]>,
    /// (n_faces) vertex indices, counter-clockwise from outside.
    pub faces: Vec<[i64; 3]>,
    /// (n_uvs) parametric coordinates in `[0, 1]^2`.
    pub uvs: Vec<[f64; 2]>,
    /// (n_faces) indices into `uvs` per corner.
    pub uv_faces: Vec<[i64; 3]>,
}

/// Gutter left between the chart and the edge of UV space.
const MARGIN: f64 = 0.02;

struct Grid {
    nu: usize,
    nv: usize,
    wrap_u: bool,
    /// Rows `v = 0` and `v = 1` collapse to one vertex (sphere poles).
    poles: bool,
}

impl Grid {
    fn build(&self, surface: impl Fn(f64, f64) -> DVec3) -> ShapeMesh {
        let (nu, nv) = (self.nu, self.nv);
        let cols = if self.wrap_u { nu } else { nu + 1 };
        let mut mesh = ShapeMesh::default();
        let mut vertex = vec![vec![0i64; nu + 1]; nv + 1];
        for (j, row) in vertex.iter_mut().enumerate() {
            let at_pole = self.poles && (j == 0 || j == nv);
            for (i, slot) in row.iter_mut().enumerate() {
                if (at_pole && i > 0) || (self.wrap_u && i == nu) {
                    continue;
                }
                *slot = mesh.positions.len() as i64;
                let p = surface(i as f64 / nu as f64, j as f64 / nv as f64);
                mesh.positions.push(p.to_array());
            }
            for i in 0..=nu {
                if at_pole {
                    row[i] = row[0];
                } else if i >= cols {
                    row[i] = row[i % cols];
                }
            }
        }
        let uv_index = |i: usize, j: usize| (j * (nu + 1) + i) as i64;
        for j in 0..=nv {
            for i in 0..=nu {
                let t = DVec2::new(i as f64 / nu as f64, j as f64 / nv as f64);
                mesh.uvs.push((DVec2::splat(MARGIN) + t * (1.0 - 2.0 * MARGIN)).to_array());
            }
        }
        for j in 0..nv {
            for i in 0..nu {
                let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
                let tris: &[[usize; 3]] = if self.poles && j == 0 {
                    &[[0, 2, 3]]
                } else if self.poles && j == nv - 1 {
                    &[[0, 1, 2]]
                } else {
                    &[[0, 1, 2], [0, 2, 3]]
                };
                for tri in tris {
                    mesh.faces.push(tri.map(|k| vertex[corners[k].1][corners[k].0]));
                    mesh.uv_faces.push(tri.map(|k| uv_index(corners[k].0, corners[k].1)));
                }
            }
        }
        mesh
    }
}

/// Latitude–longitude sphere of `radius` (one chart, a seam along a meridian, two poles).
/// `u` = longitude / 2pi, `v` = (latitude + pi/2) / pi. Outward normals; `H = 1/radius`.
pub fn uv_sphere(radius: f64, n_lon: usize, n_lat: usize) -> ShapeMesh {
    ellipsoid([radius; 3], n_lon, n_lat)
}

/// Axis-aligned ellipsoid with semi-axes `axes`, parameterised like [`uv_sphere`].
pub fn ellipsoid(axes: [f64; 3], n_lon: usize, n_lat: usize) -> ShapeMesh {
    let grid = Grid { nu: n_lon.max(3), nv: n_lat.max(2), wrap_u: true, poles: true };
    grid.build(|u, v| {
        let (lon, lat) = (TAU * u, PI * (v - 0.5));
        if v == 0.0 || v == 1.0 {
            return DVec3::new(0.0, 0.0, lat.signum() * axes[2]);
        }
        DVec3::new(axes[0] * lat.cos() * lon.cos(), axes[1] * lat.cos() * lon.sin(), axes[2] * lat.sin())
    })
}

/// Torus around the z axis, tube centre radius `major`, tube radius `minor`; `u` runs around the
/// axis, `v` around the tube (`v = 0` on the outer equator). Both directions are self-adjacent
/// seams of one chart. `H = (R + 2a cos v) / (2a (R + a cos v))`, `K = cos v / (a (R + a cos v))`.
pub fn torus(major: f64, minor: f64, n_u: usize, n_v: usize) -> ShapeMesh {
    let grid = Grid { nu: n_u.max(3), nv: n_v.max(3), wrap_u: true, poles: false };
    let mut mesh = grid.build(|u, v| {
        let (phi, psi) = (TAU * u, TAU * v);
        let ring = major + minor * psi.cos();
        DVec3::new(ring * phi.cos(), ring * phi.sin(), minor * psi.sin())
    });
    // Close the tube: the last row of positions repeats the first.
    let row = n_u.max(3);
    let last_row_start = mesh.positions.len() - row;
    for face in &mut mesh.faces {
        for v in face.iter_mut() {
            if *v as usize >= last_row_start {
                *v -= last_row_start as i64;
            }
        }
    }
    mesh.positions.truncate(last_row_start);
    mesh
}

/// Open cylinder of `radius` and `height` around the z axis (one chart, one self-adjacent seam,
/// two border loops). `H = 1/(2 radius)`, `K = 0`.
pub fn cylinder(radius: f64, height: f64, n_around: usize, n_along: usize) -> ShapeMesh {
    let grid = Grid { nu: n_around.max(3), nv: n_along.max(1), wrap_u: true, poles: false };
    grid.build(|u, v| DVec3::new(radius * (TAU * u).cos(), radius * (TAU * u).sin(), height * (v - 0.5)))
}

/// Square `[0, size]^2` in the plane `z = 0` (normal +z) with the affine parameterisation
/// `(x, y) = size (u', v')` (one chart, border all around).
pub fn plane(size: f64, n: usize) -> ShapeMesh {
    let grid = Grid { nu: n.max(1), nv: n.max(1), wrap_u: false, poles: false };
    grid.build(|u, v| DVec3::new(size * u, size * v, 0.0))
}

/// Unit square in `z = 0` cut along `x = 1/2` into two charts: the left half keeps its affine
/// layout, the right half is stretched anisotropically, rotated by 30 degrees and, if `mirrored`,
/// reflected (a clockwise chart). Exercises every kind of seam transition map.
pub fn split_plane(n: usize, mirrored: bool) -> ShapeMesh {
    let mut mesh = plane(1.0, n.max(2) & !1);
    let rotation = DVec2::from_angle(PI / 6.0);
    let (flip, offset) = if mirrored { (-1.0, DVec2::new(0.95, 0.35)) } else { (1.0, DVec2::new(0.7, 0.35)) };
    let left = |p: [f64; 3]| [0.05 + 0.8 * p[0], 0.05 + 0.9 * p[1]];
    let right = |p: [f64; 3]| {
        let local = DVec2::new(flip * 0.5 * (p[0] - 0.5), 0.3 * p[1]);
        (rotation.rotate(local) + offset).to_array()
    };
    let positions = &mesh.positions;
    let mut uvs = Vec::with_capacity(3 * mesh.faces.len());
    let mut uv_faces = Vec::with_capacity(mesh.faces.len());
    for face in &mesh.faces {
        let corners = face.map(|v| positions[v as usize]);
        let in_right_half = corners.iter().map(|p| p[0]).sum::<f64>() > 1.5;
        let base = uvs.len() as i64;
        uvs.extend(corners.map(|p| if in_right_half { right(p) } else { left(p) }));
        uv_faces.push([base, base + 1, base + 2]);
    }
    mesh.uvs = uvs;
    mesh.uv_faces = uv_faces;
    mesh
}
