//! Per-vertex values (DESIGN.md §1.9): chart-masked bilinear lookup of the feature maps at every corner
//! UV of a vertex, averaged over its corners; direct evaluation where no texel is usable.

use super::corners::{Corner, VertexCorners};
use super::feature_map::FeatureMaps;
use super::vertex_values::{sums_apply, vertex_values};
use crate::atlas::Atlas;
use crate::cancel;
use crate::error::Result;
use crate::evaluation::{evaluate_point, prepare, Patterns};
use crate::features::CurvatureMethod;
use crate::sampling::Placement;
use crate::settings::{ComputeSettings, VertexQuery};
use glam::DVec2;
use rayon::prelude::*;

/// Bilinear lookup of every map at `uv` into `out` (one value per map, NaN where the map has no
/// finite value there), using only texels of `chart` with accepted samples; `false` (and `out`
/// untouched) when no such texel is among the four nearest.
fn lookup(maps: &FeatureMaps, uv: DVec2, chart: i32, out: &mut [f64]) -> bool {
    let w = maps.resolution as i64;
    let (x, y) = (uv.x * w as f64 - 0.5, uv.y * w as f64 - 0.5);
    let (i0, j0) = (x.floor() as i64, y.floor() as i64);
    let (fx, fy) = (x - i0 as f64, y - j0 as f64);
    let mut texels = [(0usize, 0.0f64); 4];
    let mut n = 0;
    for (di, dj, weight) in
        [(0, 0, (1.0 - fx) * (1.0 - fy)), (1, 0, fx * (1.0 - fy)), (0, 1, (1.0 - fx) * fy), (1, 1, fx * fy)]
    {
        let (i, j) = (i0 + di, j0 + dj);
        if i < 0 || j < 0 || i >= w || j >= w {
            continue;
        }
        let t = (j * w + i) as usize;
        if maps.chart[t] == chart && maps.n_valid[t] > 0 {
            texels[n] = (t, weight);
            n += 1;
        }
    }
    if n == 0 {
        return false;
    }
    for (slot, map) in out.iter_mut().zip(&maps.values) {
        let (mut sum, mut weights) = (0.0, 0.0);
        for &(t, weight) in &texels[..n] {
            let v = f64::from(map[t]);
            if v.is_finite() {
                sum += weight * v;
                weights += weight;
            }
        }
        *slot = if weights > 0.0 { sum / weights } else { f64::NAN };
    }
    true
}

/// The running mean of the finite values of each feature over a vertex's corners.
#[derive(Default)]
struct CornerMeans {
    sums: Vec<f64>,
    counts: Vec<u32>,
    /// Scratch: the current corner's value of each feature.
    corner_values: Vec<f64>,
}

impl CornerMeans {
    /// Empties the means for a vertex with `n_features` features.
    fn reset(&mut self, n_features: usize) {
        for column in [&mut self.sums, &mut self.corner_values] {
            column.clear();
            column.resize(n_features, 0.0);
        }
        self.counts.clear();
        self.counts.resize(n_features, 0);
    }

    /// Adds the values in `self.corner_values`.
    fn add_corner(&mut self) {
        for ((sum, count), &v) in self.sums.iter_mut().zip(&mut self.counts).zip(&self.corner_values) {
            if v.is_finite() {
                *sum += v;
                *count += 1;
            }
        }
    }

    /// Writes the means to `out`, leaving it as it is where no corner had a finite value.
    fn write(&self, out: &mut [f32]) {
        for ((slot, &sum), &count) in out.iter_mut().zip(&self.sums).zip(&self.counts) {
            if count > 0 {
                *slot = (sum / f64::from(count)) as f32;
            }
        }
    }
}

/// Per-vertex values of every map, one `Vec` per feature with one value per *input* vertex
/// (vertices the file split at seams get the value of their welded vertex). The direct query of
/// the surfels' integral estimators sums their moments at the vertices ([`vertex_values`]).
///
/// # Errors
/// [`UvfeatError::Cancelled`](crate::error::UvfeatError::Cancelled) when [`cancel`] stopped the
/// call; [`vertex_values`]' errors.
pub fn per_vertex(
    atlas: &Atlas,
    maps: &FeatureMaps,
    settings: &ComputeSettings,
    query: VertexQuery,
) -> Result<Vec<Vec<f32>>> {
    if query == VertexQuery::Direct && sums_apply(atlas, settings) {
        return Ok(vertex_values(atlas, settings)?.values);
    }
    let corners = VertexCorners::new(atlas);
    let patterns = Patterns::new(settings);
    prepare(atlas, settings);
    let n_features = maps.features.len();
    let mut geometric = vec![f32::NAN; corners.n_vertices() * n_features];
    // Scratch per rayon job, not per vertex: the lists of corner values took several allocations
    // per vertex, three per corner and one per feature (the 200K-face ellipsoid's two features:
    // 16-22 -> 8-10 ms).
    let per_thread = || (Vec::new(), CornerMeans::default());
    geometric.par_chunks_mut(n_features.max(1)).enumerate().for_each_init(
        per_thread,
        |(scratch, means), (vertex, out)| {
            if cancel::requested() {
                return;
            }
            means.reset(n_features);
            let mut found = false;
            if query == VertexQuery::Texture {
                for Corner { uv, chart, .. } in corners.of(vertex) {
                    if lookup(maps, uv, chart, &mut means.corner_values) {
                        means.add_corner();
                        found = true;
                    }
                }
            }
            if !found {
                let placement = Placement::of_vertex(vertex as u32, settings.seed);
                for Corner { uv, .. } in corners.of(vertex) {
                    let result = evaluate_point(atlas, uv, placement, settings, &patterns, scratch);
                    for (slot, f) in means.corner_values.iter_mut().zip(&maps.features) {
                        *slot = f64::from(result.values[f.index()]);
                    }
                    means.add_corner();
                }
            }
            means.write(out);
        },
    );
    cancel::check()?;
    let ids = &atlas.topology.vertex_ids;
    Ok((0..n_features).map(|f| ids.iter().map(|&g| geometric[g as usize * n_features + f]).collect()).collect())
}

/// Every atlas corner's UV and geometric vertex and, per feature, its chart-masked bilinear
/// lookup (the value [`per_vertex`] averages over a vertex's corners; NaN where no texel of the
/// corner's chart with samples is among the four nearest): what a texture read at that UV should
/// give, which a bake's gutters are fitted to.
pub fn per_corner(atlas: &Atlas, maps: &FeatureMaps) -> (Vec<DVec2>, Vec<u32>, Vec<Vec<f32>>) {
    let corners = VertexCorners::new(atlas);
    let n_features = maps.features.len();
    let mut values = vec![f64::NAN; corners.n_corners() * n_features];
    // Each corner is found once: its UV kept from the same parallel pass as its lookup.
    let uvs: Vec<DVec2> = values
        .par_chunks_mut(n_features.max(1))
        .enumerate()
        .map(|(c, out)| {
            let corner = corners.corner(c);
            lookup(maps, corner.uv, corner.chart, out);
            corner.uv
        })
        .collect();
    let per_feature =
        (0..n_features).map(|f| values.iter().skip(f).step_by(n_features).map(|&v| v as f32).collect()).collect();
    let vertex = (0..corners.n_vertices()).flat_map(|g| std::iter::repeat_n(g as u32, corners.range(g).len()));
    (uvs, vertex.collect(), per_feature)
}

/// Principal directions `[d1, d2]` of the quadric fit at every *input* vertex, evaluated directly
/// at one corner UV of the vertex (a line field has no sign, so texels cannot be averaged
/// bilinearly like scalar maps); NaN where the fit failed.
///
/// # Errors
/// [`UvfeatError::Cancelled`](crate::error::UvfeatError::Cancelled) when [`cancel`] stopped the call.
pub fn per_vertex_directions(atlas: &Atlas, settings: &ComputeSettings) -> Result<Vec<[[f32; 3]; 2]>> {
    let settings = ComputeSettings { method: CurvatureMethod::Fit, standard_errors: false, ..settings.clone() };
    let patterns = Patterns::new(&settings);
    prepare(atlas, &settings);
    let corners = VertexCorners::new(atlas);
    let geometric: Vec<[[f32; 3]; 2]> = (0..corners.n_vertices())
        .into_par_iter()
        .map_init(Vec::new, |scratch, vertex| {
            if cancel::requested() {
                return [[f32::NAN; 3]; 2];
            }
            // The first corner where the fit succeeds: a corner UV on a chart's edge may fall on
            // a gutter texel of the raster, which has no centre.
            let placement = Placement::of_vertex(vertex as u32, settings.seed);
            corners
                .of(vertex)
                .map(|c| evaluate_point(atlas, c.uv, placement, &settings, &patterns, scratch).directions)
                .find(|d| d[0][0].is_finite())
                .unwrap_or([[f32::NAN; 3]; 2])
        })
        .collect();
    cancel::check()?;
    Ok(atlas.topology.vertex_ids.iter().map(|&g| geometric[g as usize]).collect())
}
