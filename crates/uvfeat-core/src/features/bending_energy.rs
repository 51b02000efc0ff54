//! Local bending energy (DESIGN.md §2.1, paper eq. 5; Huang et al. 2006; decision A4).

use super::statistics::WeightedSums;

/// `e(p) = sum dA_i |n - n_i|^2 / rho_i^2 / sum dA_i` over samples with `rho_i >= 0.1 r`.
///
/// Squared numerator (a finite limit, dimensionally a bending energy); the inner exclusion keeps
/// texel- and facet-level noise from being amplified by `1/rho^2`. Limit as `r -> 0`:
/// `(k1^2 + k2^2) / 2` (sphere of radius R: `1/R^2`, plane 0, unit cylinder 0.5). Units 1/length^2.
pub fn bending_energy(bending: &WeightedSums) -> f64 {
    bending.mean()
}
