//! The Jacobian `J_T` of a triangle's parameterisation (DESIGN.md §1.2.5, §1.3.1): the exact metric of
//! the piecewise-linear mesh, constant per triangle (built per frame by `frame::FaceMap`).

use glam::{DVec2, DVec3};

/// `J_T = [X1-X0, X2-X0] [U1-U0, U2-U0]^-1`: columns `P_u`, `P_v` (object units per uv unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobian {
    /// `P_u = dP/du`.
    pub pu: DVec3,
    /// `P_v = dP/dv`.
    pub pv: DVec3,
}

impl Jacobian {
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
