//! Per-vertex values evaluated at the vertices themselves (DESIGN.md §1.9): each welded vertex is
//! the centre of its own neighbourhood, whose surfels' moments are summed (DESIGN.md §1.4.9), with
//! no feature map in between (`Atlas.per_vertex` and `uvfeat.compute` with the surfels).

use super::corners::{Corner, VertexCorners};
use crate::atlas::Atlas;
use crate::cancel;
use crate::error::{Result, UvfeatError};
use crate::evaluation::{integration, Integration, PixelResult};
use crate::features::{surfel_sums, SurfelCentre};
use crate::raster::morton;
use crate::sampling::SampleCounts;
use crate::settings::ComputeSettings;
use rayon::prelude::*;

/// Values at every input vertex.
#[derive(Debug, Clone, PartialEq)]
pub struct VertexValues {
    /// One `Vec` per feature, one value per input vertex.
    pub values: Vec<Vec<f32>>,
    /// Per input vertex: surfels summed (`valid`) and those of them inside the ball that a mesh
    /// border passes through (`border`: the neighbourhood is truncated).
    pub counts: Vec<SampleCounts>,
}

/// Whether `settings` can be evaluated from the surfels' moments on `atlas`: the surfel
/// quadrature's integral estimators (the quadric fit needs every sample, not sums).
pub fn sums_apply(atlas: &Atlas, settings: &ComputeSettings) -> bool {
    integration(atlas, settings) == Integration::SurfelSums
}

/// Every feature of `settings` at every *input* vertex (one `Vec` per feature, in the order of
/// `settings.features`; vertices the file split at seams share their welded vertex's value; NaN
/// where a vertex is on no chart), with each vertex's counts.
///
/// # Errors
/// [`UvfeatError::InvalidParameter`] for settings that fail validation or that the sums do not
/// serve ([`sums_apply`]).
pub fn vertex_values(atlas: &Atlas, settings: &ComputeSettings) -> Result<VertexValues> {
    values_at(atlas, settings, None)
}

/// [`vertex_values`] with a radius per input vertex (`radii[i]` for row `i`; rows the file split at
/// seams are one welded vertex, which takes its first row's radius): each vertex's ball, inner
/// exclusion and estimators take its own radius, and `settings.radius` is not read.
///
/// # Errors
/// As [`vertex_values`]; [`UvfeatError::InvalidParameter`] when `radii` has not one positive
/// finite radius per input vertex.
pub fn vertex_values_at_radii(atlas: &Atlas, settings: &ComputeSettings, radii: &[f64]) -> Result<VertexValues> {
    let ids = &atlas.topology.vertex_ids;
    if radii.len() != ids.len() {
        return Err(UvfeatError::InvalidParameter {
            name: "radius",
            reason: format!("{} per-vertex radii for {} vertices", radii.len(), ids.len()),
        });
    }
    if let Some(row) = radii.iter().position(|r| !(r.is_finite() && *r > 0.0)) {
        return Err(UvfeatError::InvalidParameter {
            name: "radius",
            reason: format!("the radius of vertex {row} is {}: radii must be positive and finite", radii[row]),
        });
    }
    let mut welded = vec![f64::NAN; atlas.frame.positions.len()];
    for (&g, &r) in ids.iter().zip(radii).rev() {
        welded[g as usize] = r;
    }
    values_at(atlas, settings, Some(&welded))
}

/// Values at the welded vertices, each with radius `radii[vertex]` where given.
fn values_at(atlas: &Atlas, settings: &ComputeSettings, radii: Option<&[f64]>) -> Result<VertexValues> {
    settings.validate()?;
    if !sums_apply(atlas, settings) {
        return Err(UvfeatError::InvalidParameter {
            name: "quadrature",
            reason: "values at the vertices sum the surfels' moments: quadrature=\"surfels\" with method=\"integral\""
                .into(),
        });
    }
    // Each vertex's first corner, read once (the topology's corner tables are scattered).
    let first_corners: Vec<Option<Corner>> = {
        let corners = VertexCorners::new(atlas);
        (0..corners.n_vertices()).into_par_iter().map(|vertex| corners.first(vertex)).collect()
    };
    let frame = &atlas.frame;
    atlas.surfels(settings.surface);
    // Vertices in the order of their texels along a Z curve, so that the vertices one thread takes
    // in turn share most of their surfels, which then come from the cache (the search is bound by
    // memory latency: in the file's order the armadillo took 1.5-1.9x as long).
    let mut order: Vec<(u64, u32)> = first_corners
        .par_iter()
        .enumerate()
        .map(|(vertex, corner)| (corner.map_or(u64::MAX, |c| z_order(c.uv, atlas.resolution())), vertex as u32))
        .collect();
    order.par_sort_unstable();
    let shared_sums = settings.surfel_sums();
    let sorted: Vec<PixelResult> = order
        .par_iter()
        // One copy of the settings per job, its radius set per vertex where the vertices have their own.
        .map_init(
            || settings.clone(),
            |own, &(_, vertex)| {
                if cancel::requested() {
                    return PixelResult::EMPTY;
                }
                let vertex = vertex as usize;
                let Some(corner) = first_corners[vertex] else {
                    return PixelResult::EMPTY;
                };
                let distortion = frame.sampling_distortion(&atlas.topology, corner.face, corner.uv);
                let (position, normal) = (frame.positions[vertex], frame.normals[vertex]);
                let centre =
                    SurfelCentre::new(position, normal, corner.uv, corner.chart, &distortion, atlas.resolution());
                let sums = match radii {
                    Some(radii) => {
                        own.radius = radii[vertex];
                        own.surfel_sums()
                    }
                    None => shared_sums,
                };
                let (stats, counts) = surfel_sums(atlas, &centre, &sums);
                if counts.valid == 0 {
                    return PixelResult::EMPTY;
                }
                PixelResult::estimated(&stats, None, counts, own)
            },
        )
        .collect();
    cancel::check()?;
    let mut results = vec![PixelResult::EMPTY; sorted.len()];
    for (&(_, vertex), result) in order.iter().zip(sorted) {
        results[vertex as usize] = result;
    }
    let ids = &atlas.topology.vertex_ids;
    let values = settings
        .features
        .iter()
        .map(|f| ids.iter().map(|&g| results[g as usize].values[f.index()]).collect())
        .collect();
    Ok(VertexValues { values, counts: ids.iter().map(|&g| results[g as usize].counts).collect() })
}

/// Position of texel-space point `uv` along a Z (Morton) curve over a `resolution`² grid.
fn z_order(uv: glam::DVec2, resolution: usize) -> u64 {
    let cell = |x: f64| (x * resolution as f64).clamp(0.0, resolution as f64 - 1.0) as usize;
    morton(cell(uv.x), cell(uv.y))
}
