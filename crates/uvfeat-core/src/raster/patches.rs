//! Compact per-face patches of the smooth surface for the sampler's fast path: the
//! same surface [`FaceMap::smooth_position`] and [`FaceMap::normal`] evaluate, stored as one
//! 128-byte f32 record per face so that a neighbourhood's faces stay in cache (a [`FaceMap`] is
//! 352 bytes of f64; on a 100K-face mesh their 35 MB did not fit in any cache and the lookup was
//! a third of the sampling time).
//!
//! The Phong-lifted position is a quadratic polynomial in the parametric offset `d = uv - uv0`
//! inside a face: with the barycentric weights `b_i(d)` and the heights
//! `s_i(d) = (x_i - p(d)) . n_i`, both affine in `d`, the lift `1/2 sum b_i s_i n_i` is quadratic.
//! Positions are stored relative to the frame's [`FacePatches::origin`] (the centre of the
//! bounding box), so that f32 keeps the small differences `q - p` the estimators use accurate.
//!
//! [`FaceMap`]: crate::frame::FaceMap
//! [`FaceMap::smooth_position`]: crate::frame::FaceMap::smooth_position
//! [`FaceMap::normal`]: crate::frame::FaceMap::normal

use crate::cancel;
use crate::frame::{FaceMap, Frame};
use crate::mesh::Topology;
use glam::{DVec2, DVec3, Vec2, Vec3};
use rayon::prelude::*;

/// One face's patch: 31 f32 words, aligned to cache lines so that a patch spans two of them.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub struct FacePatch {
    /// UV of corner 0, the origin of the offset `d`.
    pub uv0: [f32; 2],
    /// Chart of the face; -1 for a face without a parameterisation (never evaluated).
    pub chart: i32,
    /// Area element `J` (object area per uv area).
    pub area_element: f32,
    /// Position coefficients relative to the origin: `1, du, dv, du^2, du dv, dv^2`.
    pub position: [[f32; 3]; 6],
    /// Unnormalised interpolated normal: `1, du, dv`.
    pub normal: [[f32; 3]; 3],
}

impl FacePatch {
    const EMPTY: FacePatch =
        FacePatch { uv0: [0.0; 2], chart: -1, area_element: 0.0, position: [[0.0; 3]; 6], normal: [[0.0; 3]; 3] };

    fn new(map: &FaceMap, chart: i32, origin: DVec3) -> Self {
        let (pu, pv) = (map.jacobian.pu, map.jacobian.pv);
        // Barycentric weights b_i = g_i + h_i du + k_i dv.
        let inverse = map.barycentric_map();
        let (h1, k1) = (inverse.x_axis.x, inverse.y_axis.x);
        let (h2, k2) = (inverse.x_axis.y, inverse.y_axis.y);
        let weights = [(1.0, -h1 - h2, -k1 - k2), (0.0, h1, k1), (0.0, h2, k2)];
        let mut coefficients = [map.x0 - origin, pu, pv, DVec3::ZERO, DVec3::ZERO, DVec3::ZERO];
        for (&(x, n), (g, h, k)) in map.corners().iter().zip(weights) {
            // Height s_i = c - a du - e dv; the lift adds n_i b_i s_i / 2.
            let (c, a, e) = ((x - map.x0).dot(n), pu.dot(n), pv.dot(n));
            let terms = [g * c, h * c - g * a, k * c - g * e, -h * a, -h * e - k * a, -k * e];
            for (coefficient, term) in coefficients.iter_mut().zip(terms) {
                *coefficient += 0.5 * term * n;
            }
        }
        Self {
            uv0: map.uv0.as_vec2().to_array(),
            chart,
            area_element: map.area_element as f32,
            position: coefficients.map(|c| c.as_vec3().to_array()),
            normal: [map.n0, map.nu, map.nv].map(|c| c.as_vec3().to_array()),
        }
    }

    /// Position at parametric offset `d = uv - uv0`, relative to the origin.
    #[inline]
    pub fn position_at(&self, d: Vec2) -> Vec3 {
        let c = self.position.map(Vec3::from_array);
        c[0] + c[1] * d.x + c[2] * d.y + c[3] * (d.x * d.x) + c[4] * (d.x * d.y) + c[5] * (d.y * d.y)
    }

    /// Position (relative to the origin) and unit normal at parametric offset `d`, evaluated in
    /// f64 from the f32 coefficients, so that the sum adds no rounding of its own (evaluated in
    /// f32, the shared lattice's texel points raised the clean sphere's H error by 6 %).
    pub fn point_and_normal_f64(&self, d: DVec2) -> (Vec3, Vec3) {
        let c = self.position.map(|c| Vec3::from_array(c).as_dvec3());
        let n = self.normal.map(|c| Vec3::from_array(c).as_dvec3());
        let position = c[0] + c[1] * d.x + c[2] * d.y + c[3] * (d.x * d.x) + c[4] * (d.x * d.y) + c[5] * (d.y * d.y);
        let normal = (n[0] + n[1] * d.x + n[2] * d.y).normalize_or_zero();
        (position.as_vec3(), normal.as_vec3())
    }

    /// Unit normal at parametric offset `d`.
    #[inline]
    pub fn normal_at(&self, d: Vec2) -> Vec3 {
        let c = self.normal.map(Vec3::from_array);
        (c[0] + c[1] * d.x + c[2] * d.y).normalize_or_zero()
    }
}

/// The patches of every face for one frame.
#[derive(Debug, Clone, Default)]
pub struct FacePatches {
    /// Origin of the stored positions: the centre of the frame's bounding box.
    pub origin: DVec3,
    /// One patch per face, indexed like `Topology::faces`.
    pub faces: Vec<FacePatch>,
}

impl FacePatches {
    /// The patches of `frame`.
    pub fn new(topology: &Topology, frame: &Frame) -> Self {
        let origin = bounding_box_centre(&frame.positions);
        // Collected in parallel, not filled and then overwritten: a one-thread fill of the 26 MB
        // of a 200K-face mesh's patches took 6-10 ms of the atlas.
        // A stop skips the remaining faces: the atlas checks for it before keeping them.
        let faces = (0..topology.faces.len())
            .into_par_iter()
            .map(|face| if cancel::requested() { FacePatch::EMPTY } else { patch(topology, frame, face, origin) })
            .collect();
        Self { origin, faces }
    }

    /// Recomputes the patches in place for a new frame.
    pub fn refresh(&mut self, topology: &Topology, frame: &Frame) {
        let origin = bounding_box_centre(&frame.positions);
        self.origin = origin;
        self.faces.par_iter_mut().enumerate().for_each(|(face, slot)| *slot = patch(topology, frame, face, origin));
    }
}

/// The patch of `face` (empty for a face without a parameterisation).
fn patch(topology: &Topology, frame: &Frame, face: usize, origin: DVec3) -> FacePatch {
    let map = frame.face_map(topology, face as u32);
    map.map_or(FacePatch::EMPTY, |map| FacePatch::new(&map, topology.face_chart[face], origin))
}

/// The centre of the bounding box of `positions` (the origin without positions).
fn bounding_box_centre(positions: &[DVec3]) -> DVec3 {
    let (low, high) = positions
        .par_iter()
        .fold(|| (DVec3::INFINITY, DVec3::NEG_INFINITY), |(low, high), &p| (low.min(p), high.max(p)))
        .reduce(|| (DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), (c, d)| (a.min(c), b.max(d)));
    if low.x <= high.x {
        0.5 * (low + high)
    } else {
        DVec3::ZERO
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::TriangleMesh;
    use glam::DVec2;

    /// The surface at `uv` in `face`, in absolute coordinates, as the fast path sees it.
    fn evaluate(patches: &FacePatches, face: u32, uv: DVec2) -> (DVec3, DVec3) {
        let patch = &patches.faces[face as usize];
        let d = (uv - DVec2::from_array(patch.uv0.map(f64::from))).as_vec2();
        (patch.position_at(d).as_dvec3() + patches.origin, patch.normal_at(d).as_dvec3())
    }

    /// The patches reproduce the f64 face maps (smooth position and normal) to f32 precision,
    /// inside the faces and where the lookup extrapolates just outside them.
    #[test]
    fn patches_evaluate_the_smooth_surface_of_the_face_maps() {
        let torus = crate::shapes::torus(2.0, 0.5, 24, 12);
        let mesh = TriangleMesh::new(&torus.positions, &torus.faces, &torus.uvs, &torus.uv_faces).unwrap();
        let topology = Topology::build(&mesh, 0.0).unwrap();
        let frame = Frame::new(&topology, &mesh.positions).unwrap();
        let patches = FacePatches::new(&topology, &frame);
        let mut worst: f64 = 0.0;
        for f in 0..topology.faces.len() {
            let map = frame.face_map(&topology, f as u32).unwrap();
            let uv = topology.corner_uvs(f);
            for (b1, b2) in [(0.2, 0.3), (0.0, 0.0), (0.6, 0.5), (-0.1, 0.4)] {
                let at = uv[0] * (1.0 - b1 - b2) + uv[1] * b1 + uv[2] * b2;
                let (position, normal) = evaluate(&patches, f as u32, at);
                worst = worst.max((position - map.smooth_position(at)).length());
                assert!((normal - map.normal(at)).length() < 1e-5);
            }
            assert_eq!(patches.faces[f].chart, topology.face_chart[f]);
        }
        assert!(worst < 2e-6, "{worst}");
    }
}
