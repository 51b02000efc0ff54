//! A neighbourhood summed over the atlas's surfels (DESIGN.md §1.4.8, `quadrature = "surfels"`):
//! the surfels connected to the centre inside the ball, each counted once with its exact area.
//!
//! The pattern's neighbourhood is a disk in the centre's parametric plane carried across seams by
//! hinge maps; around convex regions and round parts thinner than the ball that development
//! overlaps itself (surface counted two to five times on a scan at r = 6 %), and behind saddles
//! it leaves gaps. Surfels partition the surface, so neither happens: the neighbourhood is the
//! set of surfels reached from the centre's through neighbouring texels of a chart and across
//! seams while inside the ball, as the object-space reference's search over edges does.
//!
//! The level of the pyramid is the coarsest whose ball holds about the settings' surfels per ball
//! (`samples`, 256 by default), so the cost does not grow with the radius. A surfel's weight ramps
//! linearly over one surfel width across the ball's edge, centred so that a plane's disk weighs
//! exactly `pi r^2` (as the shared lattice's ramp, DESIGN.md §1.4.7).
//!
//! The surface summed is the triangle lookup's smooth surface through the vertex normals (DESIGN.md
//! §1.3.6), as for the pattern's samples, or with `surface = "facets"` the mesh's own facets, as
//! the object-space reference and its refinements measure them (surfels and centre alike).

use super::centre::Centre;
use super::geodesic::arc_distance;
use super::sample::{ramp_centre, Sample, SampleCounts};
use super::settings::{Criterion, SamplerSettings};
use crate::atlas::Atlas;
use crate::raster::{Surface, SurfelLevel, SurfelPoint, Surfels};
use crate::stamps::Stamps;
use glam::{DVec2, DVec3};
use std::cell::RefCell;

thread_local! {
    /// The surfels reached by the current search (per thread: no allocation per neighbourhood).
    static REACHED: RefCell<(Stamps, Vec<u32>)> = RefCell::new((Stamps::new(0), Vec::new()));
}

/// A texel stretched up to this ratio of its sides is sized by its area.
const SQUARE_STRETCH: f64 = 2.0;

/// The side of the square a texel `longer` long and `side` on the side of its area counts as in
/// the choice of a level ([`surfel_level`]): its area's, up to a stretch of [`SQUARE_STRETCH`],
/// so that a ball sums about its surfels per ball whatever the stretch of the charts of uvfeat's
/// atlas (normal cones of 45 degrees: up to `sqrt(2)`; sized by the longer side, the dragon's
/// balls summed 1.4x the surfels they asked for), and beyond it a length that keeps a stretched
/// chart's surfels (whose centroids sag below a curved surface) about as long as a square's.
pub(super) fn level_side(longer: f64, side: f64) -> f64 {
    side.max(longer / SQUARE_STRETCH.sqrt())
}

/// The pyramid level whose surfels, about `2^k / W` parametric units wide, put about `target` in
/// the ball where a finest surfel counts as a square of side `texel_side` ([`level_side`]).
pub(super) fn surfel_level(n_levels: usize, texel_side: f64, radius: f64, target: f64) -> usize {
    // A level-k surfel counts as a square of side texel_side 2^k; `target` of them fill the ball
    // when 2^k = r sqrt(pi / target) / texel_side.
    let scale = radius * (std::f64::consts::PI / target).sqrt() / texel_side;
    let widest = scale.log2().round();
    (widest.max(0.0) as usize).min(n_levels.saturating_sub(1))
}

/// The centre the surfels of `surface` are measured from: `centre` itself on the smooth surface,
/// moved onto its face's facet for `Surface::Facets` (where the lookup's lift would put it up to
/// `h^2 k / 8` off the facets, moving H by `4 delta / r^2`).
pub fn surfel_centre(atlas: &Atlas, centre: &Centre, surface: Surface) -> Option<Centre> {
    match surface {
        Surface::Smooth => Some(*centre),
        Surface::Facets => {
            let map = atlas.frame.face_map(&atlas.topology, centre.home.face)?;
            Some(Centre { position: map.position(centre.home.point), ..*centre })
        }
    }
}

/// Appends the surfels of the ball's connected part around `centre` (see [`surfel_centre`]) to
/// `out` as samples (`pattern_index` is the surfel's index in its level); `border` counts those in
/// the ball that a mesh border passes through (the neighbourhood is truncated). A ball narrower
/// than the finest surfels holds none: the features are NaN there.
pub fn gather_surfels(
    atlas: &Atlas,
    centre: &Centre,
    settings: &SamplerSettings,
    out: &mut Vec<Sample>,
) -> SampleCounts {
    let surfels = atlas.surfels(settings.surface);
    let mut counts = SampleCounts::default();
    let w = atlas.resolution() as f64;
    let texels = (centre.distortion.sigma1 / w, centre.distortion.area_element().sqrt() / w);
    let Some(ball) = SurfelBall::new(
        atlas,
        surfels,
        (centre.uv, centre.chart),
        texels,
        settings.radius,
        SurfelCount::per_ball(settings.surfels_per_ball),
        ramp_centre,
    ) else {
        return counts;
    };
    let level = surfels.level(ball.level);
    let (inner, outer) = ball.ramp;
    let r = settings.radius;
    ball.search(level, centre.position, |s, distance| {
        let SurfelPoint { position, area, .. } = level.point[s as usize];
        let offset = position - centre.position;
        // The surfel holding the centre keeps its area (its elevation is 0 there).
        let sin_alpha = if distance > 1e-6 * r { centre.normal.dot(offset) / distance } else { 0.0 };
        let geodesic = if settings.with_geodesic { arc_distance(distance, sin_alpha) } else { f64::NAN };
        if settings.criterion == Criterion::Geodesic && geodesic >= r {
            return;
        }
        let ramp = ((outer - distance) / (outer - inner)).min(1.0);
        out.push(Sample {
            position,
            normal: if settings.with_normals { level.normal[s as usize] } else { DVec3::NAN },
            area: area * ramp,
            distance,
            sin_alpha,
            geodesic,
            pattern_index: s,
        });
        counts.valid += 1;
        counts.border += u32::from(level.on_border[s as usize] && distance < r);
    });
    counts
}

/// How many surfels a ball sums.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfelCount {
    /// About this many in a plane's ball.
    pub per_ball: f64,
    /// At a level no coarser than this one (more surfels then): the levels built for the balls of
    /// a call ([`levels_to_build`]).
    pub coarsest: usize,
}

impl SurfelCount {
    /// About `per_ball` surfels, at any level.
    pub fn per_ball(per_ball: f64) -> Self {
        Self { per_ball, coarsest: usize::MAX }
    }
}

/// A ball clamped to a finer level than it asks for sums 4 times the surfels per level; the levels
/// a call builds leave at most this share of its balls' work to such balls (a coarser level of a
/// 512² pyramid costs what about a quarter of a scan's balls do).
const CLAMPED_WORK: f64 = 0.05;

/// The coarsest level to build for balls that ask for levels with `asked[k]` of them at level `k`:
/// the finest whose clamped balls add at most [`CLAMPED_WORK`] of all the balls' work.
pub fn levels_to_build(asked: &[usize]) -> usize {
    let balls: usize = asked.iter().sum();
    let extra = |built: usize| -> f64 {
        asked.iter().enumerate().skip(built + 1).map(|(k, &n)| n as f64 * (4f64.powi((k - built) as i32) - 1.0)).sum()
    };
    (0..asked.len()).find(|&built| extra(built) <= CLAMPED_WORK * balls as f64).unwrap_or(asked.len().saturating_sub(1))
}

/// Where a ball's surfels are summed: the level, the surfel of it holding the centre, and the
/// ramp across the ball's edge.
#[derive(Debug, Clone, Copy)]
pub struct SurfelBall {
    /// The level whose surfels put about the asked number in the ball.
    pub level: usize,
    /// The surfel of that level holding the centre.
    pub start: u32,
    /// Weights fall linearly from 1 at `ramp.0` to 0 at `ramp.1`: one surfel wide, centred as
    /// the caller asks ([`SurfelBall::new`]).
    pub ramp: (f64, f64),
    /// The ball's radius: the search goes on only from surfels inside it ([`SurfelBall::search`]).
    pub radius: f64,
}

impl SurfelBall {
    /// The ball of `radius` around the point `uv` of `chart`, where a finest surfel is up to
    /// `texels.0` long and `texels.1` on the side of its area (`sigma_1 / W`, `sqrt(sigma_1
    /// sigma_2) / W`), summed at the level that puts about `count.per_ball` surfels in a plane's
    /// ball (fewer only at the finest level, more where `count.coarsest` is finer). `None` where neither the point's texel nor its eight
    /// neighbours hold a surfel of its chart (the centre of a gutter texel lies just off its
    /// chart). `centring` places the ramp (its width in units of `r` to its centre):
    /// [`ramp_centre`] where the samples' areas are read (a plane's disk weighs exactly `pi r^2`),
    /// [`moment_ramp_centre`](super::moment_ramp_centre) where only ratios of their moments are.
    pub fn new(
        atlas: &Atlas,
        surfels: &Surfels,
        (uv, chart): (DVec2, i32),
        texels: (f64, f64),
        radius: f64,
        count: SurfelCount,
        centring: fn(f64) -> f64,
    ) -> Option<Self> {
        let finest = (surfels.n_levels() > 0).then(|| surfels.level(0))?;
        let texel = atlas.nearest_texel(uv, |t| finest.at(t, chart).is_some())?;
        let level = Self::asked_level(surfels.n_levels(), texels, radius, count.per_ball).min(count.coarsest);
        let start = surfels.ancestor(finest.at(texel, chart)?, level);
        let width = (texels.1 * (1u64 << level) as f64).min(0.5 * radius);
        let edge = radius * centring(width / radius);
        Some(Self { level, start, ramp: (edge - width / 2.0, edge + width / 2.0), radius })
    }

    /// The level of a pyramid of `n_levels` that a ball of `radius` around a point whose finest
    /// surfel is `texels` (as [`SurfelBall::new`]) sums about `per_ball` surfels at.
    pub fn asked_level(n_levels: usize, texels: (f64, f64), radius: f64, per_ball: f64) -> usize {
        surfel_level(n_levels, level_side(texels.0, texels.1), radius, per_ball)
    }

    /// Runs `visit(s, distance)` on every surfel `s` of `level` (this ball's) whose centroid is
    /// within the ramp's outer edge of `centre` and adjacent to the start or to a surfel connected
    /// to it through surfels inside the ball, breadth first, as the reference's search over edges.
    pub fn search(&self, level: &SurfelLevel, centre: DVec3, mut visit: impl FnMut(u32, f64)) {
        let outer = self.ramp.1;
        REACHED.with_borrow_mut(|(reached, queue)| {
            reached.reset(level.len());
            // Each neighbour is written at `len` before it is known to be new (no branch to
            // mispredict): one slot past the level's surfels takes the last such write.
            if queue.len() <= level.len() {
                queue.resize(level.len() + 1, 0);
            }
            reached.insert(self.start);
            queue[0] = self.start;
            let (mut next, mut len) = (0, 1);
            while next < len {
                let s = queue[next];
                next += 1;
                // The ring just outside the ball is a third of the surfels reached: no root for them.
                let distance2 = (level.point[s as usize].position - centre).length_squared();
                if distance2 >= outer * outer {
                    continue;
                }
                // Only surfels inside the ball lead on (the centre's always): the ramp's outer
                // half would join sheets that meet just outside the ball, such as the two sides
                // of a thin part, which the reference's search over edges keeps apart (on the
                // dragon at r = 4 %, ten such vertices 13-29 % off made 43 % of H's error).
                if distance2 < self.radius * self.radius || s == self.start {
                    for &t in level.neighbours(s) {
                        let new = reached.insert(t);
                        queue[len] = t;
                        len += usize::from(new);
                    }
                }
                visit(s, distance2.sqrt());
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_are_built_as_far_as_the_balls_clamped_below_them_cost_a_twentieth_more() {
        // One ball in a thousand asking two levels up sums 16x at the finest: kept there.
        assert_eq!(levels_to_build(&[1000, 0, 1]), 0);
        // One in ten: 15 extra balls' work per such ball at level 0, 3 at level 1; level 2 built.
        assert_eq!(levels_to_build(&[100, 0, 10]), 2);
        // A few asking one level up (3 extra each): 15 of 1,000 fit, 20 do not.
        assert_eq!(levels_to_build(&[985, 15]), 0);
        assert_eq!(levels_to_build(&[980, 20]), 1);
        assert_eq!(levels_to_build(&[]), 0);
    }

    #[test]
    fn a_texel_counts_as_the_square_of_its_area_up_to_a_stretch_of_two() {
        // 1.5 : 1 and 2 : 1 at unit area: the unit square.
        for stretch in [1.0, 1.5, 2.0] {
            assert!((level_side(f64::sqrt(stretch), 1.0) - 1.0).abs() < 1e-12, "{stretch}");
        }
        // 8 : 1 (sides sqrt(8) and 1 / sqrt(8)): a square of side 2, four times the area's.
        assert!((level_side(8.0_f64.sqrt(), 1.0) - 2.0).abs() < 1e-12);
    }
}
