//! Feature maps over the computation texture (DESIGN.md §1.9): every texel centre of a `W_c x W_c`
//! grid is a point `s` where all requested features are evaluated, in parallel over tiles.

use crate::atlas::Atlas;
use crate::error::Result;
use crate::evaluation::{evaluate_point, prepare, Patterns, PixelResult};
use crate::features::{CurvatureMethod, Feature};
use crate::sampling::Placement;
use crate::settings::ComputeSettings;
use crate::tile_evaluation::{evaluate_tile, shared_lattice_applies, texel_uv};
use rayon::prelude::*;

/// Side of the square tiles of texels evaluated together, so that their neighbourhoods' reads of
/// the buffers stay in cache (16 measured faster than 8 and as fast as 32).
const TILE: usize = 16;

/// The texels `j * w + i` of each [`TILE`]² tile of a `w`² texture, tile after tile: the parallel
/// evaluation works tile by tile.
fn tiles(w: usize) -> Vec<Vec<usize>> {
    let tiles = w.div_ceil(TILE);
    (0..tiles * tiles)
        .map(|tile| {
            let (ti, tj) = (tile % tiles * TILE, tile / tiles * TILE);
            (tj..(tj + TILE).min(w)).flat_map(|j| (ti..(ti + TILE).min(w)).map(move |i| j * w + i)).collect()
        })
        .collect()
}

/// Neighbourhood area ratio above which a neighbourhood holds more than one sheet: one smooth sheet
/// gives about 1 at any curvature, two sheets about 2, overlapping seam routes up to about 1.1.
pub const SEVERAL_SHEETS: f32 = 1.5;

/// Totals over a map, for reports.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MapSummary {
    /// Texels on a chart (where features were evaluated).
    pub texels: usize,
    /// Fraction of those that ran stage 2 of adaptive sampling.
    pub second_stage_fraction: f64,
    /// Fraction whose principal curvatures needed `H^2 - K` clamped.
    pub clamped_fraction: f64,
    /// Missing samples over all pattern samples drawn.
    pub missing_fraction: f64,
    /// Texels whose neighbourhood was cut by a mesh border (some samples dropped there).
    pub truncated_texels: usize,
    /// Texels whose neighbourhood holds more than one sheet of the surface (area ratio above
    /// [`SEVERAL_SHEETS`]): the ball is wider than a thin part there.
    pub several_sheet_texels: usize,
    /// Mean accepted samples per texel.
    pub mean_valid: f64,
}

/// The requested features on a `resolution`² texture, texel `(i, j)` at index `j * W_c + i`
/// (v up), NaN outside charts, plus per-texel diagnostics.
#[derive(Debug, Clone)]
pub struct FeatureMaps {
    /// `W_c`.
    pub resolution: usize,
    /// Features, in the order of `values`.
    pub features: Vec<Feature>,
    /// One map per feature.
    pub values: Vec<Vec<f32>>,
    /// One standard-error map per feature, when requested.
    pub standard_errors: Option<Vec<Vec<f32>>>,
    /// Chart of each texel centre (-1 off the charts).
    pub chart: Vec<i32>,
    /// Accepted samples per texel.
    pub n_valid: Vec<u32>,
    /// Samples whose relocation failed.
    pub n_missing: Vec<u32>,
    /// Samples dropped at a mesh border.
    pub n_border: Vec<u32>,
    /// Texels that ran stage 2 (adaptive sampling).
    pub second_stage: Vec<bool>,
    /// Principal directions `[d1, d2]` of every texel (unit 3D vectors, a line field: the sign is
    /// arbitrary), with the curvature method `Fit`; NaN off the charts.
    pub directions: Option<Vec<[[f32; 3]; 2]>>,
    /// Relative RMS residual of the fit per texel, with the curvature method `Fit`.
    pub fit_residual: Option<Vec<f32>>,
    /// Neighbourhood area over `pi r^2` per texel (see [`PixelResult::area_ratio`]).
    pub area_ratio: Vec<f32>,
    /// Totals.
    pub summary: MapSummary,
}

impl FeatureMaps {
    /// Evaluates `settings.features` at every texel of the computation texture.
    ///
    /// # Errors
    /// [`crate::UvfeatError::InvalidParameter`] from [`ComputeSettings::validate`].
    pub fn compute(atlas: &Atlas, settings: &ComputeSettings) -> Result<Self> {
        settings.validate()?;
        let w = settings.resolution;
        let patterns = Patterns::new(settings);
        prepare(atlas, settings);
        let tiles = tiles(w);
        let shared = shared_lattice_applies(atlas, settings);
        let results: Vec<PixelResult> = tiles
            .par_iter()
            .map_init(Vec::new, |scratch, texels| {
                if shared {
                    return evaluate_tile(atlas, settings, &patterns, texels, scratch);
                }
                let placement = |t: usize| Placement::of_pixel((t % w) as u32, (t / w) as u32, settings.seed);
                texels
                    .iter()
                    .map(|&t| evaluate_point(atlas, texel_uv(t, w), placement(t), settings, &patterns, scratch))
                    .collect()
            })
            .flatten_iter()
            .collect();
        // The results by texel, as references: moving the 120-byte results into texel order took
        // a tenth of a 200K-face torus's features.
        let mut slot = vec![0; w * w];
        for (k, &t) in tiles.iter().flatten().enumerate() {
            slot[t] = k;
        }
        let pixels: Vec<&PixelResult> = slot.par_iter().map(|&k| &results[k]).collect();
        let chart = (0..w * w).into_par_iter().map(|t| atlas.chart_at(texel_uv(t, w))).collect();
        Ok(Self::assemble(&pixels, chart, settings))
    }

    fn assemble(pixels: &[&PixelResult], chart: Vec<i32>, settings: &ComputeSettings) -> Self {
        let pick = |f: &(dyn Fn(&PixelResult) -> f32 + Sync)| pixels.par_iter().map(|p| f(p)).collect::<Vec<f32>>();
        let values = settings.features.iter().map(|feat| pick(&|p| p.values[feat.index()])).collect();
        let standard_errors = settings
            .standard_errors
            .then(|| settings.features.iter().map(|feat| pick(&|p| p.errors[feat.index()])).collect());
        let fitted = settings.method == CurvatureMethod::Fit;
        let directions = fitted.then(|| pixels.iter().map(|p| p.directions).collect());
        let fit_residual = fitted.then(|| pick(&|p| p.residual));
        let evaluated: Vec<&PixelResult> = pixels.iter().copied().filter(|p| p.counts.valid > 0).collect();
        let n = evaluated.len().max(1) as f64;
        let drawn: u64 = evaluated.iter().map(|p| u64::from(p.counts.valid + p.counts.missing + p.counts.border)).sum();
        let summary = MapSummary {
            texels: evaluated.len(),
            second_stage_fraction: evaluated.iter().filter(|p| p.second_stage).count() as f64 / n,
            clamped_fraction: evaluated.iter().filter(|p| p.clamped).count() as f64 / n,
            missing_fraction: evaluated.iter().map(|p| f64::from(p.counts.missing)).sum::<f64>() / drawn.max(1) as f64,
            truncated_texels: evaluated.iter().filter(|p| p.counts.border > 0).count(),
            several_sheet_texels: evaluated.iter().filter(|p| p.area_ratio > SEVERAL_SHEETS).count(),
            mean_valid: evaluated.iter().map(|p| f64::from(p.counts.valid)).sum::<f64>() / n,
        };
        Self {
            resolution: settings.resolution,
            features: settings.features.clone(),
            values,
            standard_errors,
            chart,
            n_valid: pixels.par_iter().map(|p| p.counts.valid).collect(),
            n_missing: pixels.par_iter().map(|p| p.counts.missing).collect(),
            n_border: pixels.par_iter().map(|p| p.counts.border).collect(),
            second_stage: pixels.par_iter().map(|p| p.second_stage).collect(),
            directions,
            fit_residual,
            area_ratio: pick(&|p| p.area_ratio),
            summary,
        }
    }
}
