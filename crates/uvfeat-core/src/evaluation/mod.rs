//! Stage 5 of the pipeline: the features at one parametric point (sampling, full or two-stage
//! adaptive, DESIGN.md §1.8; one pass of statistics; every estimator; optional batch-means standard
//! errors), and on a tile of texels at once with the shared lattice ([`evaluate_tile`]).

mod integration;
mod tile;

pub use integration::{integration, Integration};
pub use tile::{evaluate_tile, texel_uv};

use crate::atlas::Atlas;
use crate::features::{
    estimate, fit_relative_error, quadric_fit, relative_standard_error, surfel_sums, CurvatureMethod, Feature,
    NeighbourhoodStats, QuadricFit, SurfelCentre,
};
use crate::lookup::Lookup;
use crate::sampling::{
    centre_at, disk_pattern, gather, gather_covering, gather_surfels, surfel_centre, Centre, Placement, Sample,
    SampleCounts, TURNS,
};
use crate::settings::ComputeSettings;
use glam::DVec2;

/// Interleaved batches behind the standard errors.
const BATCHES: usize = 8;

/// The sample patterns of a run (shared by every pixel).
#[derive(Debug, Clone)]
pub struct Patterns {
    /// Full `N`-cell pattern, or stage 1 (`N/2` cells) when adaptive.
    pub first: Vec<DVec2>,
    /// Stage 2 (`N - N/2` cells, independent jitter); empty unless adaptive.
    pub second: Vec<DVec2>,
}

impl Patterns {
    /// Patterns for `settings` (DESIGN.md §1.4.2, §1.8, decision A19).
    pub fn new(settings: &ComputeSettings) -> Self {
        let n = settings.samples;
        if settings.adaptive {
            Self { first: disk_pattern(n / 2, settings.seed, 1), second: disk_pattern(n - n / 2, settings.seed, 2) }
        } else {
            Self { first: disk_pattern(n, settings.seed, 0), second: Vec::new() }
        }
    }
}

/// Builds the data `settings` reads (the coverage, patches, seam maps, bilinear buffers, surfels)
/// before the parallel work starts, rather than in the first worker that needs it while the others
/// wait on it idle.
pub fn prepare(atlas: &Atlas, settings: &ComputeSettings) {
    atlas.coverage();
    atlas.patches();
    if !integration(atlas, settings).uses_surfels() {
        atlas.seam_maps();
    }
    if settings.lookup == Lookup::Bilinear {
        atlas.buffers();
    }
    if integration(atlas, settings).uses_surfels() {
        // Every level: a texel's ball may ask for any.
        let surfels = atlas.surfels(settings.surface);
        if let Some(coarsest) = surfels.n_levels().checked_sub(1) {
            surfels.level(coarsest);
        }
    }
}

/// Features and diagnostics of one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelResult {
    /// Every feature, in `Feature::ALL` order (NaN where there were no samples).
    pub values: [f32; 9],
    /// Standard errors in the same order (NaN unless requested).
    pub errors: [f32; 9],
    /// Sample counts over both stages.
    pub counts: SampleCounts,
    /// Stage 2 of adaptive sampling ran.
    pub second_stage: bool,
    /// `H^2 - K < 0` was clamped for the principal curvatures.
    pub clamped: bool,
    /// Principal directions `d1, d2` of the fit (NaN unless the curvature method is the fit).
    pub directions: [[f32; 3]; 2],
    /// Relative RMS residual of the fit (NaN unless the curvature method is the fit).
    pub residual: f32,
    /// Surface area of the neighbourhood over `pi r^2`: about 1 for one smooth sheet at any
    /// curvature (a sphere's cap inside a ball holds exactly `pi r^2`), about 2 where the ball
    /// holds both sides of a part thinner than `r`.
    pub area_ratio: f32,
}

impl PixelResult {
    /// The estimates of one neighbourhood's statistics (and fit), with its counts and area ratio.
    pub fn estimated(
        stats: &NeighbourhoodStats,
        fit: Option<&QuadricFit>,
        counts: SampleCounts,
        settings: &ComputeSettings,
    ) -> Self {
        let estimates = estimate(stats, fit, &settings.estimators());
        PixelResult {
            values: estimates.values.map(|v| v as f32),
            errors: [f32::NAN; 9],
            counts,
            second_stage: false,
            clamped: estimates.clamped,
            directions: EMPTY_DIRECTIONS,
            residual: f32::NAN,
            area_ratio: (stats.geodesic_disk.w / (std::f64::consts::PI * settings.radius * settings.radius)) as f32,
        }
    }

    /// A point off the charts.
    pub const EMPTY: PixelResult = PixelResult {
        values: [f32::NAN; 9],
        errors: [f32::NAN; 9],
        counts: SampleCounts { valid: 0, missing: 0, border: 0 },
        second_stage: false,
        clamped: false,
        directions: EMPTY_DIRECTIONS,
        residual: f32::NAN,
        area_ratio: f32::NAN,
    };
}

/// Evaluates every feature at parametric point `uv` placed by `placement`; `scratch` holds the
/// samples (reused across calls, so nothing is allocated per pixel).
pub fn evaluate_point(
    atlas: &Atlas,
    uv: DVec2,
    placement: Placement,
    settings: &ComputeSettings,
    patterns: &Patterns,
    scratch: &mut Vec<Sample>,
) -> PixelResult {
    let Some(centre) = centre_at(atlas, uv, settings.lookup) else {
        return PixelResult::EMPTY;
    };
    let sampler = settings.sampler();
    let integration = integration(atlas, settings);
    if integration.uses_surfels() {
        let Some(centre) = surfel_centre(atlas, &centre, settings.surface) else { return PixelResult::EMPTY };
        if integration == Integration::SurfelSums {
            // The integral estimators read sums, which the surfels' moments give (exactly for H).
            let at = SurfelCentre::new(
                centre.position,
                centre.normal,
                centre.uv,
                centre.chart,
                &centre.distortion,
                atlas.resolution(),
            );
            let (stats, counts) = surfel_sums(atlas, &at, &settings.surfel_sums());
            return if counts.valid == 0 {
                PixelResult::EMPTY
            } else {
                PixelResult::estimated(&stats, None, counts, settings)
            };
        }
        scratch.clear();
        let counts = gather_surfels(atlas, &centre, &sampler, scratch);
        return surfel_result(settings, &centre, counts, scratch);
    }
    let stats_settings = settings.stats();
    let estimators = settings.estimators();
    let first = patterns.first.len();
    let (mut counts, reach) =
        gather_covering(atlas, &centre, &patterns.first, placement, &sampler, settings.grow_margin, scratch);
    let mut stats = NeighbourhoodStats::default();
    stats.accumulate(scratch, centre.normal, &stats_settings);
    let mut second_stage = false;
    // With the fit, adaptive sampling decides on the stage-1 fit's own errors; that fit is the final
    // one unless stage 2 runs.
    let mut stage_one_fit = None;
    if settings.adaptive {
        let stage_one = (settings.method == CurvatureMethod::Fit)
            .then(|| quadric_fit(centre.position, centre.normal, scratch, settings.radius, true));
        let relative_error = |f: Feature| match &stage_one {
            Some(fit) => fit_relative_error(f, fit.as_ref(), &stats, &estimators),
            None => relative_standard_error(f, &stats, &estimators),
        };
        let needs_more = settings.features.iter().any(|&f| !(relative_error(f) <= settings.tau));
        stage_one_fit = stage_one;
        if needs_more && !patterns.second.is_empty() {
            second_stage = true;
            let second = patterns.second.len();
            let total = (first + second) as f64;
            let start = scratch.len();
            counts.add(gather(atlas, &centre, &patterns.second, placement, &reach, &sampler, scratch));
            // Each stage's samples stood for A_uv / N_stage; pooled they stand for A_uv / N.
            stats.scale_areas(first as f64 / total);
            let mut more = NeighbourhoodStats::default();
            more.accumulate(&scratch[start..], centre.normal, &stats_settings);
            more.scale_areas(second as f64 / total);
            stats.merge(&more);
        }
    }
    // Pooled stages weight their samples by A_uv / N_stage, equal up to one sample for N/2 and
    // N - N/2: the fit, invariant to a common scale of the weights, pools them as they are.
    let fit = match stage_one_fit {
        Some(fit) if !second_stage => fit,
        _ => fit_if_asked(settings, &centre, scratch),
    };
    let mut result = fitted_result(&stats, fit, counts, settings);
    result.second_stage = second_stage;
    if settings.standard_errors {
        result.errors = batch_standard_errors(scratch, &centre, settings, second_stage, first);
        if let Some(fit) = fit {
            result.errors = with_fit_errors(result.errors, &fit);
        }
    }
    result
}

/// The features of a neighbourhood summed over surfels (`samples`, DESIGN.md §1.4.8).
fn surfel_result(settings: &ComputeSettings, centre: &Centre, counts: SampleCounts, samples: &[Sample]) -> PixelResult {
    let mut stats = NeighbourhoodStats::default();
    stats.accumulate(samples, centre.normal, &settings.stats());
    fitted_result(&stats, fit_if_asked(settings, centre, samples), counts, settings)
}

/// The estimates with the fit's directions and residual (when there is a fit).
fn fitted_result(
    stats: &NeighbourhoodStats,
    fit: Option<QuadricFit>,
    counts: SampleCounts,
    settings: &ComputeSettings,
) -> PixelResult {
    let mut result = PixelResult::estimated(stats, fit.as_ref(), counts, settings);
    if let Some(fit) = fit {
        result.directions = [fit.d1, fit.d2].map(|d| d.as_vec3().to_array());
        result.residual = fit.residual as f32;
    }
    result
}

/// The standard errors of the fitted curvatures (see [`QuadricFit::standard_error`]) in place of
/// the batches' NaN: a fit to an eighth of the samples is far noisier than the fit to all of them
/// (torus at r = 0.3, 128 samples: batch means 0.10 / r for H against a measured spread over seeds
/// of 0.0009 / r), so the batches do not fit at all.
fn with_fit_errors(mut errors: [f32; 9], fit: &QuadricFit) -> [f32; 9] {
    for feature in Feature::ALL.into_iter().filter(|f| f.from_fit()) {
        errors[feature.index()] = fit.standard_error(feature) as f32;
    }
    errors
}

const EMPTY_DIRECTIONS: [[f32; 3]; 2] = [[f32::NAN; 3]; 2];

/// The quadric fit of `samples` when the settings ask for it (with its standard errors when they
/// are asked for too).
fn fit_if_asked(settings: &ComputeSettings, centre: &Centre, samples: &[Sample]) -> Option<QuadricFit> {
    if settings.method == CurvatureMethod::Fit {
        quadric_fit(centre.position, centre.normal, samples, settings.radius, settings.standard_errors)
    } else {
        None
    }
}

/// Standard errors from the spread of the estimates of `BATCHES` interleaved batches. A batch
/// takes whole groups of turned copies of a base point (see `disk_pattern`), so that each batch
/// keeps the pattern's cancellation of the anisotropy.
fn batch_standard_errors(
    samples: &[Sample],
    centre: &Centre,
    settings: &ComputeSettings,
    pooled: bool,
    first: usize,
) -> [f32; 9] {
    let stats_settings = settings.stats();
    let estimators = settings.estimators();
    let mut batches: [Vec<Sample>; BATCHES] = Default::default();
    for sample in samples {
        let group = sample.pattern_index as usize / TURNS;
        batches[group % BATCHES].push(*sample);
    }
    // Each batch holds about 1/BATCHES of the samples, so its absolute areas are scaled back up.
    let pooled_scale = if pooled { first as f64 / settings.samples as f64 } else { 1.0 };
    let values: Vec<[f64; 9]> = batches
        .iter()
        .map(|batch| {
            let mut stats = NeighbourhoodStats::default();
            stats.accumulate(batch, centre.normal, &stats_settings);
            stats.scale_areas(BATCHES as f64 * pooled_scale);
            // No fit per batch: the fitted curvatures' errors are the full fit's own.
            estimate(&stats, None, &estimators).values
        })
        .collect();
    std::array::from_fn(|f| {
        let finite: Vec<f64> = values.iter().map(|v| v[f]).filter(|x| x.is_finite()).collect();
        let n = finite.len() as f64;
        if n < 2.0 {
            return f32::NAN;
        }
        let mean = finite.iter().sum::<f64>() / n;
        let var = finite.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (var / n).sqrt() as f32
    })
}
