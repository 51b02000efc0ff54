//! Per-frame geometry buffers (DESIGN.md §1.3.1, §1.3.3, §1.3.5): position, normal and distortion of
//! the surface point each texel shows, evaluated from the reusable [`Coverage`].

use super::Coverage;
use crate::frame::Frame;
use crate::mesh::{uv_barycentric, Topology};
use glam::DVec3;
use half::f16;
use rayon::prelude::*;

/// Storage precision of the position and normal buffers (DESIGN.md §1.3.5, decision A22).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Precision {
    /// 32-bit floats (default).
    #[default]
    F32,
    /// Values rounded to IEEE half floats, as the paper's GPU textures hold them (Table 2).
    F16,
}

impl Precision {
    fn round(self, x: f32) -> f32 {
        match self {
            Precision::F32 => x,
            Precision::F16 => f16::from_f32(x).to_f32(),
        }
    }

    /// `v` rounded to the precision of the buffers (centres and samples read at that precision).
    pub fn round_point(self, v: DVec3) -> DVec3 {
        match self {
            Precision::F32 => v,
            Precision::F16 => DVec3::from_array(v.to_array().map(|x| f64::from(f16::from_f64(x)))),
        }
    }
}

/// Surface attributes per texel; empty texels hold NaN. Indexing as in [`Coverage`].
#[derive(Debug, Clone, Default)]
pub struct GeometryBuffers {
    /// Barycentric interpolation of the face's positions at the point shown (object units).
    pub position: Vec<[f32; 3]>,
    /// Interpolated vertex normal, renormalised.
    pub normal: Vec<[f32; 3]>,
    /// `(sigma_1, sigma_2)` of the face, object units per uv unit.
    pub sigma: Vec<[f32; 2]>,
    /// Angle of the `sigma_1` axis from +u (radians).
    pub theta: Vec<f32>,
}

impl GeometryBuffers {
    /// Evaluates the buffers of one frame; parallel over rows.
    pub fn evaluate(topology: &Topology, coverage: &Coverage, frame: &Frame, precision: Precision) -> Self {
        let n = coverage.face.len();
        let mut buffers = Self {
            position: vec![[f32::NAN; 3]; n],
            normal: vec![[f32::NAN; 3]; n],
            sigma: vec![[f32::NAN; 2]; n],
            theta: vec![f32::NAN; n],
        };
        buffers.fill(topology, coverage, frame, precision);
        buffers
    }

    /// Writes the covered texels (empty texels keep their NaN).
    fn fill(&mut self, topology: &Topology, coverage: &Coverage, frame: &Frame, precision: Precision) {
        let row = coverage.resolution;
        self.position
            .par_chunks_mut(row)
            .zip(self.normal.par_chunks_mut(row))
            .zip(self.sigma.par_chunks_mut(row))
            .zip(self.theta.par_chunks_mut(row))
            .enumerate()
            .for_each(|(j, (((position, normal), sigma), theta))| {
                for i in 0..row {
                    let t = j * row + i;
                    let Some((face, uv)) = coverage.anchor(topology, t) else {
                        continue;
                    };
                    let face = face as usize;
                    let weights = uv_barycentric(&topology.corner_uvs(face), uv);
                    let tri = topology.faces[face];
                    let interpolate =
                        |values: &[DVec3]| -> DVec3 { (0..3).map(|k| values[tri[k] as usize] * weights[k]).sum() };
                    let p = interpolate(&frame.positions);
                    let nrm = interpolate(&frame.normals).normalize_or_zero();
                    position[i] = p.as_vec3().to_array().map(|x| precision.round(x));
                    normal[i] = nrm.as_vec3().to_array().map(|x| precision.round(x));
                    let d = frame.distortion[face];
                    sigma[i] = [d.sigma1 as f32, d.sigma2 as f32];
                    theta[i] = d.theta as f32;
                }
            });
    }
}
