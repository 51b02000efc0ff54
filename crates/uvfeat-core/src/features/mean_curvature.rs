//! Mean curvature from the sphere-volume integral invariant (DESIGN.md §2.4, paper eq. 7; Hulin &
//! Troyanov 2003, Pottmann et al. 2007).

use super::statistics::{VolumeWeighting, WeightedSums};

/// `H(p) = -(8 / (3 r)) <sin(alpha)>_w`, `w = dA rho`, computed as the ratio estimator
/// `H = -2 <sin(alpha)>_w / <rho>_w`.
///
/// Derived from `V_r = (2 pi / 3) r^3 - (pi / 4) H r^4 + O(r^5)` without the cancellation of the
/// printed form. With volume-consistent radii `<rho>_w = 3r/4` and both forms agree; the ratio
/// form divides by the pattern's *empirical* `<rho>_w` instead, so the radial unevenness of one
/// finite stratified pattern (shared by every pixel, hence a bias of about 1 % over a whole map
/// at N = 256) cancels. `volume_weighting = "uniform"` keeps the paper's literal estimator
/// (`8H/9` bias, reproduction only).
///
/// `H = (k1 + k2)/2`, positive where the surface bends away from the normal (unit sphere with
/// outward normals: `+1`). Units 1/length. `r` is the radius of the ball whose inside volume is
/// measured: larger `r` smooths more (H at scale `r`).
///
/// Integrand for adaptive sampling: `g = -(8/(3r)) sin(alpha)`, unit `1/r`.
pub fn mean_curvature(elevation: &WeightedSums, radial: &WeightedSums, radius: f64, weighting: VolumeWeighting) -> f64 {
    -8.0 / (3.0 * radius) * elevation.mean() * radial_correction(radial, weighting)
}

/// `(3/4) / <rho/r>_w` for distance weighting (1 for the paper's uniform weighting): the factor
/// that replaces the expected radial moment of area-uniform samples by the pattern's own.
pub fn radial_correction(radial: &WeightedSums, weighting: VolumeWeighting) -> f64 {
    match weighting {
        VolumeWeighting::Distance => 0.75 / radial.mean(),
        VolumeWeighting::Uniform => 1.0,
    }
}

/// Standard error of [`mean_curvature`].
pub fn mean_curvature_error(elevation: &WeightedSums, radius: f64) -> f64 {
    8.0 / (3.0 * radius) * elevation.standard_error()
}
