//! Sphere-volume integral invariant `V_r` (DESIGN.md §2.3; Pottmann et al. 2007/2009).

use super::open_volume::{ball_volume, open_volume};
use super::statistics::{VolumeWeighting, WeightedSums};

/// Volume of the ball of radius `r` at `p` inside the solid (opposite the normal):
/// `V_r = 4 pi r^3 / 3 - V_o`. Plane `2 pi r^3 / 3`; unit sphere (outward normals)
/// `2 pi r^3 / 3 - pi r^4 / 4`. Units length^3.
pub fn volume_invariant(
    elevation: &WeightedSums,
    radial: &WeightedSums,
    radius: f64,
    weighting: VolumeWeighting,
) -> f64 {
    ball_volume(radius) - open_volume(elevation, radial, radius, weighting)
}
