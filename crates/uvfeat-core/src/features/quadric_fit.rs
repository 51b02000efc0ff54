//! The fitting estimator: a weighted least-squares fit of the neighbourhood's normal
//! sections by osculating circles, in the local frame of `p`, on the same seam-aware,
//! area-weighted samples as the integral estimators.
//!
//! With an orthonormal frame `(t1, t2, n)` at `p`, `(x, y, z)` the coordinates of `q_i - p` in it,
//! `rho^2 = x^2 + y^2` and `(u, v) = (x, y) / rho` the direction of `q_i` in the tangent plane, the
//! fit minimises `sum dA_i (z_i - h_i)^2` over
//!
//! `h = c0 + c1 x + c2 y + kappa(u, v) d^2 / 2`,  `kappa(u, v) = a u^2 + 2 b u v + c v^2`,
//!
//! with `d^2 = rho^2 + z^2 = |q_i - p|^2` the squared chord. A circle of curvature `kappa` tangent
//! at the centre satisfies `z = kappa d^2 / 2` exactly (chord property), for every point of the
//! circle: the model is exact on spheres at any radius, and its error elsewhere comes only from
//! how the curvature varies, not from the `rho^4` term of every curved section that biases a
//! plain quadric `z = kappa rho^2 / 2` by `r^2 kappa^2 / 4` (12 % on the torus of the benchmarks at
//! 4 % of the diagonal, measured). Higher polynomial terms would absorb that bias too, but the
//! `rho^4` terms are almost collinear with `rho^2` over a disk and multiply the noise of `a, b, c`
//! by about 4 (H error on the 0.2 %-noise torus at 4 %: 71 % with quartic terms, 17 % with
//! circles). The chord property holds in the frame of the true tangent plane at the true point,
//! so the fit runs twice: the second time from the fitted point `p + c0 n`, with the fitted normal.
//!
//! The free offset `c0` and tilt `c1, c2` absorb the noise of `p` and of `n`: the curvatures are
//! those of the fitted graph at `(0, 0)`, from its shape operator `I^-1 II` with
//! `I = [[1 + c1^2, c1 c2], [c1 c2, 1 + c2^2]]`, `II = [[a, b], [b, c]] / sqrt(1 + c1^2 + c2^2)`.
//! Its eigenvalues are curvatures towards `n`; uvfeat's convention (positive where the surface
//! bends *away* from the outward normal, unit sphere `H = +1`) flips their sign.

use super::Feature;
use crate::sampling::Sample;
use glam::DVec3;

/// Unknowns `(c0, c1, c2, a, b, c)`.
const UNKNOWNS: usize = 6;

/// A Cholesky pivot below this fraction of its diagonal entry means the samples do not determine
/// the fit (too few, or all on a line): the fit returns `None` rather than garbage.
const MIN_PIVOT: f64 = 1e-10;

/// Curvatures, principal directions and residual of one fitted neighbourhood.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadricFit {
    /// Mean curvature `H = (k1 + k2) / 2`.
    pub mean: f64,
    /// Gaussian curvature `K = k1 k2`.
    pub gaussian: f64,
    /// Largest principal curvature.
    pub k1: f64,
    /// Smallest principal curvature.
    pub k2: f64,
    /// Unit direction of `k1` (tangent to the fitted surface). A line field: the sign is made
    /// deterministic (largest world component positive), not meaningful.
    pub d1: DVec3,
    /// Unit direction of `k2`: `n_fit x d1`, so `(d1, d2, n_fit)` is right-handed.
    pub d2: DVec3,
    /// Weighted RMS distance of the samples to the fitted surface, relative to `r`: a quality
    /// measure (near 0 on smooth surfaces well inside the ball, large on creases and noise).
    pub residual: f64,
    /// Standard errors of `mean` and `gaussian` over random draws of the samples: the
    /// heteroscedasticity-consistent ("sandwich") covariance `A^-1 (sum (w e)^2 x x^T) A^-1` of
    /// the weighted least squares, `A = sum w x x^T`, carried to H and K by their gradients at the
    /// fitted frame (where the tilt vanishes, `H = -(a + c)/2`, `K = ac - b^2`). It treats the
    /// samples as independent, so a stratified pattern's error is overstated, as the integral
    /// estimators' own errors are (DESIGN.md §1.8): adaptive sampling compares it to `tau`. NaN
    /// unless asked for (one more pass over the samples).
    pub mean_error: f64,
    /// See `mean_error`.
    pub gaussian_error: f64,
}

impl QuadricFit {
    /// The standard error of `feature` as the fit estimates it: `mean_error` for `H`, and for
    /// `k1`, `k2` and the curvedness, which follow it; `gaussian_error` for `K`; NaN for the shape
    /// index, which has none, and for the features the fit does not estimate.
    pub fn standard_error(&self, feature: Feature) -> f64 {
        match feature {
            Feature::MeanCurvature | Feature::K1 | Feature::K2 | Feature::Curvedness => self.mean_error,
            Feature::GaussianCurvature => self.gaussian_error,
            _ => f64::NAN,
        }
    }
}

/// One sample in a local frame, in units of `r`.
#[derive(Clone, Copy)]
struct Local {
    z: f64,
    /// Regressors of `(c0, c1, c2, a, b, c)`.
    basis: [f64; UNKNOWNS],
}

impl Local {
    fn new(offset: DVec3, frame: &Frame) -> Self {
        let (x, y, z) = (offset.dot(frame.t1), offset.dot(frame.t2), offset.dot(frame.normal));
        let rho2 = x * x + y * y;
        let d2 = rho2 + z * z;
        // At the centre itself the direction is undefined, and its regressors vanish with d.
        let [u, w, v] = if rho2 > 0.0 { [0.5 * x * x / rho2, x * y / rho2, 0.5 * y * y / rho2] } else { [0.0; 3] };
        Self { z, basis: [1.0, x, y, u * d2, w * d2, v * d2] }
    }

    fn height(&self, coef: &[f64; UNKNOWNS]) -> f64 {
        self.basis.iter().zip(coef).map(|(p, c)| p * c).sum()
    }
}

/// Origin and orthonormal axes of a fit.
struct Frame {
    origin: DVec3,
    t1: DVec3,
    t2: DVec3,
    normal: DVec3,
}

impl Frame {
    fn new(origin: DVec3, normal: DVec3) -> Self {
        let (t1, t2) = normal.any_orthonormal_pair();
        Self { origin, t1, t2, normal }
    }
}

/// The weighted least squares of the model in `frame` (unknowns `(c0, c1, c2, a, b, c)` in units
/// of `r`): `A = sum w x x^T` (lower triangle) and `sum w x z`.
fn normal_equations(frame: &Frame, samples: &[Sample], radius: f64) -> ([[f64; UNKNOWNS]; UNKNOWNS], [f64; UNKNOWNS]) {
    let mut ata = [[0.0; UNKNOWNS]; UNKNOWNS];
    let mut atb = [0.0; UNKNOWNS];
    for s in samples {
        // Coordinates in units of r keep the normal equations well scaled at every radius.
        let q = Local::new((s.position - frame.origin) / radius, frame);
        for i in 0..UNKNOWNS {
            atb[i] += s.area * q.basis[i] * q.z;
            for (j, &basis) in q.basis[..=i].iter().enumerate() {
                ata[i][j] += s.area * q.basis[i] * basis;
            }
        }
    }
    (ata, atb)
}

/// Gradients of `H r = -(a + c)/2` and `K r^2 = ac - b^2` with respect to the coefficients, in
/// the fitted frame (where the tilt `c1, c2` vanishes): see [`QuadricFit::mean_error`].
fn curvature_gradients(coef: &[f64; UNKNOWNS]) -> [[f64; UNKNOWNS]; 2] {
    let [_, _, _, a, b, c] = *coef;
    [[0.0, 0.0, 0.0, -0.5, 0.0, -0.5], [0.0, 0.0, 0.0, c, -2.0 * b, a]]
}

/// Fits osculating circles to `samples` around `centre` with normal `normal` (unit) at scale
/// `radius`; `None` when the samples do not determine the fit.
pub fn quadric_fit(
    centre: DVec3,
    normal: DVec3,
    samples: &[Sample],
    radius: f64,
    with_errors: bool,
) -> Option<QuadricFit> {
    let first = Frame::new(centre, normal);
    let (ata, atb) = normal_equations(&first, samples, radius);
    let [c0, c1, c2, ..] = solve_cholesky(ata, atb)?;
    let fitted = Frame::new(centre + c0 * radius * normal, (normal - c1 * first.t1 - c2 * first.t2).normalize());
    let (ata, atb) = normal_equations(&fitted, samples, radius);
    let coef = solve_cholesky(ata, atb)?;
    // The sandwich variance of `g . coef` is `u^T M u`, `u = A^-1 g`, `M = sum (w e)^2 x x^T`:
    // summed with the residual, in the same pass over the samples.
    let projections = with_errors.then(|| curvature_gradients(&coef).map(|g| solve_cholesky(ata, g)));
    let (mut sum_w, mut sum_we2, mut variances) = (0.0, 0.0, [0.0; 2]);
    for s in samples {
        let q = Local::new((s.position - fitted.origin) / radius, &fitted);
        let e = q.z - q.height(&coef);
        sum_w += s.area;
        sum_we2 += s.area * e * e;
        for (variance, u) in variances.iter_mut().zip(projections.iter().flatten()) {
            if let Some(u) = u {
                *variance += (s.area * e * q.height(u)).powi(2);
            }
        }
    }
    let error = |k: usize| match projections {
        Some(us) if us[k].is_some() => variances[k].sqrt(),
        _ => f64::NAN,
    };
    let (mean_error, gaussian_error) = (error(0) / radius, error(1) / (radius * radius));
    let [_, c1, c2, a, b, c] = coef;
    let (a, b, c) = (a / radius, b / radius, c / radius);
    let Frame { t1, t2, normal, .. } = fitted;
    // Graph at (0, 0): tangents X_x = t1 + c1 n, X_y = t2 + c2 n, unit normal towards +n.
    let (xx, xy) = (t1 + c1 * normal, t2 + c2 * normal);
    let n_fit = xx.cross(xy).normalize();
    let w = (1.0 + c1 * c1 + c2 * c2).sqrt();
    let (e, f, g) = (1.0 + c1 * c1, c1 * c2, 1.0 + c2 * c2);
    let (l, m, nn) = (a / w, b / w, c / w);
    let det_i = e * g - f * f;
    // Curvatures towards n; uvfeat's signs are their negatives.
    let mean_towards = (e * nn - 2.0 * f * m + g * l) / (2.0 * det_i);
    let gaussian = (l * nn - m * m) / det_i;
    let root = (mean_towards * mean_towards - gaussian).max(0.0).sqrt();
    // k1 (largest in uvfeat's signs) is the smallest curvature towards n.
    let lambda1 = mean_towards - root;
    // (II - lambda I) v = 0: either row gives v; take the better conditioned one.
    let rows = [(m - lambda1 * f, -(l - lambda1 * e)), (nn - lambda1 * g, -(m - lambda1 * f))];
    let (xi, eta) = if rows[0].0.hypot(rows[0].1) >= rows[1].0.hypot(rows[1].1) { rows[0] } else { rows[1] };
    // At an umbilic every direction is principal: fall back to t1.
    let d1 = (xi * xx + eta * xy).try_normalize().unwrap_or(t1);
    let d1 = canonical_sign(d1);
    Some(QuadricFit {
        mean: -mean_towards,
        gaussian,
        k1: -lambda1,
        k2: -(mean_towards + root),
        d1,
        d2: n_fit.cross(d1),
        residual: (sum_we2 / sum_w).sqrt(),
        mean_error,
        gaussian_error,
    })
}

/// `v` or `-v`, whichever has its largest-magnitude component positive.
fn canonical_sign(v: DVec3) -> DVec3 {
    let a = v.abs();
    let largest = if a.x >= a.y && a.x >= a.z {
        v.x
    } else if a.y >= a.z {
        v.y
    } else {
        v.z
    };
    if largest < 0.0 {
        -v
    } else {
        v
    }
}

/// Solves `A c = b` for symmetric positive definite `A` given by its lower triangle, by Cholesky;
/// `None` when a pivot is not positive enough (singular or ill-conditioned system).
fn solve_cholesky(mut a: [[f64; UNKNOWNS]; UNKNOWNS], mut b: [f64; UNKNOWNS]) -> Option<[f64; UNKNOWNS]> {
    for j in 0..UNKNOWNS {
        let diagonal = a[j][j];
        let pivot = diagonal - (0..j).map(|k| a[j][k] * a[j][k]).sum::<f64>();
        if !(pivot > MIN_PIVOT * diagonal) {
            return None;
        }
        a[j][j] = pivot.sqrt();
        for i in j + 1..UNKNOWNS {
            let dot = (0..j).map(|k| a[i][k] * a[j][k]).sum::<f64>();
            a[i][j] = (a[i][j] - dot) / a[j][j];
        }
    }
    for i in 0..UNKNOWNS {
        b[i] = (b[i] - (0..i).map(|k| a[i][k] * b[k]).sum::<f64>()) / a[i][i];
    }
    for i in (0..UNKNOWNS).rev() {
        b[i] = (b[i] - (i + 1..UNKNOWNS).map(|k| a[k][i] * b[k]).sum::<f64>()) / a[i][i];
    }
    Some(b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    /// Samples of the surface whose normal section in each direction `phi` of the tangent plane is a
    /// circle of curvature `kappa(phi) = a cos^2 + 2 b cos sin + c sin^2` (the model, exactly),
    /// towards `+n`, on a polar grid of radius `r`, in the frame `(e1, e2, n)` rotated by `frame`
    /// and moved to `origin`; weights proportional to the polar area element.
    fn circle_samples(frame: DQuat, origin: DVec3, [a, b, c]: [f64; 3], r: f64) -> Vec<Sample> {
        let mut out = Vec::new();
        for i in 1..=12 {
            for j in 0..24 {
                let rho = r * f64::from(i) / 12.0;
                let phi = std::f64::consts::TAU * f64::from(j) / 24.0;
                let (cos, sin) = (phi.cos(), phi.sin());
                let kappa = a * cos * cos + 2.0 * b * cos * sin + c * sin * sin;
                let z = kappa * rho * rho / (1.0 + (1.0 - kappa * kappa * rho * rho).sqrt());
                out.push(Sample {
                    position: origin + frame * DVec3::new(rho * cos, rho * sin, z),
                    normal: frame * DVec3::Z,
                    area: rho,
                    distance: rho,
                    sin_alpha: 0.0,
                    geodesic: rho,
                    pattern_index: 0,
                });
            }
        }
        out
    }

    #[test]
    fn spheres_are_recovered_exactly_at_any_radius() {
        // A quadric fit is off by r^2 / (4 R^2) here (25 % at r = R); osculating circles are exact.
        let frame = DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
        for r in [0.1, 0.5, 0.95] {
            let samples = circle_samples(frame, DVec3::ZERO, [-1.0, 0.0, -1.0], r);
            let fit = quadric_fit(DVec3::ZERO, frame * DVec3::Z, &samples, r, false).unwrap();
            assert!((fit.mean - 1.0).abs() < 1e-9 && (fit.gaussian - 1.0).abs() < 1e-9, "r = {r}: {fit:?}");
            assert!(fit.residual < 1e-9);
        }
    }

    #[test]
    fn curvatures_directions_and_signs_of_an_anisotropic_surface() {
        let frame = DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
        // Sections bending away from n: k1 = 2 along x, k2 = 0.5 along y.
        let samples = circle_samples(frame, DVec3::ZERO, [-2.0, 0.0, -0.5], 0.3);
        let fit = quadric_fit(DVec3::ZERO, frame * DVec3::Z, &samples, 0.3, false).unwrap();
        assert!((fit.k1 - 2.0).abs() < 1e-9 && (fit.k2 - 0.5).abs() < 1e-9, "{fit:?}");
        assert!((fit.mean - 1.25).abs() < 1e-9 && (fit.gaussian - 1.0).abs() < 1e-9);
        assert!(fit.d1.dot(frame * DVec3::X).abs() > 1.0 - 1e-12);
        assert!(fit.d2.dot(frame * DVec3::Y).abs() > 1.0 - 1e-12);
        // A saddle: k1 > 0 > k2.
        let saddle = circle_samples(frame, DVec3::ZERO, [1.0, 0.0, -1.0], 0.3);
        let fit = quadric_fit(DVec3::ZERO, frame * DVec3::Z, &saddle, 0.3, false).unwrap();
        assert!((fit.k1 - 1.0).abs() < 1e-9 && (fit.k2 + 1.0).abs() < 1e-9 && fit.mean.abs() < 1e-9, "{fit:?}");
    }

    #[test]
    fn offset_and_tilt_of_p_and_n_do_not_bias_the_curvatures() {
        // The centre given 1 % of r off the surface and a normal tilted by 0.15 rad: the second
        // pass fits from the fitted point and normal.
        let frame = DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
        let (n, r) = (frame * DVec3::Z, 0.3);
        let samples = circle_samples(frame, DVec3::ZERO, [-2.0, 0.0, -0.5], r);
        let tilted = (n + 0.15 * (frame * DVec3::new(0.6, 0.8, 0.0))).normalize();
        let fit = quadric_fit(0.01 * r * n, tilted, &samples, r, false).unwrap();
        assert!((fit.k1 - 2.0).abs() < 2e-3 && (fit.k2 - 0.5).abs() < 2e-3, "{fit:?}");
        assert!(fit.d1.dot(frame * DVec3::X).abs() > 0.9999);
    }

    /// For independent samples the sandwich errors of `H` and `K` match the spread of the fit over
    /// repeated draws (here: uniform area samples of a noisy surface with `k1 = 2`, `k2 = 0.5`).
    #[test]
    fn sandwich_errors_match_the_spread_over_independent_draws() {
        let (r, draws, n) = (0.3, 300, 200);
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut uniform = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut means, mut gaussians, mut reported) = (Vec::new(), Vec::new(), (0.0, 0.0));
        for _ in 0..draws {
            let samples: Vec<Sample> = (0..n)
                .map(|_| {
                    let (rho, phi) = (r * uniform().sqrt(), std::f64::consts::TAU * uniform());
                    let (x, y) = (rho * phi.cos(), rho * phi.sin());
                    let noise = 0.02 * r * (uniform() - 0.5);
                    let z = -(2.0 * x * x + 0.5 * y * y) / 2.0 + noise;
                    Sample {
                        position: DVec3::new(x, y, z),
                        normal: DVec3::Z,
                        area: 1.0,
                        distance: rho,
                        sin_alpha: 0.0,
                        geodesic: rho,
                        pattern_index: 0,
                    }
                })
                .collect();
            let fit = quadric_fit(DVec3::ZERO, DVec3::Z, &samples, r, true).unwrap();
            means.push(fit.mean);
            gaussians.push(fit.gaussian);
            reported.0 += fit.mean_error / f64::from(draws);
            reported.1 += fit.gaussian_error / f64::from(draws);
        }
        let spread = |v: &[f64]| {
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
        };
        let (h, k) = (spread(&means) / reported.0, spread(&gaussians) / reported.1);
        assert!((0.8..1.25).contains(&h) && (0.8..1.25).contains(&k), "measured / reported: H {h}, K {k}");
    }

    #[test]
    fn too_few_or_collinear_samples_give_none() {
        let samples = circle_samples(DQuat::IDENTITY, DVec3::ZERO, [1.0, 0.0, 1.0], 0.2);
        assert!(quadric_fit(DVec3::ZERO, DVec3::Z, &samples[..4], 0.2, false).is_none());
        let line: Vec<Sample> = samples.iter().filter(|s| s.position.y.abs() < 1e-12).copied().collect();
        assert!(quadric_fit(DVec3::ZERO, DVec3::Z, &line, 0.2, false).is_none());
    }
}
