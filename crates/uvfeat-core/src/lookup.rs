//! Surface lookup at a parametric point (SPEC §1.3, `lookup = "triangle"`): the exact
//! barycentric interpolation of the face the point's texel shows.

use crate::atlas::Atlas;
use glam::{DVec2, DVec3};

/// The surface at a parametric point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Position (object units).
    pub position: DVec3,
    /// Unit normal, interpolated from the vertex normals and renormalised.
    pub normal: DVec3,
    /// Face whose parameterisation was evaluated.
    pub face: u32,
    /// Area element `J = sigma_1 sigma_2` of that face (object area per uv area).
    pub area_element: f64,
}

/// Evaluates the surface at `uv`, expected in `chart`.
///
/// Uses the face of the texel containing `uv` when that texel belongs to `chart`, else the face of
/// the nearest texel of `chart` in the 3x3 neighbourhood (points in the gutter just outside a
/// chart extrapolate the closest face linearly). `None` when no texel of `chart` is near.
pub fn surface_point(atlas: &Atlas, uv: DVec2, chart: i32) -> Option<SurfacePoint> {
    let face = face_near(atlas, uv, chart)?;
    Some(evaluate_face(atlas, face, uv))
}

/// Barycentric evaluation of `face`'s affine parameterisation at `uv` (extrapolating outside).
pub fn evaluate_face(atlas: &Atlas, face: u32, uv: DVec2) -> SurfacePoint {
    let topology = &atlas.topology;
    let [u0, u1, u2] = topology.corner_uvs[face as usize];
    let area2 = (u1 - u0).perp_dot(u2 - u0);
    let b1 = (uv - u0).perp_dot(u2 - u0) / area2;
    let b2 = (u1 - u0).perp_dot(uv - u0) / area2;
    let weights = [1.0 - b1 - b2, b1, b2];
    let tri = topology.faces[face as usize];
    let blend = |values: &[DVec3]| -> DVec3 { (0..3).map(|k| values[tri[k] as usize] * weights[k]).sum() };
    let frame = &atlas.frame;
    SurfacePoint {
        position: blend(&frame.positions),
        normal: blend(&frame.normals).normalize_or_zero(),
        face,
        area_element: frame.distortion[face as usize].area_element(),
    }
}

fn face_near(atlas: &Atlas, uv: DVec2, chart: i32) -> Option<u32> {
    let coverage = &atlas.coverage;
    let texel = atlas.nearest_texel(uv, |t| coverage.chart[t] == chart)?;
    u32::try_from(coverage.face[texel]).ok()
}
