//! Gaussian curvature (DESIGN.md §2.5): curvature moments (default) or the paper's geodesic-disk area.

use super::statistics::WeightedSums;
use std::f64::consts::PI;

/// How Gaussian curvature is estimated (decision A15).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GaussianMethod {
    /// Normal-curvature moments, `K = 3 <k>^2 - 2 <k^2>` (default: low noise).
    #[default]
    Moments,
    /// Bertrand–Diquet–Puiseux geodesic-disk area, `K = 12 (pi r^2 - GA) / (pi r^4)` (the paper's;
    /// per-pixel noise is large, use it for reproduction).
    GeodesicArea,
}

/// Moments estimator: with `k_i = -2 sin(alpha_i) / rho_i` (normal curvature of the osculating
/// circle through `q_i`), `K_m = 3 <k>_w^2 - 2 <k^2>_w = H_m^2 - 2 Var_w(k)`, `w = dA rho^2`
/// (the `dA` of the original contract, DESIGN.md §2.5b, times `rho^2` against the facet noise of triangle meshes), `rho >= 0.1 r`. Averaging `kappa_n(phi) = k1 cos^2 + k2 sin^2` over phi gives
/// `<kappa_n> = H`, `<kappa_n^2> = (3 k1^2 + 2 k1 k2 + 3 k2^2)/8`, hence `K = k1 k2`. Sign-free
/// w.r.t. the normal. Units 1/length^2.
pub fn gaussian_curvature_moments(normal_curvature: &WeightedSums) -> f64 {
    3.0 * normal_curvature.mean().powi(2) - 2.0 * normal_curvature.mean_square()
}

/// Geodesic-area estimator: `K = 12 (pi r^2 - GA) / (pi r^4)` with `GA = sum_{d_i < r} dA_i`,
/// `d_i` the arc-length geodesic estimate (DESIGN.md §2.5a). Needs the margin `m >= 1.1` so the
/// geodesic disk lies inside the sampled ellipse. Units 1/length^2.
pub fn gaussian_curvature_geodesic_area(geodesic_disk: &WeightedSums, radius: f64) -> f64 {
    if geodesic_disk.w <= 0.0 {
        return f64::NAN;
    }
    12.0 * (PI * radius * radius - geodesic_disk.wg) / (PI * radius.powi(4))
}

/// Standard error of the geodesic-area estimator (`GA` is a sum of `dA [d < r]`).
pub fn gaussian_curvature_geodesic_area_error(geodesic_disk: &WeightedSums, radius: f64) -> f64 {
    12.0 / (PI * radius.powi(4)) * geodesic_disk.w * geodesic_disk.standard_error()
}
