//! Open sphere volume `V_o` (SPEC §2.2, paper eq. 6 reconstructed, decision A1).

use super::statistics::WeightedSums;
use std::f64::consts::PI;

/// Volume of the ball of radius `r` at `p` outside the solid (on the side of the normal):
/// `V_o = (4 pi r^3 / 3) <(1 - sin(alpha)) / 2>_w`, `w = dA rho` (the horizon / solid-angle
/// argument: the shell of radius rho is open over the solid angle `integral (1 - sin alpha) dphi`).
///
/// Range `[0, 4 pi r^3 / 3]`; plane `2 pi r^3 / 3`; convex regions less. Units length^3.
pub fn open_volume(elevation: &WeightedSums, radius: f64) -> f64 {
    ball_volume(radius) * (1.0 - elevation.mean()) / 2.0
}

/// Standard error of [`open_volume`] (and of the volume invariant).
pub fn open_volume_error(elevation: &WeightedSums, radius: f64) -> f64 {
    ball_volume(radius) * elevation.standard_error() / 2.0
}

/// `4 pi r^3 / 3`.
pub fn ball_volume(radius: f64) -> f64 {
    4.0 * PI * radius.powi(3) / 3.0
}
