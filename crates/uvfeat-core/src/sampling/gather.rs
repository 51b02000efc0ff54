//! Gathering a neighbourhood sample by sample (DESIGN.md §1.4, `relocation = per_sample`): each pattern
//! point is mapped onto the centre's sampling domain, relocated across seams on its own, looked
//! up, and kept when it lies in the ball.

use super::centre::Centre;
use super::domain::Domain;
use super::fast_path;
use super::located::{locate_target, located_sample};
use super::pattern::Placement;
use super::per_chart::gather_per_chart;
use super::reach::Reach;
use super::sample::{unit_ellipse_area, Sample, SampleCounts};
use super::settings::{Overlaps, SamplerSettings};
use super::sheets::keep_first_routes;
use crate::atlas::Atlas;
use crate::relocation::Relocation;
use glam::DVec2;

/// Samples the neighbourhood of `centre` with `pattern` (unit-disk points) placed by `placement` and
/// stretched per direction by `reach`. Each sample stands for `m(phi)^2 A_uv / N` of parametric
/// area (see [`Reach`]). Accepted samples are appended to `out` (no allocation once it has grown).
/// With `relocation = per_chart` the paper's per-chart repetition samples instead.
pub fn gather(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    placement: Placement,
    reach: &Reach,
    settings: &SamplerSettings,
    out: &mut Vec<Sample>,
) -> SampleCounts {
    if settings.relocation == Relocation::PerChart {
        return gather_per_chart(atlas, centre, pattern, placement, reach, settings, out);
    }
    let domain = Domain::new(centre, placement, reach, settings);
    let first = out.len();
    let mut counts = if fast_path::applies(atlas, settings) {
        fast_path::gather(atlas, centre, pattern, &domain, out)
    } else {
        gather_exact(atlas, centre, pattern, &domain, settings, out)
    };
    if settings.overlaps == Overlaps::Drop {
        let dropped = keep_first_routes(atlas, centre, pattern, &domain, settings, first, out);
        counts.valid -= dropped;
    }
    counts
}

/// The exact path: every pattern point located and evaluated on its own.
fn gather_exact(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    domain: &Domain,
    settings: &SamplerSettings,
    out: &mut Vec<Sample>,
) -> SampleCounts {
    let cell_area = unit_ellipse_area(centre, settings) / pattern.len() as f64;
    let mut counts = SampleCounts::default();
    for (pattern_index, &disk) in pattern.iter().enumerate() {
        let offset = domain.offset(disk);
        let located = locate_target(atlas, centre, centre.uv + offset.uv, settings);
        let uv_area = cell_area * offset.area_scale;
        located_sample(atlas, centre, located, uv_area, pattern_index as u32, settings, out, &mut counts);
    }
    counts
}
