//! Principal curvatures (DESIGN.md §2.6, paper eq. 9).

/// `k1,2 = H +- sqrt(max(H^2 - K, 0))`, `k1 >= k2`; returns `(k1, k2, clamped)` where `clamped`
/// says `H^2 - K < 0` had to be clamped (noisy estimates, decision A17). With the moments pair
/// `(H_m, K_m)`, `H^2 - K = 2 Var_w(k) >= 0` and nothing is ever clamped. Units 1/length; the
/// signs follow `H` (convex w.r.t. the normal: positive).
pub fn principal_curvatures(mean: f64, gaussian: f64) -> (f64, f64, bool) {
    let discriminant = mean * mean - gaussian;
    let root = discriminant.max(0.0).sqrt();
    (mean + root, mean - root, discriminant < 0.0)
}
