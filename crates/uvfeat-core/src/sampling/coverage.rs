//! Gathering a neighbourhood whose ellipse really covers the ball. Where the metric varies strongly
//! over the neighbourhood (distorted charts), the ellipse of the centre's metric can end inside the
//! ball; samples accepted at the rim of the pattern reveal that, and the neighbourhood is gathered
//! again with a larger margin instead of being estimated over a truncated region.

use super::neighbourhood::{ellipse_area, gather, Centre, Sample, SampleCounts, SamplerSettings};
use crate::atlas::Atlas;
use glam::DVec2;

/// Largest ellipse margin the coverage check grows to.
pub const MAX_MARGIN: f64 = 4.0;

/// Pattern radius beyond which an accepted sample shows that the ellipse did not reach around the
/// ball in its direction: with a matching metric and margin `m` the ball ends at radius `1/m`.
const EDGE_RADIUS: f64 = 0.95;

/// `true` when no accepted sample came from the rim of the pattern.
fn covers_the_ball(samples: &[Sample], pattern: &[DVec2]) -> bool {
    samples.iter().all(|s| pattern[s.pattern_index as usize].length_squared() < EDGE_RADIUS * EDGE_RADIUS)
}

/// Gathers the neighbourhood of `centre` into `out` (cleared first) with `pattern` turned by `psi`;
/// with `grow`, the margin of `sampler` is raised by half until the ellipse covers the ball (or
/// reaches [`MAX_MARGIN`]). Returns the counts and the parametric ellipse area used; `sampler` keeps
/// the final margin (for a second stage).
pub fn gather_covering(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    psi: f64,
    sampler: &mut SamplerSettings,
    grow: bool,
    out: &mut Vec<Sample>,
) -> (SampleCounts, f64) {
    loop {
        out.clear();
        let area = ellipse_area(centre, sampler);
        let counts = gather(atlas, centre, pattern, psi, area / pattern.len() as f64, sampler, out);
        if !grow || sampler.margin >= MAX_MARGIN || covers_the_ball(out, pattern) {
            return (counts, area);
        }
        sampler.margin = (sampler.margin * 1.5).min(MAX_MARGIN);
    }
}
