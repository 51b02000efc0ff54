//! Stage 4 of the pipeline: surface lookup at a parametric point (DESIGN.md §1.3): the exact
//! interpolation of the face the point's texel shows (`lookup = "triangle"`, default), or the
//! paper's bilinear filtering of the geometry buffers (`lookup = "bilinear"`).

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

/// How a parametric point is turned into a surface point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Lookup {
    /// The face's own interpolation, with the smooth (Phong) lift (default).
    #[default]
    Triangle,
    /// Bilinear filtering of the four nearest texels of the geometry buffers that belong to the
    /// chart, as a GPU texture fetch does (the paper's; flat facets, buffer precision, and a blur
    /// of one texel across faces).
    Bilinear,
}

impl Lookup {
    /// The surface at `uv` in `chart`; `face` is the face containing `uv` when the caller knows it
    /// (the walk found it).
    #[inline]
    pub fn evaluate(self, atlas: &Atlas, face: Option<u32>, uv: DVec2, chart: i32) -> Option<SurfacePoint> {
        match (self, face) {
            (Lookup::Triangle, Some(face)) => evaluate_face(atlas, face, uv),
            _ => self.surface_point(atlas, uv, chart),
        }
    }

    /// The surface at `uv` in `chart`.
    #[inline]
    pub fn surface_point(self, atlas: &Atlas, uv: DVec2, chart: i32) -> Option<SurfacePoint> {
        match self {
            Lookup::Triangle => surface_point(atlas, uv, chart),
            Lookup::Bilinear => bilinear_point(atlas, uv, chart),
        }
    }
}

/// Bilinear filtering of the buffers at `uv` over the texels of `chart` among the four nearest
/// (weights renormalised); the nearest texel of `chart` where none of the four belongs to it.
fn bilinear_point(atlas: &Atlas, uv: DVec2, chart: i32) -> Option<SurfacePoint> {
    let coverage = atlas.coverage();
    let buffers = atlas.buffers();
    let n = atlas.resolution() as i64;
    let (x, y) = (uv.x * n as f64 - 0.5, uv.y * n as f64 - 0.5);
    let (i0, j0) = (floor(x), floor(y));
    let (fx, fy) = (x - i0 as f64, y - j0 as f64);
    let usable = |t: usize| coverage.chart[t] == chart && buffers.position[t][0].is_finite();
    let mut texels = [(0usize, 0.0f64); 4];
    let mut count = 0;
    for (di, dj, weight) in
        [(0, 0, (1.0 - fx) * (1.0 - fy)), (1, 0, fx * (1.0 - fy)), (0, 1, (1.0 - fx) * fy), (1, 1, fx * fy)]
    {
        let (i, j) = (i0 + di, j0 + dj);
        // The weight first: a texel with none is not loaded at all.
        if weight > 0.0 && i >= 0 && j >= 0 && i < n && j < n && usable((j * n + i) as usize) {
            texels[count] = ((j * n + i) as usize, weight);
            count += 1;
        }
    }
    if count == 0 {
        texels[0] = (atlas.nearest_texel(uv, usable)?, 1.0);
        count = 1;
    }
    let texels = &texels[..count];
    let total: f64 = texels.iter().map(|&(_, w)| w).sum();
    let mut point = SurfacePoint { position: DVec3::ZERO, normal: DVec3::ZERO, face: 0, area_element: 0.0 };
    let mut heaviest = 0.0;
    for &(t, w) in texels {
        let w = w / total;
        point.position += DVec3::from_array(buffers.position[t].map(f64::from)) * w;
        point.normal += DVec3::from_array(buffers.normal[t].map(f64::from)) * w;
        point.area_element += f64::from(buffers.sigma[t][0]) * f64::from(buffers.sigma[t][1]) * w;
        if w > heaviest {
            heaviest = w;
            point.face = u32::try_from(coverage.face[t]).ok()?;
        }
    }
    point.normal = point.normal.try_normalize()?;
    Some(point)
}

/// `x.floor()` as an integer, without the library call `floor` compiles to on plain x86-64 (this
/// runs for every sample of the bilinear lookup); exact for `|x| < 2^63`.
#[inline]
fn floor(x: f64) -> i64 {
    let truncated = x as i64;
    truncated - i64::from((truncated as f64) > x)
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
    let map = atlas.frame.face_map(&atlas.topology, face)?;
    Some(SurfacePoint {
        position: map.smooth_position(uv),
        normal: map.normal(uv),
        face,
        area_element: map.area_element,
    })
}

fn face_near(atlas: &Atlas, uv: DVec2, chart: i32) -> Option<u32> {
    let coverage = atlas.coverage();
    let texel = atlas.nearest_texel(uv, |t| coverage.chart[t] == chart)?;
    u32::try_from(coverage.face[texel]).ok()
}

#[cfg(test)]
mod tests {
    #[test]
    fn floor_matches_the_library_floor() {
        for x in [-3.0, -2.5, -1.0, -0.75, -0.5, -1e-300, 0.0, 1e-300, 0.5, 1.0, 1023.999, 1024.0, 5e9 + 0.5] {
            assert_eq!(super::floor(x), x.floor() as i64, "{x}");
        }
    }
}
