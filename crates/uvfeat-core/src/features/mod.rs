//! Stage 5 of the pipeline (DESIGN.md §2): the feature estimators, each a small function of the
//! weighted sums of one neighbourhood.

mod bending_energy;
mod curvedness;
mod gaussian_curvature;
mod lattice_statistics;
mod lattice_sums;
mod mean_curvature;
mod open_volume;
mod principal_curvatures;
mod quadric_fit;
mod shape_index;
mod statistics;
mod surfel_sums;
mod volume_invariant;

pub use bending_energy::bending_energy;
pub use curvedness::curvedness;
pub use gaussian_curvature::{
    gaussian_curvature_geodesic_area, gaussian_curvature_geodesic_area_error, gaussian_curvature_moments,
    GaussianMethod,
};
pub use lattice_statistics::{lattice_statistics, LatticeNeighbourhood};
pub use lattice_sums::SumsKernel;
pub use mean_curvature::{mean_curvature, mean_curvature_error, radial_correction};
pub use open_volume::{ball_volume, open_volume, open_volume_error};
pub use principal_curvatures::principal_curvatures;
pub use quadric_fit::{quadric_fit, QuadricFit};
pub use shape_index::shape_index;
pub use statistics::{NeighbourhoodStats, StatsSettings, VolumeWeighting, WeightedSums};
pub use surfel_sums::{surfel_sums, SurfelCentre, SurfelSumSettings};
pub use volume_invariant::volume_invariant;

use crate::error::{Result, UvfeatError};

/// The features uvfeat estimates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Feature {
    /// Local bending energy, 1/length^2.
    BendingEnergy,
    /// Open sphere volume `V_o`, length^3.
    OpenVolume,
    /// Sphere-volume integral invariant `V_r`, length^3.
    VolumeInvariant,
    /// Mean curvature `H`, 1/length.
    MeanCurvature,
    /// Gaussian curvature `K`, 1/length^2.
    GaussianCurvature,
    /// Largest principal curvature `k1`, 1/length.
    K1,
    /// Smallest principal curvature `k2`, 1/length.
    K2,
    /// Shape index, dimensionless.
    ShapeIndex,
    /// Curvedness, 1/length.
    Curvedness,
}

impl Feature {
    /// Every feature, in output order.
    pub const ALL: [Feature; 9] = [
        Feature::BendingEnergy,
        Feature::OpenVolume,
        Feature::VolumeInvariant,
        Feature::MeanCurvature,
        Feature::GaussianCurvature,
        Feature::K1,
        Feature::K2,
        Feature::ShapeIndex,
        Feature::Curvedness,
    ];

    /// `true` for the curvature features, which the quadric fit estimates with `method = "fit"`
    /// (the volumes and the bending energy are always integral).
    pub fn from_fit(self) -> bool {
        !matches!(self, Feature::BendingEnergy | Feature::OpenVolume | Feature::VolumeInvariant)
    }

    /// Public name (Python, CLI, files).
    pub fn name(self) -> &'static str {
        match self {
            Feature::BendingEnergy => "bending_energy",
            Feature::OpenVolume => "open_volume",
            Feature::VolumeInvariant => "volume_invariant",
            Feature::MeanCurvature => "mean_curvature",
            Feature::GaussianCurvature => "gaussian_curvature",
            Feature::K1 => "k1",
            Feature::K2 => "k2",
            Feature::ShapeIndex => "shape_index",
            Feature::Curvedness => "curvedness",
        }
    }

    /// The feature of a public name.
    ///
    /// # Errors
    /// [`UvfeatError::InvalidParameter`] listing the valid names.
    pub fn from_name(name: &str) -> Result<Self> {
        Self::ALL.into_iter().find(|f| f.name() == name).ok_or_else(|| UvfeatError::InvalidParameter {
            name: "feature",
            reason: format!("unknown feature {name:?}; valid: {}", Self::ALL.map(Feature::name).join(", ")),
        })
    }

    /// Position in [`Feature::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// `true` for the features computed from the Gaussian curvature `K` (K itself, the principal
    /// curvatures and what derives from them).
    pub fn uses_gaussian_curvature(self) -> bool {
        matches!(
            self,
            Feature::GaussianCurvature | Feature::K1 | Feature::K2 | Feature::ShapeIndex | Feature::Curvedness
        )
    }
}

/// Where the curvature features (H, K, k1, k2, shape index, curvedness) come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CurvatureMethod {
    /// The paper's integral invariants (default).
    #[default]
    Integral,
    /// The weighted least-squares quadric of [`quadric_fit`], which also gives principal
    /// directions and a residual.
    Fit,
}

/// Settings of the estimators.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EstimatorSettings {
    /// Neighbourhood radius `r`.
    pub radius: f64,
    /// Gaussian-curvature method (also decides the pair behind `k1, k2`, shape index, curvedness).
    pub gaussian_method: GaussianMethod,
    /// Shape index is NaN where curvedness `< flat_tol / r`.
    pub flat_tol: f64,
    /// Weighting of the volume integrands.
    pub volume_weighting: VolumeWeighting,
    /// Source of the curvature features.
    pub method: CurvatureMethod,
}

/// Every feature of one neighbourhood.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimates {
    /// Values in [`Feature::ALL`] order.
    pub values: [f64; 9],
    /// `H^2 - K < 0` was clamped for the principal curvatures (geodesic-area method only).
    pub clamped: bool,
}

/// Evaluates every estimator on the sums of one neighbourhood; with [`CurvatureMethod::Fit`] the
/// curvature features come from `fit` instead (NaN where the fit failed), the volumes and bending
/// energy stay integral.
pub fn estimate(stats: &NeighbourhoodStats, fit: Option<&QuadricFit>, settings: &EstimatorSettings) -> Estimates {
    let (r, weighting) = (settings.radius, settings.volume_weighting);
    let integral_h = mean_curvature(&stats.elevation, &stats.radial, r, weighting);
    let (h, k, (k1, k2, clamped)) = if settings.method == CurvatureMethod::Fit {
        fit.map_or((f64::NAN, f64::NAN, (f64::NAN, f64::NAN, false)), |f| (f.mean, f.gaussian, (f.k1, f.k2, false)))
    } else {
        let (k, pair) = integral_curvatures(stats, integral_h, settings);
        (integral_h, k, pair)
    };
    let c = curvedness(k1, k2);
    let values = [
        bending_energy(&stats.bending),
        open_volume(&stats.elevation, &stats.radial, r, weighting),
        volume_invariant(&stats.elevation, &stats.radial, r, weighting),
        h,
        k,
        k1,
        k2,
        shape_index(k1, k2, c, r, settings.flat_tol),
        c,
    ];
    Estimates { values, clamped }
}

/// `K` and `(k1, k2, clamped)` of the integral estimators, given their `H`.
fn integral_curvatures(stats: &NeighbourhoodStats, h: f64, settings: &EstimatorSettings) -> (f64, (f64, f64, bool)) {
    let r = settings.radius;
    match settings.gaussian_method {
        GaussianMethod::Moments => {
            let k = gaussian_curvature_moments(&stats.normal_curvature);
            let spread = (2.0 * stats.normal_curvature.variance()).sqrt();
            let hm = stats.normal_curvature.mean();
            (k, (hm + spread, hm - spread, false))
        }
        GaussianMethod::GeodesicArea => {
            let k = gaussian_curvature_geodesic_area(&stats.geodesic_disk, r);
            (k, principal_curvatures(h, k))
        }
    }
}

/// The standard error of `feature`'s Monte Carlo estimate relative to its natural unit (`1/r`
/// for curvatures, `1/r^2` for K and bending energy, `r^3` for volumes), from the stage-1 sums
/// (DESIGN.md §1.8): stage 2 runs where this exceeds `tau`.
pub fn relative_standard_error(feature: Feature, stats: &NeighbourhoodStats, settings: &EstimatorSettings) -> f64 {
    let r = settings.radius;
    match feature {
        Feature::MeanCurvature => mean_curvature_error(&stats.elevation, r) * r,
        Feature::OpenVolume | Feature::VolumeInvariant => open_volume_error(&stats.elevation, r) / r.powi(3),
        Feature::BendingEnergy => stats.bending.standard_error() * r * r,
        Feature::GaussianCurvature if settings.gaussian_method == GaussianMethod::GeodesicArea => {
            gaussian_curvature_geodesic_area_error(&stats.geodesic_disk, r) * r * r
        }
        // K (moments), k1, k2, shape index, curvedness: the noise of the normal-curvature samples.
        _ => stats.normal_curvature.standard_error() * r,
    }
}

/// As [`relative_standard_error`] when the curvatures come from the quadric fit: its own
/// standard errors ([`QuadricFit::standard_error`]) for the curvature features, the integral
/// sums' for the others; NaN where the fit failed. The shape index, which has no error of its own,
/// is decided on `H`'s relative error, which it follows (NaN would run stage 2 everywhere).
pub fn fit_relative_error(
    feature: Feature,
    fit: Option<&QuadricFit>,
    stats: &NeighbourhoodStats,
    settings: &EstimatorSettings,
) -> f64 {
    if !feature.from_fit() {
        return relative_standard_error(feature, stats, settings);
    }
    let decided_on = if feature == Feature::ShapeIndex { Feature::MeanCurvature } else { feature };
    let r = settings.radius;
    let unit = if decided_on == Feature::GaussianCurvature { r * r } else { r };
    fit.map_or(f64::NAN, |f| f.standard_error(decided_on) * unit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_names_list_the_valid_ones() {
        for f in Feature::ALL {
            assert_eq!(Feature::from_name(f.name()).unwrap(), f);
            assert_eq!(Feature::ALL[f.index()], f);
        }
        let err = Feature::from_name("mean").unwrap_err().to_string();
        assert!(err.contains("mean_curvature") && err.contains("shape_index"), "{err}");
    }

    #[test]
    fn shape_index_and_curvedness_of_known_shapes() {
        let s = |k1: f64, k2: f64| shape_index(k1, k2, curvedness(k1, k2), 1.0, 1e-3);
        assert!((s(1.0, 1.0) - 1.0).abs() < 1e-12);
        assert!((s(1.0, 0.0) - 0.5).abs() < 1e-12);
        assert!(s(1.0, -1.0).abs() < 1e-12);
        assert!((s(-1.0, -1.0) + 1.0).abs() < 1e-12);
        assert!(s(0.0, 0.0).is_nan());
        assert!((curvedness(1.0, 0.0) - 0.5f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn principal_curvatures_clamp_and_order() {
        assert_eq!(principal_curvatures(1.0, 0.0), (2.0, 0.0, false));
        assert_eq!(principal_curvatures(1.0, 2.0), (1.0, 1.0, true));
    }
}
