//! The paper's per-chart pattern repetition (DESIGN.md §1.6, `relocation = per_chart`, GPU-friendly):
//! instead of relocating every sample that leaves the chart, the centre is carried once into each
//! chart across the seams its samples reach, and the whole pattern is evaluated again there,
//! keeping only the samples that land in that chart. One jump deep, as in the paper.
//!
//! Departure: a chart that borders itself (the seam of a latitude-longitude or torus chart) is
//! repeated across that seam too; the original contract's "excluding visited charts" (DESIGN.md
//! §1.6, D15) would drop every sample beyond such a seam. As in the paper, each chart is entered through one seam only (the border
//! texel closest to the centre), so near a corner where two seams to the same chart meet, the
//! samples beyond the farther one are lost.

use super::centre::Centre;
use super::domain::offsets;
use super::pattern::Placement;
use super::reach::Reach;
use super::sample::{accept, unit_ellipse_area, Candidate, Sample, SampleCounts};
use super::settings::SamplerSettings;
use crate::atlas::Atlas;
use crate::relocation::{border_texel, last_inside};
use glam::DVec2;

/// Charts one neighbourhood may repeat its pattern in; samples leading to further charts are
/// counted missing.
const MAX_CHARTS: usize = 8;

/// A chart reached across a seam, through the border texel closest to the centre.
#[derive(Debug, Clone, Copy)]
struct Mark {
    side: usize,
    distance2: f64,
}

/// Per-chart repetition of `pattern` around `centre` (see the module documentation); counts and
/// weights as in [`super::gather`].
pub fn gather_per_chart(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    placement: Placement,
    reach: &Reach,
    settings: &SamplerSettings,
    out: &mut Vec<Sample>,
) -> SampleCounts {
    let cell_area = unit_ellipse_area(centre, settings) / pattern.len() as f64;
    let mut counts = SampleCounts::default();
    let mut marks: [Option<(i32, Mark)>; MAX_CHARTS] = [None; MAX_CHARTS];
    for (pattern_index, offset) in offsets(centre, pattern, placement, reach, settings).enumerate() {
        let target = centre.uv + offset.uv;
        if atlas.chart_at(target) == centre.chart {
            let Some(point) = settings.lookup.surface_point(atlas, target, centre.chart) else {
                counts.missing += 1;
                continue;
            };
            let uv_area = cell_area * offset.area_scale;
            let candidate =
                Candidate { point, uv_area, own_chart_uv: Some(target), pattern_index: pattern_index as u32 };
            counts.valid += u32::from(accept(atlas, centre, candidate, settings, out));
            continue;
        }
        let Some(texel) = exit_texel(atlas, centre, target) else {
            counts.missing += 1;
            continue;
        };
        let side = atlas.coverage().border_side[texel] as usize;
        if atlas.seam_maps()[side].is_none() {
            counts.border += 1;
            continue;
        }
        let chart = atlas.topology.sides[side].adjacent_chart;
        let distance2 = atlas.texel_centre(texel).distance_squared(centre.uv);
        if !mark(&mut marks, chart, Mark { side, distance2 }) {
            counts.missing += 1;
        }
    }
    for (chart, m) in marks.iter().flatten() {
        let Some(map) = atlas.seam_maps()[m.side] else { continue };
        let carried = map.apply(centre.uv);
        let uv_scale = map.m.determinant().abs() * cell_area;
        for (pattern_index, offset) in offsets(centre, pattern, placement, reach, settings).enumerate() {
            let target = carried + map.m * offset.uv;
            if atlas.chart_at(target) != *chart {
                continue;
            }
            let Some(point) = settings.lookup.surface_point(atlas, target, *chart) else { continue };
            let uv_area = uv_scale * offset.area_scale;
            let candidate = Candidate { point, uv_area, own_chart_uv: None, pattern_index: pattern_index as u32 };
            counts.valid += u32::from(accept(atlas, centre, candidate, settings, out));
        }
    }
    counts
}

/// The border texel where the march from the centre towards `target` first leaves the chart
/// (DESIGN.md §1.5's march, stopped at its first crossing).
fn exit_texel(atlas: &Atlas, centre: &Centre, target: DVec2) -> Option<usize> {
    let last_inside = last_inside(atlas, centre.uv, target, centre.chart).unwrap_or(target);
    let texel = border_texel(atlas, last_inside, centre.chart)?;
    (atlas.coverage().border_side[texel] >= 0).then_some(texel)
}

/// Keeps the closest mark per chart; `false` when the table is full.
fn mark(marks: &mut [Option<(i32, Mark)>; MAX_CHARTS], chart: i32, new: Mark) -> bool {
    for slot in marks.iter_mut() {
        match slot {
            Some((c, old)) if *c == chart => {
                if new.distance2 < old.distance2 {
                    *old = new;
                }
                return true;
            }
            None => {
                *slot = Some((chart, new));
                return true;
            }
            Some(_) => {}
        }
    }
    false
}
