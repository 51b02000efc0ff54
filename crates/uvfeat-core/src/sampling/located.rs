//! From a located pattern point to a sample: the surface point where a parametric target reached
//! from the centre lies (DESIGN.md §1.5 `locate`, then the lookup), tested against the ball and
//! counted. Shared by the exact loop of `gather.rs` and the points the fast path hands over.

use super::centre::Centre;
use super::sample::{accept, is_inside, Candidate, Sample, SampleCounts};
use super::settings::SamplerSettings;
use crate::atlas::Atlas;
use crate::lookup::SurfacePoint;
use crate::relocation::{locate_with, Located};
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

/// A surface point in the ball `S(p, r)`, reached at a parametric target by a probe of the
/// coverage check.
pub struct Probed {
    /// `|q - p|`.
    pub distance: f64,
    /// Where `q` lies in the centre's chart when the path to it crossed seams and came back into
    /// that chart at a point the straight segment from the centre reaches without a crossing:
    /// the same surface point seen directly (around a tube, for instance).
    pub returned_uv: Option<DVec2>,
}

/// The surface point reached at `target` when it lies in the ball `S(p, r)`; `None` outside it or
/// off the surface (a mesh border or a failed relocation ends the neighbourhood there too).
pub fn probe_inside(atlas: &Atlas, centre: &Centre, target: DVec2, settings: &SamplerSettings) -> Option<Probed> {
    let located = locate_target(atlas, centre, target, settings);
    let returned_uv = match located {
        Located::Inside { chart, uv, jumps, .. } if jumps > 0 && chart == centre.chart => Some(uv),
        _ => None,
    };
    let Reached::Surface { point, .. } = reached(atlas, centre, located, settings) else {
        return None;
    };
    let offset = point.position - centre.position;
    let distance = offset.length();
    if !is_inside(distance, centre.normal.dot(offset) / distance.max(f64::MIN_POSITIVE), settings) {
        return None;
    }
    let seen_directly =
        |uv: &DVec2| matches!(locate_target(atlas, centre, *uv, settings), Located::Inside { jumps: 0, .. });
    Some(Probed { distance, returned_uv: returned_uv.filter(seen_directly) })
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
