//! A neighbourhood's sums straight from the surfels (DESIGN.md §1.4.9): the integral estimators'
//! moments of each surfel summed over the ball's connected part, with no sample list.
//!
//! The flat surfel quadrature (DESIGN.md §1.4.8) turns each surfel into a sample at its centroid.
//! H reads two moments, `dA (q - p)` (its numerator), which a surfel's area and centroid give
//! exactly, and `dA |q - p|^2` (its denominator), which the surfel's spread about its centroid
//! adds exactly (`area |c - p|^2 + spread`). K's moments and the volumes' `dA rho` are read at the
//! centroid. The level and the ramp are the flat quadrature's ([`SurfelBall`]).
//!
//! The search runs over the level's adjacency from the centre's surfel while the centroids are
//! inside the ball, so the neighbourhood is the ball's connected part, as the flat quadrature's
//! and the object-space reference's; a linear ramp one surfel wide weighs a plane's disk exactly.

use super::{NeighbourhoodStats, StatsSettings};
use crate::atlas::Atlas;
use crate::distortion::Distortion;
use crate::raster::{Surface, SurfelLevel, SurfelPoint};
use crate::sampling::{SampleCounts, SurfelBall};
use glam::{DVec2, DVec3};

/// Where a neighbourhood is centred: a surface point, its unit normal, where it lies in the atlas
/// and the object length of one texel there.
#[derive(Debug, Clone, Copy)]
pub struct SurfelCentre {
    /// Position `p`.
    pub position: DVec3,
    /// Unit normal `n`.
    pub normal: DVec3,
    /// Parametric point of `p` in `chart`.
    pub uv: DVec2,
    /// Chart of `uv`.
    pub chart: i32,
    /// Object length of one texel of the atlas at `p` along its longer side (the largest
    /// singular value of the parametrisation over `W`): a stretched chart's surfels, longer than
    /// wide, take a finer level, as the flat quadrature's.
    pub texel_length: f64,
    /// Object length of one texel's side for its area: `sqrt(sigma_1 sigma_2) / W` (the ramp's
    /// width, as the flat quadrature's).
    pub texel_side: f64,
}

impl SurfelCentre {
    /// The centre at `position` with unit `normal`, at `uv` of `chart`, where the atlas of
    /// `resolution`² texels has the sampler's metric `distortion`.
    pub fn new(
        position: DVec3,
        normal: DVec3,
        uv: DVec2,
        chart: i32,
        distortion: &Distortion,
        resolution: usize,
    ) -> Self {
        let w = resolution as f64;
        Self {
            position,
            normal,
            uv,
            chart,
            texel_length: distortion.sigma1 / w,
            texel_side: distortion.area_element().sqrt() / w,
        }
    }
}

/// What the sums read besides the centre.
#[derive(Debug, Clone, Copy)]
pub struct SurfelSumSettings {
    /// Radius and the estimators' weights.
    pub stats: StatsSettings,
    /// Surface the surfels lie on.
    pub surface: Surface,
    /// Sum the samples' normals (bending energy).
    pub with_normals: bool,
}

/// The sums of the ball's connected part around `centre`, with their sample counts (`valid`:
/// surfels summed; `border`: those in the ball a mesh border passes through). Empty sums where the
/// centre's texel holds no surfel of its chart.
pub fn surfel_sums(
    atlas: &Atlas,
    centre: &SurfelCentre,
    settings: &SurfelSumSettings,
) -> (NeighbourhoodStats, SampleCounts) {
    let surfels = atlas.surfels(settings.surface);
    let mut stats = NeighbourhoodStats::default();
    let mut counts = SampleCounts::default();
    let r = settings.stats.radius;
    let texels = (centre.texel_length, centre.texel_side);
    let Some(search) = SurfelBall::new(atlas, surfels, (centre.uv, centre.chart), texels, r) else {
        return (stats, counts);
    };
    let (inner, outer) = search.ramp;
    let ball =
        Ball { p: centre.position, n: centre.normal, outer, inverse_ramp: 1.0 / (outer - inner), inverse_r: 1.0 / r };
    let level = &surfels.levels[search.level];
    search
        .search(level, centre.position, |s, distance| ball.add(&mut stats, &mut counts, level, s, distance, settings));
    (stats, counts)
}

/// The ball and its ramp, seen from the centre.
struct Ball {
    p: DVec3,
    n: DVec3,
    /// The ramp's weight falls from 1 one surfel width inside `outer` to 0 at `outer`.
    outer: f64,
    /// `1 / width` of the ramp.
    inverse_ramp: f64,
    /// `1 / r`.
    inverse_r: f64,
}

impl Ball {
    /// Adds surfel `s` of `level`, at `distance` from the centre, weighed by the ramp.
    #[inline]
    fn add(
        &self,
        stats: &mut NeighbourhoodStats,
        counts: &mut SampleCounts,
        level: &SurfelLevel,
        s: u32,
        distance: f64,
        settings: &SurfelSumSettings,
    ) {
        let weight = ((self.outer - distance) * self.inverse_ramp).min(1.0);
        let SurfelPoint { position, area, spread } = level.point[s as usize];
        let (area, spread) = (area * weight, spread * weight);
        if !(area > 0.0) {
            return;
        }
        let StatsSettings { radius: r, rho_min, .. } = settings.stats;
        counts.valid += 1;
        counts.border += u32::from(level.on_border[s as usize] && distance < r);
        let inverse_r = self.inverse_r;
        let height = self.n.dot(position - self.p);
        // `dA (n . (q - p))` and `dA |q - p|^2` summed exactly over the surfel.
        let elevation = area * height;
        let second = area * distance * distance + spread;
        // The surfel holding the centre keeps its area (its elevation is 0 there).
        let inverse_distance = if distance > 1e-6 * r { 1.0 / distance } else { 0.0 };
        let sin_alpha = height * inverse_distance;
        // The volumes' weight `dA rho` at the centroid (H's ratio does not read it).
        let w = area * distance;
        stats.elevation.add_parts(w, elevation, w * sin_alpha * sin_alpha);
        stats.radial.add_parts(w, second * inverse_r, second * distance * inverse_r * inverse_r);
        // The area alone (the area ratio): the surfels serve the Euclidean ball only, never the
        // geodesic-disk K (`ComputeSettings::validate`).
        stats.geodesic_disk.add(area, 0.0);
        if distance >= rho_min {
            if settings.with_normals {
                let g = (self.n - level.normal[s as usize]).length_squared() * inverse_distance * inverse_distance;
                stats.bending.add(area, g);
            }
            // `K = 3 <k>^2 - 2 <k^2>` is a difference of two moments whose centroid errors cancel
            // when both are read by the same rule: `w = dA rho^2 / r^2` at the centroid, not with
            // the spread (the 18-chart torus's K: 0.98 % of its range with it, 0.4 % without).
            let w = area * distance * distance * inverse_r * inverse_r;
            let k = -2.0 * sin_alpha * inverse_distance;
            stats.normal_curvature.add_parts(w, w * k, w * k * k);
        }
    }
}
