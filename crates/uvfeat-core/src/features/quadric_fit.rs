//! The fitting estimator (issue 6): a weighted least-squares height function of the neighbourhood
//! in the local frame of `p`, on the same seam-aware, area-weighted samples as the integral
//! estimators.
//!
//! With an orthonormal frame `(t1, t2, n)` at `p` and `(x, y, z)` the coordinates of `q_i - p` in
//! it, the fit minimises `sum dA_i (z_i - h(x_i, y_i))^2` over
//! `h = c0 + c1 x + c2 y + (a x^2 + 2 b x y + c y^2) / 2 + (cubic and quartic terms)`.
//! The curvatures come from the quadratic part only; the cubic and quartic terms absorb the
//! higher-order shape that a pure quadric would fold into `a, b, c`: over a ball of radius `r` the
//! `rho^4` term of a sphere biases a quadric's curvature by `r^2 / (4 R^2)` (1 % on the unit sphere
//! at `r = 0.2`, measured), the quartic fit's residual bias is `O(r^4)` (measured 1e-4).
//! The free offset `c0` and tilt `c1, c2` absorb the noise of `p` and of `n`: the curvatures are
//! those of the fitted graph at `(0, 0)`, from its shape operator `I^-1 II` with
//! `I = [[1 + c1^2, c1 c2], [c1 c2, 1 + c2^2]]`, `II = [[a, b], [b, c]] / sqrt(1 + c1^2 + c2^2)`.
//! Its eigenvalues are curvatures towards `n`; uvfeat's convention (positive where the surface
//! bends *away* from the outward normal, unit sphere `H = +1`) flips their sign.

use crate::sampling::Sample;
use glam::DVec3;

/// Unknowns of the full quartic: `(c0, c1, c2, a, b, c)`, then 4 cubic and 5 quartic terms.
const UNKNOWNS: usize = 15;

/// A Cholesky pivot below this fraction of its diagonal entry means the samples do not determine
/// the quadric (too few, or all on a line): the fit returns `None` rather than garbage.
const MIN_PIVOT: f64 = 1e-10;

/// Curvatures, principal directions and residual of one fitted neighbourhood.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadricFit {
    /// Mean curvature `H = (k1 + k2) / 2`, 1/length.
    pub mean: f64,
    /// Gaussian curvature `K = k1 k2`, 1/length^2.
    pub gaussian: f64,
    /// Largest principal curvature, 1/length.
    pub k1: f64,
    /// Smallest principal curvature, 1/length.
    pub k2: f64,
    /// Unit direction of `k1`, tangent to the fitted surface. A line field: its sign is only made
    /// deterministic (largest world component positive), not meaningful.
    pub d1: DVec3,
    /// Unit direction of `k2`: `n_fit x d1`, so `(d1, d2, n_fit)` is right-handed.
    pub d2: DVec3,
    /// Weighted RMS distance of the samples to the fitted quadric, relative to `r`: a quality
    /// measure (near 0 on smooth surfaces well inside the ball, large on creases and noise).
    pub residual: f64,
}

/// Fits the height function to `samples` around `centre` with normal `normal` (unit) at scale
/// `radius`; `None` when the samples do not determine the quadric.
pub fn quadric_fit(centre: DVec3, normal: DVec3, samples: &[Sample], radius: f64) -> Option<QuadricFit> {
    let (t1, t2) = normal.any_orthonormal_pair();
    // Coordinates in units of r keep the normal equations well scaled at every radius.
    let local = |s: &Sample| {
        let d = (s.position - centre) / radius;
        (d.dot(t1), d.dot(t2), d.dot(normal))
    };
    let basis = |x: f64, y: f64| {
        let (x2, y2) = (x * x, y * y);
        [
            1.0,
            x,
            y,
            0.5 * x2,
            x * y,
            0.5 * y2,
            x2 * x,
            x2 * y,
            x * y2,
            y2 * y,
            x2 * x2,
            x2 * x * y,
            x2 * y2,
            x * y2 * y,
            y2 * y2,
        ]
    };
    let mut ata = [[0.0; UNKNOWNS]; UNKNOWNS];
    let mut atb = [0.0; UNKNOWNS];
    for s in samples {
        let (x, y, z) = local(s);
        let phi = basis(x, y);
        for i in 0..UNKNOWNS {
            atb[i] += s.area * phi[i] * z;
            for j in 0..=i {
                ata[i][j] += s.area * phi[i] * phi[j];
            }
        }
    }
    let coef = solve_cholesky(ata, atb)?;
    let (mut sum_w, mut sum_we2) = (0.0, 0.0);
    for s in samples {
        let (x, y, z) = local(s);
        let phi = basis(x, y);
        let e = z - phi.iter().zip(&coef).map(|(p, c)| p * c).sum::<f64>();
        sum_w += s.area;
        sum_we2 += s.area * e * e;
    }
    let [_, c1, c2, a, b, c, ..] = coef;
    let (a, b, c) = (a / radius, b / radius, c / radius);
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

    /// Samples of the graph `z = offset + tilt . (x, y) + (a x^2 + 2 b x y + c y^2) / 2` on a
    /// polar grid of radius `r`, in the frame `(e1, e2, n)`, equal weights.
    fn graph_samples(frame: DQuat, (offset, tilt): (f64, [f64; 2]), [a, b, c]: [f64; 3], r: f64) -> Vec<Sample> {
        let mut out = Vec::new();
        for i in 1..=12 {
            for j in 0..24 {
                let rho = r * f64::from(i) / 12.0;
                let phi = std::f64::consts::TAU * f64::from(j) / 24.0;
                let (x, y) = (rho * phi.cos(), rho * phi.sin());
                let z = offset + tilt[0] * x + tilt[1] * y + 0.5 * (a * x * x + 2.0 * b * x * y + c * y * y);
                out.push(Sample {
                    position: frame * DVec3::new(x, y, z),
                    normal: frame * DVec3::Z,
                    area: rho,
                    distance: rho,
                    sin_alpha: 0.0,
                    pattern_index: 0,
                });
            }
        }
        out
    }

    #[test]
    fn an_exact_quadric_is_recovered_with_its_directions_and_signs() {
        let frame = DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1);
        // Height -(x^2 / R1 + y^2 / R2) / 2 bends away from n: k1 = 1/R1 = 2 along x, k2 = 0.5.
        let samples = graph_samples(frame, (0.0, [0.0, 0.0]), [-2.0, 0.0, -0.5], 0.3);
        let fit = quadric_fit(DVec3::ZERO, frame * DVec3::Z, &samples, 0.3).unwrap();
        assert!((fit.k1 - 2.0).abs() < 1e-9 && (fit.k2 - 0.5).abs() < 1e-9, "{fit:?}");
        assert!((fit.mean - 1.25).abs() < 1e-9 && (fit.gaussian - 1.0).abs() < 1e-9);
        assert!(fit.d1.dot(frame * DVec3::X).abs() > 1.0 - 1e-12);
        assert!(fit.d2.dot(frame * DVec3::Y).abs() > 1.0 - 1e-12);
        assert!(fit.residual < 1e-12);
    }

    #[test]
    fn offset_and_tilt_of_p_and_n_do_not_bias_the_curvatures() {
        // A saddle z = (x^2 - y^2)/2 seen from a point off the surface with a tilted normal: the
        // tilt correction gives the curvatures of the graph at the fitted point.
        let tilt = [0.2, -0.1];
        let samples = graph_samples(DQuat::IDENTITY, (0.01, tilt), [1.0, 0.0, -1.0], 0.2);
        let fit = quadric_fit(DVec3::ZERO, DVec3::Z, &samples, 0.2).unwrap();
        // The graph of tilt + quadric at the origin: curvatures of z = c1 x + c2 y + (x^2 - y^2)/2.
        let (c1, c2) = (tilt[0], tilt[1]);
        let w2 = 1.0 + c1 * c1 + c2 * c2;
        let expected_k = -1.0 / (w2 * w2);
        assert!((fit.gaussian - expected_k).abs() < 1e-9, "{fit:?}");
        assert!(fit.k1 > 0.0 && fit.k2 < 0.0);
        assert!(fit.d1.dot(fit.d2).abs() < 1e-12);
    }

    #[test]
    fn too_few_or_collinear_samples_give_none() {
        let samples = graph_samples(DQuat::IDENTITY, (0.0, [0.0, 0.0]), [1.0, 0.0, 1.0], 0.2);
        assert!(quadric_fit(DVec3::ZERO, DVec3::Z, &samples[..4], 0.2).is_none());
        let line: Vec<Sample> = samples.iter().filter(|s| s.position.y.abs() < 1e-12).copied().collect();
        assert!(quadric_fit(DVec3::ZERO, DVec3::Z, &line, 0.2).is_none());
    }
}
