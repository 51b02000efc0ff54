//! The Jacobian `J_T` of a triangle's parameterisation (DESIGN.md §1.2.5, §1.3.1): the exact metric of
//! the piecewise-linear mesh, constant per triangle (built per frame by `frame::FaceMap`).

use glam::{DMat2, DVec2, DVec3};

/// `J_T = [X1-X0, X2-X0] [U1-U0, U2-U0]^-1`: columns `P_u`, `P_v` (object units per uv unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobian {
    /// `P_u = dP/du`.
    pub pu: DVec3,
    /// `P_v = dP/dv`.
    pub pv: DVec3,
}

/// `[U1-U0, U2-U0]^-1` of a triangle's corner UVs; `None` where the UV triangle is degenerate.
pub fn uv_inverse(uv: [DVec2; 3]) -> Option<DMat2> {
    let m = DMat2::from_cols(uv[1] - uv[0], uv[2] - uv[0]);
    (m.determinant() != 0.0).then(|| m.inverse())
}

/// The uv gradient `(d/du, d/dv)` of values given at a triangle's corners, linear over it, with
/// `inverse` its [`uv_inverse`].
#[inline]
pub fn linear_gradient(v: [DVec3; 3], inverse: DMat2) -> (DVec3, DVec3) {
    let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
    (e1 * inverse.x_axis.x + e2 * inverse.x_axis.y, e1 * inverse.y_axis.x + e2 * inverse.y_axis.y)
}

impl Jacobian {
    /// The Jacobian of the triangle with corners `x` at `uv`; `None` where its UV triangle is
    /// degenerate.
    pub fn of_triangle(x: [DVec3; 3], uv: [DVec2; 3]) -> Option<Self> {
        let (pu, pv) = linear_gradient(x, uv_inverse(uv)?);
        Some(Self { pu, pv })
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
