//! Local metric distortion (SPEC §1.3.3, paper eq. 2, decision A5): how many object units one uv
//! unit covers along the principal axes of the first fundamental form.

/// Principal stretches of the parameterisation at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distortion {
    /// Largest stretch `sigma_1 = sqrt(lambda_1)` (object units per uv unit).
    pub sigma1: f64,
    /// Smallest stretch `sigma_2 = sqrt(lambda_2) <= sigma_1`.
    pub sigma2: f64,
    /// Angle from +u of the axis of `sigma_1`, in `(-pi/2, pi/2]`.
    pub theta: f64,
}

impl Distortion {
    /// Eigen-decomposition of `I = [[E, F], [F, G]]`:
    /// `lambda_1,2 = (E+G)/2 +- sqrt(((E-G)/2)^2 + F^2)`, `theta = atan2(2F, E-G)/2`.
    pub fn from_metric([e, f, g]: [f64; 3]) -> Self {
        let mean = 0.5 * (e + g);
        let radius = (0.25 * (e - g) * (e - g) + f * f).sqrt();
        Self {
            sigma1: (mean + radius).max(0.0).sqrt(),
            sigma2: (mean - radius).max(0.0).sqrt(),
            theta: 0.5 * (2.0 * f).atan2(e - g),
        }
    }

    /// Area element `J = sigma_1 sigma_2 = sqrt(EG - F^2)` (object area per uv area).
    pub fn area_element(&self) -> f64 {
        self.sigma1 * self.sigma2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_4;

    #[test]
    fn rotated_anisotropic_stretch_is_recovered() {
        // P_u, P_v of a map stretching by 3 along 45 degrees and by 1 across it.
        let (s1, s2, th) = (3.0f64, 1.0f64, FRAC_PI_4);
        let (c, s) = (th.cos(), th.sin());
        // I = R diag(s1^2, s2^2) R^T
        let e = c * c * s1 * s1 + s * s * s2 * s2;
        let f = c * s * (s1 * s1 - s2 * s2);
        let g = s * s * s1 * s1 + c * c * s2 * s2;
        let d = Distortion::from_metric([e, f, g]);
        assert!((d.sigma1 - 3.0).abs() < 1e-12 && (d.sigma2 - 1.0).abs() < 1e-12);
        assert!((d.theta - th).abs() < 1e-12);
        assert!((d.area_element() - 3.0).abs() < 1e-12);
    }
}
