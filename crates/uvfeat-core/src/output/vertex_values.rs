//! Per-vertex values evaluated at the vertices themselves (DESIGN.md §1.9): each welded vertex is
//! the centre of its own neighbourhood, whose surfels' moments are summed (DESIGN.md §1.4.9), with
//! no feature map in between (`Atlas.per_vertex` and `uvfeat.compute` with the surfels).

use super::corners::{Corner, VertexCorners};
use crate::atlas::Atlas;
use crate::cancel;
use crate::error::{Result, UvfeatError};
use crate::evaluation::{integration, Integration, PixelResult};
use crate::features::{surfel_sums, SurfelCentre, SurfelSumSettings};
use crate::raster::morton;
use crate::raster::Surfels;
use crate::sampling::{levels_to_build, SampleCounts, SurfelBall, SurfelCount};
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
    let frame = &atlas.frame;
    let surfels = atlas.surfels(settings.surface);
    // Vertices in the order of their texels along a Z curve, so that the vertices one thread takes
    // in turn share most of their surfels, which then come from the cache (in the file's order the
    // armadillo took 1.5-1.9x as long); each with its first corner, read once (the topology's
    // corner tables are scattered).
    let mut order: Vec<(u64, u32, Option<Corner>)> = {
        let corners = VertexCorners::new(atlas);
        (0..corners.n_vertices())
            .into_par_iter()
            .map(|vertex| {
                let corner = corners.first(vertex);
                (corner.map_or(u64::MAX, |c| z_order(c.uv, atlas.resolution())), vertex as u32, corner)
            })
            .collect()
    };
    order.par_sort_unstable_by_key(|&(key, vertex, _)| (key, vertex));
    let centres: Vec<Option<SurfelCentre>> = order
        .par_iter()
        .map(|&(_, vertex, corner)| {
            let corner = corner?;
            let distortion = frame.sampling_distortion(&atlas.topology, corner.face, corner.uv);
            let (position, normal) = (frame.positions[vertex as usize], frame.normals[vertex as usize]);
            Some(SurfelCentre::new(position, normal, corner.uv, corner.chart, &distortion, atlas.resolution()))
        })
        .collect();
    let radius_of = |vertex: u32| radii.map_or(settings.radius, |radii| radii[vertex as usize]);
    // The coarser levels are built only as far as the balls need them (`levels_to_build`).
    let asked =
        order.iter().zip(&centres).filter_map(|(&(_, vertex, _), centre)| Some((centre.as_ref()?, radius_of(vertex))));
    let shared_sums = SurfelSumSettings {
        count: built_levels(surfels, asked, settings.surfel_sums().count),
        ..settings.surfel_sums()
    };
    let sorted: Vec<PixelResult> = order
        .par_iter()
        .zip(&centres)
        // One copy of the settings per job, its radius set per vertex where the vertices have their own.
        .map_init(
            || settings.clone(),
            |own, (&(_, vertex, _), centre)| {
                if cancel::requested() {
                    return PixelResult::EMPTY;
                }
                let Some(centre) = centre else {
                    return PixelResult::EMPTY;
                };
                let sums = match radii {
                    Some(_) => {
                        own.radius = radius_of(vertex);
                        SurfelSumSettings { count: shared_sums.count, ..own.surfel_sums() }
                    }
                    None => shared_sums,
                };
                let (stats, counts) = surfel_sums(atlas, centre, &sums);
                if counts.valid == 0 {
                    return PixelResult::EMPTY;
                }
                PixelResult::estimated(&stats, None, counts, own)
            },
        )
        .collect();
    cancel::check()?;
    let mut results = vec![PixelResult::EMPTY; sorted.len()];
    for (&(_, vertex, _), result) in order.iter().zip(sorted) {
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

/// `count` with the coarsest level of `surfels` that balls around the `(centre, radius)` of `asked`
/// are summed at, built here before their parallel loop: the finest whose balls that ask for
/// coarser ones add little work ([`levels_to_build`]).
fn built_levels<'a>(
    surfels: &Surfels,
    asked: impl Iterator<Item = (&'a SurfelCentre, f64)>,
    count: SurfelCount,
) -> SurfelCount {
    // A pyramid stopped before its finest level has none (the caller's check reports the stop).
    if surfels.n_levels() == 0 {
        return count;
    }
    let mut counts = vec![0; surfels.n_levels()];
    for (centre, radius) in asked {
        let texels = (centre.texel_length, centre.texel_side);
        counts[SurfelBall::asked_level(surfels.n_levels(), texels, radius, count.per_ball)] += 1;
    }
    let coarsest = levels_to_build(&counts);
    surfels.level(coarsest);
    SurfelCount { coarsest, ..count }
}

/// Position of texel-space point `uv` along a Z (Morton) curve over a `resolution`² grid.
fn z_order(uv: glam::DVec2, resolution: usize) -> u64 {
    let cell = |x: f64| (x * resolution as f64).clamp(0.0, resolution as f64 - 1.0) as usize;
    morton(cell(uv.x), cell(uv.y))
}
