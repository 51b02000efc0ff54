//! Mean curvature from the sphere-volume integral invariant (SPEC §2.4, paper eq. 7; Hulin &
//! Troyanov 2003, Pottmann et al. 2007).

use super::statistics::WeightedSums;

/// `H(p) = -(8 / (3 r)) <sin(alpha)>_w`, `w = dA rho`.
///
/// Derived from `V_r = (2 pi / 3) r^3 - (pi / 4) H r^4 + O(r^5)` without the cancellation of the
/// printed form. `H = (k1 + k2)/2`, positive where the surface bends away from the normal (unit
/// sphere with outward normals: `+1`). Units 1/length. `r` is the radius of the ball whose inside
/// volume is measured: larger `r` smooths more (H at scale `r`).
///
/// Integrand for adaptive sampling: `g = -(8/(3r)) sin(alpha)`, unit `1/r`.
pub fn mean_curvature(elevation: &WeightedSums, radius: f64) -> f64 {
    -8.0 / (3.0 * radius) * elevation.mean()
}

/// Standard error of [`mean_curvature`].
pub fn mean_curvature_error(elevation: &WeightedSums, radius: f64) -> f64 {
    8.0 / (3.0 * radius) * elevation.standard_error()
}
