//! Stage 3 of the pipeline: per-frame mesh quantities (DESIGN.md §1.9, animation): everything that
//! depends on positions and is recomputed for each frame, on top of the reused topology.

use crate::distortion::{corner_metrics, interpolated_metric, seam_corner_metrics, Distortion};
use crate::error::Result;
use crate::mesh::{linear_gradient, seam_maps, uv_inverse, vertex_normals, Jacobian, SeamMap, Topology};
use glam::{DMat2, DVec2, DVec3};
use rayon::prelude::*;

/// Cap on a face's roughness: a face nearly edge-on to its vertex normals (a fold) would otherwise
/// outweigh every face around it in a ball's mean.
const MAX_FACE_ROUGHNESS: f64 = 10.0;

/// A face's affine parameterisation for the frame: `P(uv) = x0 + J (uv - uv0)` and the
/// (unnormalised) interpolated normal `N(uv) = n0 + J_N (uv - uv0)`. Barycentric interpolation is
/// affine in uv, so this is exact, and two multiply-adds per coordinate evaluate it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceMap {
    /// UV of corner 0.
    pub uv0: DVec2,
    /// Position of corner 0.
    pub x0: DVec3,
    /// `J = [P_u, P_v]`.
    pub jacobian: Jacobian,
    /// Vertex normal of corner 0.
    pub n0: DVec3,
    /// `dN/du` of the interpolated (unnormalised) normal.
    pub nu: DVec3,
    /// `dN/dv` of the interpolated normal.
    pub nv: DVec3,
    /// Area element `J = |P_u x P_v|` (object area per uv area).
    pub area_element: f64,
    /// Corner positions and unit vertex normals, for the smooth (Phong) lift.
    corners: [(DVec3, DVec3); 3],
    /// Inverse of `[U1 - U0, U2 - U0]`: uv offset -> barycentrics of corners 1 and 2.
    to_barycentric: DMat2,
}

impl FaceMap {
    /// The face's area over its area projected on the mean of its corners' vertex normals: how
    /// much more area a rough surface holds than the smooth surface it scatters about. The facets
    /// of a noisy scan tilt about its surface and the vertex normals average the tilts out, so a
    /// ball over one rough sheet holds about the mean of this over the ball times `pi r^2` (the
    /// noisy 200K lat-long sphere of docs/PEERS.md: 1.2 at the equator, up to 2.5 beside the poles,
    /// whose thin faces the same noise tilts further). 1 for a face without area.
    pub fn roughness(&self) -> f64 {
        let [(a, na), (b, nb), (c, nc)] = self.corners;
        let twice_area = (b - a).cross(c - a);
        let projected = twice_area.dot((na + nb + nc).normalize_or_zero()).abs();
        if projected > 0.0 {
            (twice_area.length() / projected).min(MAX_FACE_ROUGHNESS)
        } else {
            1.0
        }
    }

    #[inline]
    fn new(x: [DVec3; 3], n: [DVec3; 3], uv: [DVec2; 3]) -> Option<Self> {
        let inv = uv_inverse(uv)?;
        let (pu, pv) = linear_gradient(x, inv);
        let (nu, nv) = linear_gradient(n, inv);
        let jacobian = Jacobian { pu, pv };
        let corners = [(x[0], n[0]), (x[1], n[1]), (x[2], n[2])];
        Some(Self {
            uv0: uv[0],
            x0: x[0],
            jacobian,
            n0: n[0],
            nu,
            nv,
            area_element: pu.cross(pv).length(),
            corners,
            to_barycentric: inv,
        })
    }

    /// Position at `uv` (extrapolates linearly outside the face).
    #[inline]
    pub fn position(&self, uv: DVec2) -> DVec3 {
        let d = uv - self.uv0;
        self.x0 + self.jacobian.pu * d.x + self.jacobian.pv * d.y
    }

    /// Position at `uv` on the smooth surface through the vertices with the vertex normals:
    /// Phong tessellation `p + 1/2 sum_i b_i ((x_i - p) . n_i) n_i` (Boubekeur & Alexa 2008, with
    /// the shape factor 1/2 that lifts a chord onto its circle to second order). The flat facet
    /// lies up to `h^2 k / 8` below the smooth surface, which moves a sphere-volume H estimate by
    /// `4 delta / r^2`; the lift removes that facet bias from both the centre and the samples.
    /// Zero at the vertices and on flat regions; edges depend on their two vertices only, so the
    /// lift is continuous across faces and seams.
    #[inline]
    pub fn smooth_position(&self, uv: DVec2) -> DVec3 {
        let p = self.position(uv);
        let weights = self.barycentric(uv);
        let lift: DVec3 = self.corners.iter().zip(weights).map(|(&(x, n), w)| n * (w * (x - p).dot(n))).sum();
        p + 0.5 * lift
    }

    /// Barycentric coordinates of `uv` (negative outside the face).
    #[inline]
    pub fn barycentric(&self, uv: DVec2) -> [f64; 3] {
        let b = self.to_barycentric * (uv - self.uv0);
        [1.0 - b.x - b.y, b.x, b.y]
    }

    /// Corner positions and unit vertex normals.
    pub(crate) fn corners(&self) -> &[(DVec3, DVec3); 3] {
        &self.corners
    }

    /// Inverse of `[U1 - U0, U2 - U0]`: uv offset -> barycentrics of corners 1 and 2.
    pub(crate) fn barycentric_map(&self) -> DMat2 {
        self.to_barycentric
    }

    /// Unit normal at `uv` (interpolated vertex normals, renormalised).
    #[inline]
    pub fn normal(&self, uv: DVec2) -> DVec3 {
        let d = uv - self.uv0;
        (self.n0 + self.nu * d.x + self.nv * d.y).normalize_or_zero()
    }
}

/// Positions, normals and triangle metrics of one frame (its seam maps: [`Frame::seam_maps`]).
#[derive(Debug, Clone)]
pub struct Frame {
    /// (n_geometric) welded vertex positions.
    pub positions: Vec<DVec3>,
    /// (n_geometric) unit vertex normals.
    pub normals: Vec<DVec3>,
    /// (n_faces) distortion of each face (zeros where the Jacobian is missing).
    pub distortion: Vec<Distortion>,
    /// (n_corners) smoothed metric `[E, F, G]` of each atlas corner (see [`corner_metrics`]).
    pub corner_metrics: Vec<[f64; 3]>,
}

impl Frame {
    /// Computes the frame from the input positions (one row per input vertex).
    ///
    /// # Errors
    /// Vertex count mismatch or non-finite positions (see [`Topology::geometric_positions`]).
    pub fn new(topology: &Topology, input_positions: &[DVec3]) -> Result<Self> {
        let n_faces = topology.faces.len();
        let mut frame = Self {
            positions: Vec::new(),
            normals: Vec::new(),
            distortion: vec![ZERO_DISTORTION; n_faces],
            corner_metrics: Vec::new(),
        };
        frame.refresh(topology, input_positions)?;
        Ok(frame)
    }

    /// Recomputes the frame in place for new input positions: the per-face tables are
    /// overwritten, not reallocated (they are the bulk of a frame's memory traffic). On error
    /// nothing has changed.
    ///
    /// # Errors
    /// As [`Frame::new`].
    pub fn refresh(&mut self, topology: &Topology, input_positions: &[DVec3]) -> Result<()> {
        self.positions = topology.geometric_positions(input_positions)?;
        self.normals = vertex_normals(&self.positions, &topology.faces);
        let face_metrics: Vec<Option<[f64; 3]>> = (0..topology.faces.len())
            .into_par_iter()
            .map(|face| self.face_map(topology, face as u32).map(|map| map.jacobian.metric()))
            .collect();
        self.distortion
            .par_iter_mut()
            .zip(&face_metrics)
            .for_each(|(distortion, metric)| *distortion = metric.map_or(ZERO_DISTORTION, Distortion::from_metric));
        self.corner_metrics = corner_metrics(topology, |f| face_metrics[f]);
        Ok(())
    }

    /// (n_sides) the transition map of each boundary side of `topology` in this frame; `None`
    /// where nothing is across.
    pub fn seam_maps(&self, topology: &Topology) -> Vec<Option<SeamMap>> {
        let metrics = seam_corner_metrics(topology, &self.corner_metrics, &self.positions, &self.normals);
        seam_maps(topology, |face, corner| metrics[topology.corner_groups[face as usize][corner] as usize])
    }

    /// The affine position and normal maps of `face` for this frame; `None` for a face outside
    /// every chart or with a degenerate UV triangle. Built on demand from the vertices rather than
    /// stored: a stored map takes 344 bytes per face (a third of a GiB for a million faces),
    /// about as many bytes to load as the corners it is built from.
    #[inline]
    pub fn face_map(&self, topology: &Topology, face: u32) -> Option<FaceMap> {
        let face = face as usize;
        if topology.face_chart[face] < 0 {
            return None;
        }
        let corners = topology.faces[face];
        let gather = |values: &[DVec3]| corners.map(|v| values[v as usize]);
        FaceMap::new(gather(&self.positions), gather(&self.normals), topology.corner_uvs(face))
    }

    /// The sampler's metric at `uv` in `face`: the face's own metric, unless it is far more
    /// anisotropic than the smoothed field around it (a UV sliver, see [`corner_metrics`]); then
    /// the smoothed field. Where the two agree the face's metric is kept, so regular
    /// parameterisations sample exactly as DESIGN.md §1.4 says. Zero for a face without a
    /// parameterisation.
    pub fn sampling_distortion(&self, topology: &Topology, face: u32, uv: DVec2) -> Distortion {
        // Only the face's UV triangle is needed here, not its whole map (built from the vertices:
        // that was a fifth of a texel's centre on the shared lattice).
        let face = face as usize;
        let corners = topology.corner_uvs(face);
        let to_barycentric = DMat2::from_cols(corners[1] - corners[0], corners[2] - corners[0]);
        if topology.face_chart[face] < 0 || to_barycentric.determinant() == 0.0 {
            return ZERO_DISTORTION;
        }
        let b = to_barycentric.inverse() * (uv - corners[0]);
        let own = self.distortion[face];
        let smooth = Distortion::from_metric(interpolated_metric(
            topology,
            &self.corner_metrics,
            face,
            [1.0 - b.x - b.y, b.x, b.y],
        ));
        // A metric without a second stretch (a smoothed metric that could not be formed is zero)
        // is infinitely anisotropic: it never replaces a usable one.
        let anisotropy = |d: &Distortion| if d.sigma2 > 0.0 { d.sigma1 / d.sigma2 } else { f64::INFINITY };
        if anisotropy(&own) > SLIVER_ANISOTROPY * anisotropy(&smooth) {
            smooth
        } else {
            own
        }
    }
}

/// A face whose stretch ratio exceeds the smoothed field's by this factor is a sliver.
const SLIVER_ANISOTROPY: f64 = 2.0;

/// Distortion of faces without a usable Jacobian.
const ZERO_DISTORTION: Distortion = Distortion { sigma1: 0.0, sigma2: 0.0, theta: 0.0 };

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn affine_map_is_recovered_exactly() {
        // P(u, v) = (2u + v, 3v, u - v)
        let p = |t: DVec2| DVec3::new(2.0 * t.x + t.y, 3.0 * t.y, t.x - t.y);
        let uv = [DVec2::new(0.1, 0.2), DVec2::new(0.7, 0.3), DVec2::new(0.2, 0.9)];
        let map = FaceMap::new(uv.map(p), [DVec3::Z; 3], uv).unwrap();
        assert!((map.jacobian.pu - DVec3::new(2.0, 0.0, 1.0)).length() < 1e-12);
        assert!((map.jacobian.pv - DVec3::new(1.0, 3.0, -1.0)).length() < 1e-12);
        let d = DVec2::new(0.3, -0.2);
        let w = map.jacobian.pu * d.x + map.jacobian.pv * d.y;
        assert!((map.jacobian.pseudo_inverse(w).unwrap() - d).length() < 1e-12);
        let inside = DVec2::new(0.3, 0.4);
        assert!((map.position(inside) - p(inside)).length() < 1e-12);
        // Flat normals: the smooth lift is zero.
        assert!((map.smooth_position(inside) - p(inside)).length() < 1e-12);
    }
}
