//! The metric of the surface at the scale of the ball, for the shared lattice's plane (DESIGN.md
//! §1.4.7).
//!
//! A face's own metric is that of its flat triangle. On a rough surface (a scan's noise along the
//! normals) the triangles are tilted against the surface they sample, so they are longer than it:
//! at the scale of the ball the surface is stretched less than its faces say. The centre's ellipse
//! then falls short of the ball, most texels' balls reach the rim of their disks and sum a second,
//! grown lattice (the noisy 200K torus of docs/PEERS.md: 199K of 242K texels at r = 2 %).

use super::centre::Centre;
use super::located::locate_target;
use super::settings::SamplerSettings;
use crate::atlas::Atlas;
use crate::distortion::Distortion;
use crate::relocation::Located;
use glam::{DVec2, DVec3};

/// Fraction of `r` the chords reach on either side of the centre: far enough to average a scan's
/// noise over a few faces, near enough that round a lat-long pole the chord along a circle of
/// latitude does not wrap.
const REACH: f64 = 0.5;

/// Smallest ratio of a secant stretch to the face's: below it the chords folded (a thin part, a
/// wrapped circle of latitude) rather than smoothed.
const SMALLEST_RATIO: f64 = 0.4;

/// Largest ratio of the secant's larger stretch to the face's: chords are never longer than the
/// surface between their ends, so more means the ends were reached round a seam elsewhere.
const LARGEST_RATIO: f64 = 1.1;

/// The metric at `centre` from the chords between the surface points `REACH r` away on either side
/// of it along `u`, `v` and their diagonal (measured in the face's metric): `E = |P(s + a e_u) -
/// P(s - a e_u)|^2 / (2a)^2`, `G` likewise, `F` from the diagonal's chord less `E` and `G`. `None`
/// where an end is off the surface, the chords are degenerate, or the stretches leave the face's by
/// more than the ratios above (then the face's metric serves).
pub fn secant_distortion(atlas: &Atlas, centre: &Centre, settings: &SamplerSettings) -> Option<Distortion> {
    let face = centre.distortion;
    let [e, _, g] = face.metric();
    let (du, dv) = (REACH * settings.radius / e.sqrt(), REACH * settings.radius / g.sqrt());
    let point = |offset: DVec2| -> Option<DVec3> {
        match locate_target(atlas, centre, centre.uv + offset, settings) {
            Located::Inside { chart, uv, face, .. } => {
                settings.lookup.evaluate(atlas, face, uv, chart).map(|point| point.position)
            }
            Located::Border | Located::Missing => None,
        }
    };
    let half_chord2 = |offset: DVec2| Some(point(offset)?.distance_squared(point(-offset)?) / 4.0);
    let e = half_chord2(DVec2::new(du, 0.0))? / (du * du);
    let g = half_chord2(DVec2::new(0.0, dv))? / (dv * dv);
    let f = (half_chord2(DVec2::new(du, dv))? - du * du * e - dv * dv * g) / (2.0 * du * dv);
    if !(e > 0.0 && g > 0.0 && e * g - f * f > 0.0) {
        return None;
    }
    let secant = Distortion::from_metric([e, f, g]);
    let within = secant.sigma1 >= SMALLEST_RATIO * face.sigma1
        && secant.sigma2 >= SMALLEST_RATIO * face.sigma2
        && secant.sigma1 <= LARGEST_RATIO * face.sigma1;
    within.then_some(secant)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::Feature;
    use crate::lookup::Lookup;
    use crate::mesh::{Topology, TriangleMesh};
    use crate::sampling::{centre_at, pcg_hash};
    use crate::settings::ComputeSettings;
    use crate::shapes::{plane, ShapeMesh};
    use crate::AtlasOptions;
    use std::sync::Arc;

    fn atlas(shape: &ShapeMesh) -> Atlas {
        let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
        let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
        Atlas::new(topology, &mesh.positions, &AtlasOptions { resolution: 512, ..Default::default() }).unwrap()
    }

    #[test]
    fn on_a_rough_plane_the_secant_metric_is_the_plane_s_and_the_face_s_is_longer() {
        // A unit plane of 64 x 64 quads laid out on 0.96 of the unit square (stretch 1 / 0.96),
        // its vertices moved along the normal by up to half an edge.
        let mut shape = plane(1.0, 64);
        for (k, p) in shape.positions.iter_mut().enumerate() {
            p[2] = (f64::from(pcg_hash(k as u32)) / f64::from(u32::MAX) - 0.5) / 64.0;
        }
        let atlas = atlas(&shape);
        let settings = ComputeSettings::new(vec![Feature::MeanCurvature], 0.1).sampler();
        let stretch = 1.0 / 0.96;
        let (mut faces, mut secants) = (Vec::new(), Vec::new());
        for k in 0..20 {
            let uv = DVec2::new(0.3 + 0.02 * f64::from(k), 0.45 + 0.005 * f64::from(k));
            let centre = centre_at(&atlas, uv, Lookup::default()).unwrap();
            let secant = secant_distortion(&atlas, &centre, &settings).unwrap();
            faces.push(centre.distortion.area_element().sqrt() / stretch);
            secants.push(secant.area_element().sqrt() / stretch);
            assert!((secant.sigma1 / stretch - 1.0).abs() < 0.03 && (secant.sigma2 / stretch - 1.0).abs() < 0.03);
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        assert!(mean(&faces) > 1.05, "the faces' stretch {:.3} of the plane's", mean(&faces));
        assert!((mean(&secants) - 1.0).abs() < 0.01, "the secants' stretch {:.3} of the plane's", mean(&secants));
    }

    #[test]
    fn near_a_border_the_face_metric_serves() {
        let atlas = atlas(&plane(1.0, 32));
        let settings = ComputeSettings::new(vec![Feature::MeanCurvature], 0.1).sampler();
        let centre = centre_at(&atlas, DVec2::new(0.03, 0.5), Lookup::default()).unwrap();
        assert_eq!(secant_distortion(&atlas, &centre, &settings), None);
    }
}
