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
//! and the object-space reference's. A linear ramp one surfel wide across the ball's edge weighs
//! the surfels, centred so that the estimators' ratios see a sharp ball's moments
//! ([`moment_ramp_centre`]: every estimator the sums feed is a ratio of them); the area ratio the
//! maps report is read against the area that ramp gives a plane's disk.

use super::{NeighbourhoodStats, StatsSettings, WeightedSums};
use crate::atlas::Atlas;
use crate::distortion::Distortion;
use crate::raster::{Surface, SurfelLevel, SurfelPoint};
use crate::sampling::{moment_ramp_area, moment_ramp_centre, SampleCounts, SurfelBall, SurfelCount};
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
    /// singular value of the parametrisation over `W`): a texel stretched past 2 : 1 takes a finer
    /// level than its area asks for, as the flat quadrature's (`sampling::level_side`).
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
    /// Surfels a plane's ball is summed over, and the coarsest level it may be summed at
    /// ([`SurfelBall::new`]; the values at the vertices build only the levels their balls need,
    /// `sampling::levels_to_build`).
    pub count: SurfelCount,
}

/// The sums of the ball's connected part around `centre`, with their sample counts (`valid`:
/// surfels summed; `border`: those in the ball a mesh border passes through). Empty sums where the
/// centre's texel holds no surfel of its chart. No `sum w^2` is kept (the sums give no standard
/// errors: [`WeightedSums::standard_error`] is NaN).
pub fn surfel_sums(
    atlas: &Atlas,
    centre: &SurfelCentre,
    settings: &SurfelSumSettings,
) -> (NeighbourhoodStats, SampleCounts) {
    let surfels = atlas.surfels(settings.surface);
    let mut sums = BallSums::default();
    let r = settings.stats.radius;
    let texels = (centre.texel_length, centre.texel_side);
    let at = (centre.uv, centre.chart);
    let Some(search) = SurfelBall::new(atlas, surfels, at, texels, r, settings.count, moment_ramp_centre) else {
        return (NeighbourhoodStats::default(), SampleCounts::default());
    };
    let (inner, outer) = search.ramp;
    let width = outer - inner;
    let ball = Ball {
        p: centre.position,
        n: centre.normal,
        outer,
        inverse_ramp: 1.0 / width,
        inverse_r2: 1.0 / (r * r),
        r,
        rho_min: settings.stats.rho_min,
    };
    let level = surfels.level(search.level);
    if settings.with_normals {
        search.search(level, centre.position, |s, distance| ball.add::<true>(&mut sums, level, s, distance));
    } else {
        search.search(level, centre.position, |s, distance| ball.add::<false>(&mut sums, level, s, distance));
    }
    // The area ratio is read against the area the moments' ramp gives a plane's disk.
    (sums.stats(r, 1.0 / moment_ramp_area(width / r)), sums.counts)
}

/// The ball and its ramp, seen from the centre.
struct Ball {
    p: DVec3,
    n: DVec3,
    /// The moments' ramp falls from 1 one surfel width inside `outer` to 0 at `outer`.
    outer: f64,
    /// `1 / width` of the ramp.
    inverse_ramp: f64,
    /// `1 / r^2`.
    inverse_r2: f64,
    r: f64,
    /// Inner exclusion of the curvature moments and bending.
    rho_min: f64,
}

/// The estimators' sums over a ball, only those the surfels feed (few enough to stay in registers:
/// the sums are half the time of a ball).
#[derive(Default)]
struct BallSums {
    /// `sum dA rho`: the volumes' weight (elevation and radial alike).
    volume_weight: f64,
    /// `sum dA n.(q - p)` and `sum dA rho sin^2(alpha)`.
    elevation: (f64, f64),
    /// `sum dA |q - p|^2` and `sum dA rho |q - p|^2`.
    radial: (f64, f64),
    /// `sum dA`.
    area: f64,
    /// `sum w`, `sum w k`, `sum w k^2` of the curvature moments (`w = dA rho^2 / r^2`).
    curvature: (f64, f64, f64),
    /// `sum dA`, `sum dA g` and `sum dA g^2` of the bending integrand.
    bending: (f64, f64, f64),
    counts: SampleCounts,
}

impl BallSums {
    /// The sums as the estimators read them (`w2` left 0), the area scaled by `area_scale`.
    fn stats(&self, r: f64, area_scale: f64) -> NeighbourhoodStats {
        let inverse_r = 1.0 / r;
        let sums = |w, wg, wg2| WeightedSums { w, w2: 0.0, wg, wg2 };
        NeighbourhoodStats {
            elevation: sums(self.volume_weight, self.elevation.0, self.elevation.1),
            radial: sums(self.volume_weight, self.radial.0 * inverse_r, self.radial.1 * inverse_r * inverse_r),
            bending: sums(self.bending.0, self.bending.1, self.bending.2),
            normal_curvature: sums(self.curvature.0, self.curvature.1, self.curvature.2),
            // The area alone (the area ratio): the surfels serve the Euclidean ball only, never the
            // geodesic-disk K (`ComputeSettings::validate`).
            geodesic_disk: sums(self.area * area_scale, 0.0, 0.0),
        }
    }
}

impl Ball {
    /// Adds surfel `s` of `level`, at `distance` from the centre, weighed by the ramp (and its
    /// normal's bending integrand `WITH_NORMALS`).
    #[inline]
    fn add<const WITH_NORMALS: bool>(&self, sums: &mut BallSums, level: &SurfelLevel, s: u32, distance: f64) {
        let weight = ((self.outer - distance) * self.inverse_ramp).min(1.0);
        let SurfelPoint { position, area, spread } = level.point[s as usize];
        let (area, spread) = (area * weight, spread * weight);
        if !(area > 0.0) {
            return;
        }
        sums.counts.valid += 1;
        sums.counts.border += u32::from(distance < self.r && level.on_border[s as usize]);
        let height = self.n.dot(position - self.p);
        let distance2 = distance * distance;
        // `dA (n . (q - p))` and `dA |q - p|^2` summed exactly over the surfel.
        let elevation = area * height;
        let second = area * distance2 + spread;
        // The surfel holding the centre keeps its area (its elevation is 0 there).
        let inverse_distance2 = if distance > 1e-6 * self.r { 1.0 / distance2 } else { 0.0 };
        // The volumes' weight `dA rho` at the centroid (H's ratio does not read it), with
        // `dA rho sin^2(alpha) = dA h^2 / rho`.
        let w = area * distance;
        sums.volume_weight += w;
        sums.elevation.0 += elevation;
        sums.elevation.1 += elevation * height * distance * inverse_distance2;
        sums.radial.0 += second;
        sums.radial.1 += second * distance;
        sums.area += area;
        if distance >= self.rho_min {
            if WITH_NORMALS {
                let g = (self.n - level.normal[s as usize]).length_squared() * inverse_distance2;
                sums.bending.0 += area;
                sums.bending.1 += area * g;
                sums.bending.2 += area * g * g;
            }
            // `K = 3 <k>^2 - 2 <k^2>` is a difference of two moments whose centroid errors cancel
            // when both are read by the same rule: `w = dA rho^2 / r^2` at the centroid, not with
            // the spread (the 18-chart torus's K: 0.98 % of its range with it, 0.4 % without).
            // With `k = -2 h / rho^2`: `w k = -2 dA h / r^2`, `w k^2 = 4 dA h^2 / (r^2 rho^2)`.
            sums.curvature.0 += area * distance2 * self.inverse_r2;
            sums.curvature.1 += -2.0 * elevation * self.inverse_r2;
            sums.curvature.2 += 4.0 * elevation * height * self.inverse_r2 * inverse_distance2;
        }
    }
}
