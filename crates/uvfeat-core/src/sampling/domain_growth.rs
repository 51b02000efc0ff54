//! Gathering a neighbourhood whose sampling domain really covers the ball. Where the metric varies
//! strongly over the neighbourhood (near the poles of a latitude-longitude chart, across distorted
//! charts), the ellipse of the centre's metric can end inside the ball; samples accepted at the rim
//! of the pattern reveal that. The domain then grows only in the directions that need it (see
//! [`Reach`]): probes along each direction find how far the ball reaches, and the neighbourhood is
//! gathered once more instead of being estimated over a truncated region.

use super::centre::Centre;
use super::gather::gather;
use super::located::probe_inside;
use super::pattern::Placement;
use super::reach::{Reach, DIRECTIONS};
use super::sample::{unit_ellipse, Sample, SampleCounts};
use super::settings::SamplerSettings;
use crate::atlas::Atlas;
use glam::DVec2;

/// Largest margin the coverage check grows a direction to.
pub const MAX_MARGIN: f64 = 4.0;

/// Pattern radius beyond which an accepted sample shows that the domain did not reach around the
/// ball in its direction: with a matching metric and margin `m` the ball ends at radius `1/m`.
pub const EDGE_RADIUS: f64 = 0.95;

/// Factor a direction's margin grows by when its rim samples are inside the ball.
const GROWTH: f64 = 1.5;

/// Smallest growth of a probed direction, and the slack over the predicted boundary.
const MIN_GROWTH: f64 = 1.1;
const PROBE_SAFETY: f64 = 1.1;

/// Probes per direction (the prediction converges in one or two).
const MAX_PROBES: usize = 6;

/// Directions next to an accepted sample from the rim of the pattern.
fn rim_directions(samples: &[Sample], pattern: &[DVec2], placement: Placement) -> [bool; DIRECTIONS] {
    let mut marked = [false; DIRECTIONS];
    for sample in samples {
        let disk = pattern[sample.pattern_index as usize];
        if placement.placed_area_radius(disk) >= EDGE_RADIUS * EDGE_RADIUS {
            let w = placement.place(disk);
            let (below, above, _) = Reach::bracket(w.y.atan2(w.x));
            marked[below] = true;
            marked[above] = true;
        }
    }
    marked
}

/// Grows every direction's margin while the surface point at its rim is still inside the ball.
/// Along a ray the distance from `p` grows about linearly, so a rim point at distance `d < r`
/// predicts the boundary at `r / d` times its pattern radius: one or two probes usually settle a
/// direction, and the margin ends just past the ball instead of a fixed step beyond it.
///
/// Where the ball holds a whole tube (a torus's at large radii), the rim never leaves it: the ray
/// goes round the tube and comes back across a seam into the centre's chart. A direction stops
/// growing when its rim point has come back inside the domain the other directions would cover
/// with the same margin: the surface beyond is already sampled from the other side, and growing
/// on sampled it twice and walked every such sample round the tube (1.5x the time at r = 16 %).
fn probe(atlas: &Atlas, centre: &Centre, sampler: &SamplerSettings, reach: &mut Reach) {
    let ellipse = unit_ellipse(centre, sampler);
    let to_pattern = ellipse.inverse();
    for k in 0..DIRECTIONS {
        let angle = Reach::direction_angle(k);
        let direction = DVec2::new(angle.cos(), angle.sin());
        let mut margin = reach.margin(k);
        for _ in 0..MAX_PROBES {
            if margin >= MAX_MARGIN {
                break;
            }
            let target = centre.uv + ellipse * (EDGE_RADIUS * margin * direction);
            let Some(probed) = probe_inside(atlas, centre, target, sampler) else {
                break;
            };
            // Where the ray came back round to the other side of the centre, at `w`, the two
            // directions meet half-way: at half the pattern length of the loop.
            let came_back = probed
                .returned_uv
                .map(|uv| to_pattern * (uv - centre.uv))
                .filter(|w| w.length() < margin.max(reach.at(w.y.atan2(w.x))));
            if let Some(w) = came_back {
                let half_loop = 0.5 * (EDGE_RADIUS * margin + w.length()) * PROBE_SAFETY;
                margin = half_loop.clamp(reach.margin(k), margin);
                break;
            }
            let distance = probed.distance;
            let predicted = sampler.radius / distance.max(1e-3 * sampler.radius);
            margin = (margin * (predicted * PROBE_SAFETY).max(MIN_GROWTH)).min(MAX_MARGIN);
        }
        reach.set_margin(k, margin);
    }
}

/// The reach of `centre` grown from the sampler's margin where the ball reached the rim of the
/// domain in the `marked` directions: probes set each direction's margin (up to [`MAX_MARGIN`];
/// marked directions the probes left alone grow by half).
fn grown_reach(atlas: &Atlas, centre: &Centre, sampler: &SamplerSettings, marked: &[bool; DIRECTIONS]) -> Reach {
    grow_marked(probed_reach(atlas, centre, sampler), sampler, marked)
}

/// The reach of `centre` grown from the sampler's margin by the probes alone.
pub fn probed_reach(atlas: &Atlas, centre: &Centre, sampler: &SamplerSettings) -> Reach {
    let mut reach = Reach::uniform(sampler.margin);
    probe(atlas, centre, sampler, &mut reach);
    reach
}

/// `probed` (see [`probed_reach`]) with the `marked` directions the probes left alone grown by half.
pub fn grow_marked(mut probed: Reach, sampler: &SamplerSettings, marked: &[bool; DIRECTIONS]) -> Reach {
    for (k, _) in marked.iter().enumerate().filter(|(_, &m)| m) {
        if probed.margin(k) == sampler.margin {
            probed.set_margin(k, (sampler.margin * GROWTH).min(MAX_MARGIN));
        }
    }
    probed
}

/// Gathers the neighbourhood of `centre` into `out` (cleared first) with `pattern` placed by
/// `placement` and the margin of `sampler` in every direction. With `grow`, where accepted samples
/// reach the rim, the domain grows ([`grown_reach`]) and the neighbourhood is gathered once more. Returns the counts
/// and the final reach (for a second stage).
///
/// Two gathers at most: a third, for rim samples left between the probed directions, doubled the
/// time at r = 16 % of the diagonal (the ball wraps around a 100K torus's tube there and no margin
/// covers it) and changed the neighbourhood areas of a 692-chart atlas by less than their spread.
pub fn gather_covering(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    placement: Placement,
    sampler: &SamplerSettings,
    grow: bool,
    out: &mut Vec<Sample>,
) -> (SampleCounts, Reach) {
    let reach = Reach::uniform(sampler.margin);
    out.clear();
    let counts = gather(atlas, centre, pattern, placement, &reach, sampler, out);
    if !grow {
        return (counts, reach);
    }
    let marked = rim_directions(out, pattern, placement);
    if !marked.contains(&true) {
        return (counts, reach);
    }
    let before = reach;
    let reach = grown_reach(atlas, centre, sampler, &marked);
    if reach == before {
        return (counts, reach);
    }
    out.clear();
    (gather(atlas, centre, pattern, placement, &reach, sampler, out), reach)
}
