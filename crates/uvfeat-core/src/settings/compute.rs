//! Everything a feature computation is asked to do, with the DESIGN.md §1.10 defaults in one place.

use crate::atlas::MAX_RESOLUTION;
use crate::error::{Result, UvfeatError};
use crate::features::{
    CurvatureMethod, EstimatorSettings, Feature, GaussianMethod, StatsSettings, SurfelSumSettings, VolumeWeighting,
};
use crate::lookup::Lookup;
use crate::raster::Surface;
use crate::relocation::Relocation;
use crate::sampling::{Criterion, Geodesic, Overlaps, Quadrature, SamplerSettings, SamplingPath, SurfelCount};

/// A feature computation request.
#[derive(Debug, Clone, PartialEq)]
pub struct ComputeSettings {
    /// Features to return.
    pub features: Vec<Feature>,
    /// Neighbourhood radius `r` in object units.
    pub radius: f64,
    /// Samples per neighbourhood `N` (256): the pattern's points per pixel, or with the surfels
    /// about as many surfels per ball (the pyramid level summed), whose quadrature error is a few
    /// tenths of a percent of H's range on the shared scans at 256 (docs/BENCHMARKS.md gives the
    /// trade: a quarter as many take 0.4-0.7x the time at r = 4-8 % and add up to 0.45 % to H's
    /// error, 0.8 % to K's).
    pub samples: usize,
    /// Computation texture size `W_c` (512).
    pub resolution: usize,
    /// Ellipse coverage margin `m` (1.25).
    pub margin: f64,
    /// Sample again with a larger margin where the ellipse did not cover the ball (on).
    pub grow_margin: bool,
    /// Seams a sample may cross (32, DESIGN.md §1.10; originally 3, paper 1: fragmented atlases
    /// need more, and the exact walk makes a crossing cheap).
    pub max_jumps: u32,
    /// How samples that leave their chart are relocated (exact walk).
    pub relocation: Relocation,
    /// Neighbourhood criterion (Euclidean).
    pub criterion: Criterion,
    /// Surface lookup of centres and samples (exact triangle; bilinear = paper).
    pub lookup: Lookup,
    /// Geodesic distance estimate of the geodesic-area K and criterion (arc; chord sum = paper).
    pub geodesic: Geodesic,
    /// Shared lattice per tile (default), per-texel fast path, or the exact path everywhere (the
    /// reference of both).
    pub sampling: SamplingPath,
    /// Surface reached along two routes through seams: kept (default) or counted once.
    pub overlaps: Overlaps,
    /// The pattern over the developed parametric disk (default) or the atlas's surfels.
    pub quadrature: Quadrature,
    /// The surface the surfels lie on: smooth (default) or the mesh's facets.
    pub surface: Surface,
    /// Seed of the pattern and the per-pixel rotations (0).
    pub seed: u64,
    /// Two-stage adaptive sampling (off).
    pub adaptive: bool,
    /// Stage 2 runs where the relative standard error exceeds `tau` (0.01).
    pub tau: f64,
    /// Gaussian-curvature method (moments).
    pub gaussian_method: GaussianMethod,
    /// Source of the curvature features: integral invariants (default) or the quadric fit.
    pub method: CurvatureMethod,
    /// Weighting of the volume integrands (distance).
    pub volume_weighting: VolumeWeighting,
    /// Inner exclusion of bending energy and curvature moments, as a fraction of `r` (0.1).
    pub rho_min_fraction: f64,
    /// Shape index is NaN where curvedness `< flat_tol / r` (1e-3).
    pub flat_tol: f64,
    /// Also return per-pixel standard errors (batch means over 8 interleaved batches).
    pub standard_errors: bool,
}

impl ComputeSettings {
    /// The defaults of DESIGN.md §1.10 for `features` at `radius`.
    pub fn new(features: Vec<Feature>, radius: f64) -> Self {
        Self {
            features,
            radius,
            samples: 256,
            resolution: 512,
            margin: 1.25,
            grow_margin: true,
            max_jumps: 32,
            relocation: Relocation::Walk,
            criterion: Criterion::Euclidean,
            lookup: Lookup::Triangle,
            geodesic: Geodesic::Arc,
            sampling: SamplingPath::Shared,
            overlaps: Overlaps::Keep,
            quadrature: Quadrature::Pattern,
            surface: Surface::Smooth,
            seed: 0,
            adaptive: false,
            tau: 0.01,
            gaussian_method: GaussianMethod::Moments,
            method: CurvatureMethod::Integral,
            volume_weighting: VolumeWeighting::Distance,
            rho_min_fraction: 0.1,
            flat_tol: 1e-3,
            standard_errors: false,
        }
    }

    /// Checks every parameter.
    ///
    /// # Errors
    /// [`UvfeatError::InvalidParameter`] naming the parameter and the valid range.
    pub fn validate(&self) -> Result<()> {
        if self.features.is_empty() {
            return Err(UvfeatError::InvalidParameter {
                name: "features",
                reason: "ask for at least one feature".into(),
            });
        }
        self.validate_sampling()
    }

    /// Checks the radius and the options: what sampling neighbourhoods needs (no estimator runs on
    /// a user-defined operator's samples).
    ///
    /// # Errors
    /// As [`ComputeSettings::validate`].
    pub fn validate_sampling(&self) -> Result<()> {
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return Err(UvfeatError::InvalidParameter {
                name: "radius",
                reason: format!("must be a positive, finite length, got {}", self.radius),
            });
        }
        self.validate_options()
    }

    /// Checks the options alone, before there is a mesh to resolve a radius on (a batch checks
    /// its settings once, not once per mesh); the checks that read the features (the geodesic
    /// distances of the geodesic-area K) run again with them in [`ComputeSettings::validate`].
    ///
    /// # Errors
    /// As [`ComputeSettings::validate`].
    pub fn validate_options(&self) -> Result<()> {
        let invalid = |name: &'static str, reason: String| Err(UvfeatError::InvalidParameter { name, reason });
        if self.samples < 4 || self.samples > 65_536 {
            return invalid("samples", format!("must be between 4 and 65536, got {}", self.samples));
        }
        if self.resolution == 0 || self.resolution > MAX_RESOLUTION {
            return invalid("compute_resolution", format!("must be in 1..={MAX_RESOLUTION}, got {}", self.resolution));
        }
        if !(self.margin.is_finite() && self.margin >= 1.0 && self.margin <= 4.0) {
            return invalid("margin", format!("must be in [1, 4], got {}", self.margin));
        }
        if !(self.tau >= 0.0) {
            return invalid("tau", format!("must be >= 0 (inf = stage 1 only), got {}", self.tau));
        }
        if !(0.0..1.0).contains(&self.rho_min_fraction) {
            return invalid("rho_min", format!("must be a fraction of r in [0, 1), got {}", self.rho_min_fraction));
        }
        if self.quadrature == Quadrature::Surfels && (self.adaptive || self.standard_errors) {
            return invalid(
                "quadrature",
                "\"surfels\" sums every surfel of the ball once (no random samples): adaptive sampling and \
                 standard errors do not apply"
                    .into(),
            );
        }
        if self.quadrature == Quadrature::Surfels && self.sampler().with_geodesic {
            // The surfels' ramp across the ball's edge would enter the geodesic disk's area.
            return invalid(
                "quadrature",
                "\"surfels\" serves the Euclidean ball: the geodesic criterion and gaussian_method=\
                 \"geodesic_area\" (paper mode's) need quadrature=\"pattern\""
                    .into(),
            );
        }
        if self.surface == Surface::Facets && self.quadrature != Quadrature::Surfels {
            return invalid("surface", "\"facets\" is a choice of quadrature=\"surfels\"".into());
        }
        if !(self.flat_tol >= 0.0) {
            return invalid("flat_tol", format!("must be >= 0, got {}", self.flat_tol));
        }
        Ok(())
    }

    /// Sampler part of the settings.
    pub fn sampler(&self) -> SamplerSettings {
        SamplerSettings {
            radius: self.radius,
            margin: self.margin,
            max_jumps: self.max_jumps,
            relocation: self.relocation,
            criterion: self.criterion,
            lookup: self.lookup,
            geodesic: self.geodesic,
            path: self.sampling,
            with_normals: self.features.contains(&Feature::BendingEnergy),
            // The geodesic-disk K is the only estimator that reads the samples' geodesic
            // distances; its chord sum costs 16 lookups per sample (paper mode, H alone: 8x).
            with_geodesic: self.criterion == Criterion::Geodesic
                || (self.gaussian_method == GaussianMethod::GeodesicArea
                    && self.features.iter().any(|f| f.uses_gaussian_curvature())),
            overlaps: self.overlaps,
            surface: self.surface,
            surfels_per_ball: self.samples as f64,
        }
    }

    /// Statistics part of the settings.
    pub fn stats(&self) -> StatsSettings {
        StatsSettings {
            radius: self.radius,
            rho_min: self.rho_min_fraction * self.radius,
            volume_weighting: self.volume_weighting,
        }
    }

    /// What the surfels' moment sums read (DESIGN.md §1.4.9).
    pub fn surfel_sums(&self) -> SurfelSumSettings {
        SurfelSumSettings {
            stats: self.stats(),
            surface: self.surface,
            with_normals: self.sampler().with_normals,
            count: SurfelCount::per_ball(self.samples as f64),
        }
    }

    /// Estimator part of the settings.
    pub fn estimators(&self) -> EstimatorSettings {
        EstimatorSettings {
            radius: self.radius,
            gaussian_method: self.gaussian_method,
            flat_tol: self.flat_tol,
            volume_weighting: self.volume_weighting,
            method: self.method,
        }
    }
}
