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
#[inline]
pub fn surface_point(atlas: &Atlas, uv: DVec2, chart: i32) -> Option<SurfacePoint> {
    evaluate_face(atlas, face_near(atlas, uv, chart)?, uv)
}

/// Evaluates `face`'s affine parameterisation at `uv` (extrapolating outside the face).
/// `None` for a face with a degenerate UV triangle.
#[inline]
pub fn evaluate_face(atlas: &Atlas, face: u32, uv: DVec2) -> Option<SurfacePoint> {
    let map = atlas.frame.face_maps[face as usize].as_ref()?;
    Some(SurfacePoint {
        position: map.smooth_position(uv),
        normal: map.normal(uv),
        face,
        area_element: map.area_element,
    })
}

fn face_near(atlas: &Atlas, uv: DVec2, chart: i32) -> Option<u32> {
    let coverage = &atlas.coverage;
    let texel = atlas.nearest_texel(uv, |t| coverage.chart[t] == chart)?;
    u32::try_from(coverage.face[texel]).ok()
}
