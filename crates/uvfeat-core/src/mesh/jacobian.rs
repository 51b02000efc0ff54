//! The Jacobian `J_T` of a triangle's parameterisation (SPEC §1.2.5, §1.3.1): the exact metric of
//! the piecewise-linear mesh, constant per triangle.

use glam::{DMat2, DVec2, DVec3};

/// `J_T = [X1-X0, X2-X0] [U1-U0, U2-U0]^-1`: columns `P_u`, `P_v` (object units per uv unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobian {
    /// `P_u = dP/du`.
    pub pu: DVec3,
    /// `P_v = dP/dv`.
    pub pv: DVec3,
}

impl Jacobian {
    /// Jacobian of a triangle from its positions and corner UVs; `None` for a degenerate UV triangle.
    pub fn of_triangle(x: [DVec3; 3], uv: [DVec2; 3]) -> Option<Self> {
        let du = DMat2::from_cols(uv[1] - uv[0], uv[2] - uv[0]);
        let det = du.determinant();
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv = du.inverse();
        let (e1, e2) = (x[1] - x[0], x[2] - x[0]);
        // [e1 e2] * inv: column j of the product is e1 * inv[j][0] + e2 * inv[j][1].
        Some(Self { pu: e1 * inv.x_axis.x + e2 * inv.x_axis.y, pv: e1 * inv.y_axis.x + e2 * inv.y_axis.y })
    }

    /// First fundamental form `(E, F, G) = (P_u.P_u, P_u.P_v, P_v.P_v)`.
    pub fn metric(&self) -> [f64; 3] {
        [self.pu.dot(self.pu), self.pu.dot(self.pv), self.pv.dot(self.pv)]
    }

    /// `J^+ w = (J^T J)^-1 J^T w`: the uv displacement whose image is the in-plane part of `w`.
    /// `None` when the triangle is degenerate in 3D (singular metric).
    pub fn pseudo_inverse(&self, w: DVec3) -> Option<DVec2> {
        let [e, f, g] = self.metric();
        let det = e * g - f * f;
        if det <= 1e-300 || det <= 1e-24 * (e * g) {
            return None;
        }
        let (a, b) = (self.pu.dot(w), self.pv.dot(w));
        Some(DVec2::new(g * a - f * b, e * b - f * a) / det)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn affine_map_is_recovered_exactly() {
        // P(u, v) = (2u + v, 3v, u - v)
        let p = |u: f64, v: f64| DVec3::new(2.0 * u + v, 3.0 * v, u - v);
        let uv = [DVec2::new(0.1, 0.2), DVec2::new(0.7, 0.3), DVec2::new(0.2, 0.9)];
        let j = Jacobian::of_triangle(uv.map(|t| p(t.x, t.y)), uv).unwrap();
        assert!((j.pu - DVec3::new(2.0, 0.0, 1.0)).length() < 1e-12);
        assert!((j.pv - DVec3::new(1.0, 3.0, -1.0)).length() < 1e-12);
        let d = DVec2::new(0.3, -0.2);
        let w = j.pu * d.x + j.pv * d.y;
        assert!((j.pseudo_inverse(w).unwrap() - d).length() < 1e-12);
    }
}
