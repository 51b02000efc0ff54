//! The surface the charts are grown on and projected from (DESIGN.md §1.1.1): the mesh's own where
//! it is smooth, a smoothed copy where it is rough.
//!
//! A chart's UVs need not be the projection of the surface itself, only injective: every face's
//! metric undoes the map (§1.3.3). A scan's noise folds the projection of single faces and their
//! fans, and each fold was a chart of a few faces (the noisy 200K torus of docs/PEERS.md: 3,961 of
//! its 4,228 charts had at most 20 faces); the smoothed surface projects without folds. Where the
//! surface is smooth its own projection stays: a face's UV triangle is then its shadow, whose
//! metric varies smoothly from face to face, which the sampler reads best (charting the whole
//! bunny on the smoothed surface raised its H %AE from 1.07 to 1.19).

use crate::cancel;
use crate::mesh::compressed_rows;
use glam::DVec3;
use rayon::prelude::*;

/// Angles (degrees) between a face's own and smoothed normal from which its corners start to be
/// charted on the smoothed surface, and from which they are wholly. Measured, 99th percentile of
/// the angle: the Stanford bunny 17.5°, the armadillo 23°, the dragon 48°, the noisy 200K torus 74°
/// (median 41°).
const ROUGH_FROM: f64 = 20.0;
const ROUGH_TO: f64 = 40.0;

/// Rounds of neighbour averaging of the rough parts' positions.
const POSITION_SMOOTHING_STEPS: usize = 4;

/// The positions to chart: each vertex blended from its own position towards its smoothed one by
/// its roughness, how far its faces' own normals stray from their smoothed ones (0 up to
/// [`ROUGH_FROM`], 1 from [`ROUGH_TO`] degrees; the largest of its faces'). `None` where no vertex
/// is rough: the surface is charted as it is.
pub(super) fn charted_positions(
    positions: &[DVec3],
    faces: &[[u32; 3]],
    normals: &[DVec3],
    smoothed_normals: &[DVec3],
) -> Option<Vec<DVec3>> {
    let (cos_from, cos_to) = (ROUGH_FROM.to_radians().cos(), ROUGH_TO.to_radians().cos());
    let mut roughness = vec![0.0f64; positions.len()];
    for (t, (n, s)) in faces.iter().zip(normals.iter().zip(smoothed_normals)) {
        if *n == DVec3::ZERO {
            continue;
        }
        let weight = ((cos_from - n.dot(*s)) / (cos_from - cos_to)).clamp(0.0, 1.0);
        for &v in t {
            roughness[v as usize] = roughness[v as usize].max(weight);
        }
    }
    if roughness.iter().all(|&w| w == 0.0) {
        return None;
    }
    let rings = Rings::new(positions.len(), faces);
    let mut smoothed = positions.to_vec();
    for _ in 0..POSITION_SMOOTHING_STEPS {
        if cancel::requested() {
            break;
        }
        smoothed = rings.mean(&smoothed);
    }
    Some(positions.par_iter().zip(&smoothed).zip(&roughness).map(|((p, s), &w)| p.lerp(*s, w)).collect())
}

/// Each vertex's edge neighbours, as the faces list them: each face corner names the face's other
/// two corners, so an interior edge counts twice (once per face), as do all of a closed fan's,
/// and a mean over the list weighs the ring evenly.
struct Rings {
    starts: Vec<u32>,
    neighbours: Vec<u32>,
}

impl Rings {
    fn new(n_vertices: usize, faces: &[[u32; 3]]) -> Self {
        let pairs =
            faces.iter().flat_map(|t| (0..3).flat_map(move |k| [(t[k], t[(k + 1) % 3]), (t[k], t[(k + 2) % 3])]));
        let (starts, neighbours) = compressed_rows(n_vertices, pairs);
        Self { starts, neighbours }
    }

    /// The mean of each vertex's position and its ring's, in parallel.
    fn mean(&self, positions: &[DVec3]) -> Vec<DVec3> {
        (0..positions.len())
            .into_par_iter()
            .map(|v| {
                let ring = &self.neighbours[self.starts[v] as usize..self.starts[v + 1] as usize];
                (positions[v] + ring.iter().map(|&u| positions[u as usize]).sum::<DVec3>()) / (ring.len() + 1) as f64
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::plane;

    /// The charted positions, with the mean of all face normals as every face's smoothed normal
    /// (a plane's).
    fn charted(positions: &[DVec3], faces: &[[u32; 3]]) -> Option<Vec<DVec3>> {
        let normals: Vec<DVec3> =
            faces.iter().map(|t| crate::mesh::unit_face_normal(t.map(|v| positions[v as usize]))).collect();
        let mean = normals.iter().sum::<DVec3>().normalize();
        charted_positions(positions, faces, &normals, &vec![mean; faces.len()])
    }

    fn grid() -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let shape = plane(1.0, 16);
        let positions = shape.positions.iter().map(|p| DVec3::from_array(*p)).collect();
        let faces = shape.faces.iter().map(|t| t.map(|v| v as u32)).collect();
        (positions, faces)
    }

    #[test]
    fn a_smooth_surface_is_charted_as_it_is() {
        let (positions, faces) = grid();
        assert_eq!(charted(&positions, &faces), None);
    }

    #[test]
    fn a_spike_is_charted_on_the_smoothed_surface_and_the_smooth_parts_as_they_are() {
        let (mut positions, faces) = grid();
        let spike = positions.iter().position(|p| (p.x - 0.5).abs() < 1e-9 && (p.y - 0.5).abs() < 1e-9).unwrap();
        positions[spike].z = 0.2;
        let result = charted(&positions, &faces).expect("the spike is rough");
        // Its faces tilt by about 70°: wholly smoothed, most of the way back to the plane.
        assert!(result[spike].z < 0.1, "the spike is charted at height {}", result[spike].z);
        for (v, (p, q)) in positions.iter().zip(&result).enumerate() {
            if p.truncate().distance(positions[spike].truncate()) > 0.1 {
                assert_eq!(p, q, "vertex {v}, away from the spike, moved");
            }
        }
    }
}
