//! Gathering a neighbourhood sample by sample (DESIGN.md §1.4, `relocation = per_sample`): each pattern
//! point is mapped onto the centre's sampling domain, relocated across seams on its own, looked
//! up, and kept when it lies in the ball.

use super::fast_path;
use super::neighbourhood::{
    accept, is_inside, unit_ellipse, unit_ellipse_area, Candidate, Centre, Sample, SampleCounts, SamplerSettings,
};
use super::pattern::Placement;
use super::per_chart::gather_per_chart;
use super::reach::Reach;
use crate::atlas::Atlas;
use crate::lookup::SurfacePoint;
use crate::relocation::{locate_with, Located, Relocation};
use glam::{DMat2, DVec2};

/// Where a parametric `target` reached from the centre lies on the surface.
enum Reached {
    Surface { point: SurfacePoint, m_path: DMat2, own_chart_uv: Option<DVec2> },
    Border,
    Missing,
}

/// Where `target`, an offset of the centre, lies (DESIGN.md §1.5 `locate` with the settings' method).
pub(super) fn locate_target(atlas: &Atlas, centre: &Centre, target: DVec2, settings: &SamplerSettings) -> Located {
    locate_with(atlas, settings.relocation, centre.uv, Some(&centre.home), centre.chart, target, settings.max_jumps)
}

fn reach_target(atlas: &Atlas, centre: &Centre, target: DVec2, settings: &SamplerSettings) -> Reached {
    reached(atlas, centre, locate_target(atlas, centre, target, settings), settings)
}

/// The surface point of a located target, looked up with the settings' lookup.
fn reached(atlas: &Atlas, centre: &Centre, located: Located, settings: &SamplerSettings) -> Reached {
    let (chart, uv, m_path, face, jumps) = match located {
        Located::Inside { chart, uv, m_path, face, jumps } => (chart, uv, m_path, face, jumps),
        Located::Border => return Reached::Border,
        Located::Missing => return Reached::Missing,
    };
    match settings.lookup.evaluate(atlas, face, uv, chart) {
        Some(point) => {
            Reached::Surface { point, m_path, own_chart_uv: (jumps == 0 && chart == centre.chart).then_some(uv) }
        }
        None => Reached::Missing,
    }
}

/// Distance `|q - p|` of the surface point `q` reached at `target` when it lies in the ball
/// `S(p, r)`; `None` outside it or off the surface (a mesh border or a failed relocation ends the
/// neighbourhood there too).
pub fn distance_inside(atlas: &Atlas, centre: &Centre, target: DVec2, settings: &SamplerSettings) -> Option<f64> {
    let Reached::Surface { point, .. } = reach_target(atlas, centre, target, settings) else {
        return None;
    };
    let offset = point.position - centre.position;
    let distance = offset.length();
    is_inside(distance, centre.normal.dot(offset) / distance.max(f64::MIN_POSITIVE), settings).then_some(distance)
}

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
    if fast_path::applies(atlas, settings) {
        return fast_path::gather(atlas, centre, pattern, &domain, out);
    }
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

/// Looks up and tests one located pattern point, whose cell stands for `uv_area` of the centre's
/// chart, and counts what happened to it.
#[allow(clippy::too_many_arguments)]
pub(super) fn located_sample(
    atlas: &Atlas,
    centre: &Centre,
    located: Located,
    uv_area: f64,
    pattern_index: u32,
    settings: &SamplerSettings,
    out: &mut Vec<Sample>,
    counts: &mut SampleCounts,
) {
    match reached(atlas, centre, located, settings) {
        Reached::Surface { point, m_path, own_chart_uv } => {
            let uv_area = m_path.determinant().abs() * uv_area;
            let candidate = Candidate { point, uv_area, own_chart_uv, pattern_index };
            counts.valid += u32::from(accept(atlas, centre, candidate, settings, out));
        }
        Reached::Border => counts.border += 1,
        Reached::Missing => counts.missing += 1,
    }
}

/// A pattern point's parametric offset from the centre and the factor `m(phi)^2` of its area.
pub(super) struct Offset {
    pub uv: DVec2,
    pub area_scale: f64,
}

/// The offsets of `pattern` placed by `placement`, stretched by `reach`, on the centre's ellipse.
pub(super) fn offsets<'a>(
    centre: &Centre,
    pattern: &'a [DVec2],
    placement: Placement,
    reach: &'a Reach,
    settings: &'a SamplerSettings,
) -> impl Iterator<Item = Offset> + 'a {
    let domain = Domain::new(centre, placement, reach, settings);
    pattern.iter().map(move |&disk| domain.offset(disk))
}

/// The sampling domain of one centre: the pattern's placement, the reach and the metric ellipse,
/// with the sampler's settings.
pub(super) struct Domain<'a> {
    pub ellipse: DMat2,
    pub placement: Placement,
    pub reach: &'a Reach,
    /// The margin of every direction when the reach is uniform.
    pub uniform: Option<f64>,
    pub settings: &'a SamplerSettings,
}

impl<'a> Domain<'a> {
    pub fn new(centre: &Centre, placement: Placement, reach: &'a Reach, settings: &'a SamplerSettings) -> Self {
        let uniform = reach.is_uniform().then(|| reach.margin(0));
        Self { ellipse: unit_ellipse(centre, settings), placement, reach, uniform, settings }
    }

    /// The offset of the pattern point `disk`.
    #[inline]
    pub fn offset(&self, disk: DVec2) -> Offset {
        let w = self.placement.place(disk);
        let margin = self.uniform.unwrap_or_else(|| self.reach.at(w.y.atan2(w.x)));
        Offset { uv: self.ellipse * (margin * w), area_scale: margin * margin }
    }
}
