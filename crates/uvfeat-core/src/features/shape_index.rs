//! Shape index (DESIGN.md §2.7, paper eq. 8 with its sign fixed, decision A16; Koenderink & van Doorn 1992).

use std::f64::consts::FRAC_2_PI;

/// `S = (2/pi) atan2(k1 + k2, k1 - k2)` in `[-1, 1]`, `k1 >= k2`: +1 convex cap (w.r.t. outward
/// normals), +0.5 ridge, 0 symmetric saddle, -0.5 rut, -1 concave cup. NaN where the curvedness is
/// below `flat_tol / r`: planar points have no shape. Dimensionless.
pub fn shape_index(k1: f64, k2: f64, curvedness: f64, radius: f64, flat_tol: f64) -> f64 {
    if !(curvedness >= flat_tol / radius) {
        return f64::NAN;
    }
    FRAC_2_PI * (k1 + k2).atan2(k1 - k2)
}
