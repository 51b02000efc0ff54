//! Open sphere volume `V_o` (DESIGN.md §2.2, paper eq. 6 reconstructed, decision A1).

use super::mean_curvature::radial_correction;
use super::statistics::{VolumeWeighting, WeightedSums};
use std::f64::consts::PI;

/// Volume of the ball of radius `r` at `p` outside the solid (on the side of the normal):
/// `V_o = (4 pi r^3 / 3) <(1 - sin(alpha)) / 2>_w`, `w = dA rho` (the horizon / solid-angle
/// argument: the shell of radius rho is open over the solid angle `integral (1 - sin alpha) dphi`).
///
/// As for the mean curvature, `<sin(alpha)>_w` is rescaled by the pattern's empirical radial
/// moment (`sin(alpha) ~ -kappa rho / 2`), which makes the unit sphere exact for any pattern.
///
/// Range `[0, 4 pi r^3 / 3]`; plane `2 pi r^3 / 3`; convex regions less. Units length^3.
pub fn open_volume(elevation: &WeightedSums, radial: &WeightedSums, radius: f64, weighting: VolumeWeighting) -> f64 {
    ball_volume(radius) * (1.0 - elevation.mean() * radial_correction(radial, weighting)) / 2.0
}

/// Standard error of [`open_volume`] (and of the volume invariant).
pub fn open_volume_error(elevation: &WeightedSums, radius: f64) -> f64 {
    ball_volume(radius) * elevation.standard_error() / 2.0
}

/// `4 pi r^3 / 3`.
pub fn ball_volume(radius: f64) -> f64 {
    4.0 * PI * radius.powi(3) / 3.0
}
