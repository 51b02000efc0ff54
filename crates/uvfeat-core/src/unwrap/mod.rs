//! Stage 1 of the pipeline: an automatic UV atlas for a mesh that has none (DESIGN.md §1.1.1),
//! beside the mesh.
//!
//! The parametric features need of an atlas only that each chart is injective and its distortion
//! bounded: every face's metric tensor (§1.3) undoes the parametrisation's stretch. Charts whose
//! (smoothed) normals lie within a cone of half-angle θ, projected orthographically onto the plane
//! across the cone's axis, are exactly that (stretch about `1 / cos θ`, injectivity checked as
//! they grow), and they take a fraction of a second where an optimising unwrapper (xatlas: about
//! 20 s for 100K faces on two cores) takes seconds per ten thousand faces.

mod charted_surface;
mod fragments;
mod pack;
mod segment;

use crate::atlas::MAX_RESOLUTION;
use crate::cancel;
use crate::error::{Result, UvfeatError};
use crate::mesh::{
    checked_indices, checked_positions, has_repeated_corner, sorted_half_edges, unit_face_normal, weld_positions,
};
use charted_surface::charted_positions;
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use segment::{FaceGraph, NO_FACE};

/// How the charts are cut and packed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnwrapOptions {
    /// Half-angle θ of the normal cone of a chart, in degrees, in `(0, 90)`.
    pub max_angle_degrees: f64,
    /// Texture size the packing is made for; `padding` is in texels at that size.
    pub resolution: usize,
    /// Gutter between charts, in texels at `resolution` (at least 2 keeps bilinear reads apart).
    pub padding: f64,
}

impl Default for UnwrapOptions {
    fn default() -> Self {
        Self { max_angle_degrees: 45.0, resolution: 1024, padding: 4.0 }
    }
}

/// A UV atlas for the input faces.
#[derive(Debug, Clone)]
pub struct Unwrapped {
    /// (n_uvs) UV coordinates in `[0, 1]^2`.
    pub uvs: Vec<DVec2>,
    /// (n_faces) UV indices per face corner, in the order of the input faces.
    pub uv_faces: Vec<[u32; 3]>,
    /// Number of charts.
    pub n_charts: usize,
}

/// Cuts the mesh into normal-cone charts and packs them into the unit square.
///
/// Vertices at the same position are welded first, so a mesh split at normal seams (PLY, glTF)
/// is charted as one surface; edges with more than two faces are chart borders.
///
/// # Errors
/// [`UvfeatError::EmptyMesh`], [`UvfeatError::NonFinitePosition`], [`UvfeatError::IndexOutOfRange`],
/// [`UvfeatError::InvalidResolution`], [`UvfeatError::InvalidParameter`] for an angle outside
/// `(0, 90)` degrees, a negative padding, or more charts than the resolution has room for.
pub fn unwrap(positions: &[[f64; 3]], faces: &[[i64; 3]], options: &UnwrapOptions) -> Result<Unwrapped> {
    check_options(options)?;
    if positions.is_empty() || faces.is_empty() {
        return Err(UvfeatError::EmptyMesh { vertices: positions.len(), faces: faces.len() });
    }
    let input_positions = checked_positions(positions)?;
    let input_faces = checked_indices(faces, positions.len(), "vertex")?;
    let (vertex_ids, n_welded) = weld_positions(&input_positions, 0.0);
    // Charts do not depend on the mesh's scale (the packing sets it): work in [-1, 1]^3, where no
    // distance, area or cross product of finite coordinates overflows.
    let largest = input_positions.iter().fold(0.0f64, |m, p| m.max(p.abs().max_element()));
    let unit = if largest > 0.0 { 1.0 / largest } else { 1.0 };
    let mut welded = vec![DVec3::ZERO; n_welded];
    for (p, &id) in input_positions.iter().zip(&vertex_ids) {
        welded[id as usize] = *p * unit;
    }
    let welded_faces: Vec<[u32; 3]> = input_faces.iter().map(|t| t.map(|v| vertex_ids[v as usize])).collect();
    let face_normals = |positions: &[DVec3]| -> Vec<DVec3> {
        welded_faces.par_iter().map(|t| unit_face_normal(t.map(|v| positions[v as usize]))).collect()
    };
    let neighbours = face_neighbours(&welded_faces);
    cancel::check()?;
    let own_normals = face_normals(&welded);
    let own_smoothed = smoothed_normals(&own_normals, &neighbours);
    cancel::check()?;
    let (charted, normals, smoothed) = match charted_positions(&welded, &welded_faces, &own_normals, &own_smoothed) {
        Some(charted) => {
            let normals = face_normals(&charted);
            let smoothed = smoothed_normals(&normals, &neighbours);
            (charted, normals, smoothed)
        }
        None => (welded, own_normals, own_smoothed),
    };
    cancel::check()?;
    let centroids: Vec<DVec3> =
        welded_faces.par_iter().map(|t| t.iter().map(|&v| charted[v as usize]).sum::<DVec3>() / 3.0).collect();
    let graph = FaceGraph {
        positions: &charted,
        faces: &welded_faces,
        neighbours: &neighbours,
        normals: &normals,
        smoothed_normals: &smoothed,
        centroids: &centroids,
        cell: 2.0 * mean_edge_length(&charted, &welded_faces),
    };
    let mut charts = segment::grow_charts(&graph, segment::Cone::new(options.max_angle_degrees));
    cancel::check()?;
    fragments::merge_fragments(&graph, &mut charts);
    cancel::check()?;
    pack::pack(
        &mut charts.uvs,
        &charts.uv_faces,
        &charts.uv_chart,
        charts.n_charts,
        options.resolution,
        options.padding,
    )
    .ok_or_else(|| UvfeatError::InvalidParameter {
        name: "resolution",
        reason: format!(
            "{} charts with gutters of {} texels do not fit in {}² texels; raise the resolution or the cone angle",
            charts.n_charts, options.padding, options.resolution
        ),
    })?;
    Ok(Unwrapped { uvs: charts.uvs, uv_faces: charts.uv_faces, n_charts: charts.n_charts })
}

fn check_options(options: &UnwrapOptions) -> Result<()> {
    if options.resolution == 0 || options.resolution > MAX_RESOLUTION {
        return Err(UvfeatError::InvalidResolution { resolution: options.resolution, max: MAX_RESOLUTION });
    }
    if !(options.max_angle_degrees > 0.0 && options.max_angle_degrees < 90.0) {
        return Err(UvfeatError::InvalidParameter {
            name: "max_angle",
            reason: format!(
                "{} degrees is not in (0, 90): a chart's normals must stay in one hemisphere",
                options.max_angle_degrees
            ),
        });
    }
    if !(options.padding >= 0.0 && options.padding.is_finite()) {
        return Err(UvfeatError::InvalidParameter {
            name: "padding",
            reason: format!("{} texels is not a finite, non-negative gutter", options.padding),
        });
    }
    Ok(())
}

/// The face across each edge `(k, k + 1)` of every face, [`NO_FACE`] on borders, non-manifold
/// edges, between faces of opposite orientation (which no chart may join: one would be mirrored)
/// and next to faces whose corners weld together.
fn face_neighbours(faces: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let sides = sorted_half_edges(faces);
    let mut neighbours = vec![[NO_FACE; 3]; faces.len()];
    for group in sides.chunk_by(|x, y| x.0 == y.0) {
        // A face with a repeated corner is no one's neighbour (nor does it hide one).
        let mut live = group.iter().map(|&(_, h)| h).filter(|h| !has_repeated_corner(faces[*h as usize / 3]));
        if let (Some(x), Some(y), None) = (live.next(), live.next(), live.next()) {
            let ((fx, kx), (fy, ky)) = ((x / 3, x % 3), (y / 3, y % 3));
            // Consistently oriented neighbours run along their shared edge in opposite directions.
            if faces[fx as usize][kx as usize] == faces[fy as usize][(ky as usize + 1) % 3] {
                neighbours[fx as usize][kx as usize] = fy;
                neighbours[fy as usize][ky as usize] = fx;
            }
        }
    }
    neighbours
}

/// Face normals averaged with their edge neighbours' [`SMOOTHING_STEPS`] times: what the cone
/// test reads, so that noise at the scale of the faces (a scan's, or 0.3 edge lengths of normal
/// noise: 44,076 charts on a 200K-face torus) does not cut a chart at every face.
fn smoothed_normals(normals: &[DVec3], neighbours: &[[u32; 3]]) -> Vec<DVec3> {
    let mut smoothed = normals.to_vec();
    for _ in 0..SMOOTHING_STEPS {
        smoothed = (0..normals.len())
            .into_par_iter()
            .map(|f| {
                let around = neighbours[f].iter().filter(|&&g| g != NO_FACE).map(|&g| smoothed[g as usize]);
                (smoothed[f] + around.sum::<DVec3>()).normalize_or_zero()
            })
            .collect();
    }
    smoothed
}

/// Rounds of neighbour averaging in [`smoothed_normals`] (about as many rings of faces).
const SMOOTHING_STEPS: usize = 4;

fn mean_edge_length(positions: &[DVec3], faces: &[[u32; 3]]) -> f64 {
    let total: f64 = faces
        .par_iter()
        .map(|t| (0..3).map(|k| positions[t[k] as usize].distance(positions[t[(k + 1) % 3] as usize])).sum::<f64>())
        .sum();
    let mean = total / (3 * faces.len()) as f64;
    if mean > 0.0 {
        mean
    } else {
        1.0
    }
}

impl Unwrapped {
    /// UV indices per face corner as the flat `i64` rows the mesh constructors take.
    pub fn uv_face_rows(&self) -> Vec<[i64; 3]> {
        self.uv_faces.iter().map(|t| t.map(i64::from)).collect()
    }

    /// UVs as `[f64; 2]` rows.
    pub fn uv_rows(&self) -> Vec<[f64; 2]> {
        self.uvs.iter().map(|uv| uv.to_array()).collect()
    }
}
