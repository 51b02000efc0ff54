//! The texel march of DESIGN.md §1.5 (paper §3.4, decisions A6–A8): march from the centre towards the
//! sample, and where the march leaves the chart, carry the rest of the offset across the seam with
//! the border texel's transition map.

use super::Located;
use crate::atlas::Atlas;
use crate::raster::closest_on_segment;
use glam::{DMat2, DVec2};

/// Locates `target`, an offset of `start` in chart `chart` (DESIGN.md §1.5 `locate`).
///
/// After a crossing, the march continues from the image of the crossing point (the closest point
/// of the seam edge, which the transition map carries exactly onto the other side) rather than
/// from the image of the last texel inside, which can fall just outside the new chart.
pub fn march(atlas: &Atlas, start: DVec2, chart: i32, target: DVec2, max_jumps: u32) -> Located {
    let (mut origin, mut target, mut chart) = (start, target, chart);
    let mut m_path = DMat2::IDENTITY;
    let mut jumps = 0;
    loop {
        if atlas.chart_at(target) == chart {
            return Located::Inside { chart, uv: target, m_path, jumps, face: None };
        }
        let Some(last_inside) = last_inside(atlas, origin, target, chart) else {
            return Located::Inside { chart, uv: target, m_path, jumps, face: None };
        };
        let Some(texel) = border_texel(atlas, last_inside, chart) else {
            return Located::Missing;
        };
        let side_index = atlas.coverage().border_side[texel] as usize;
        let side = &atlas.topology.sides[side_index];
        let Some(map) = atlas.seam_maps()[side_index] else {
            return Located::Border;
        };
        if jumps == max_jumps {
            return Located::Missing;
        }
        let (_, [a, b]) = atlas.topology.side_endpoints(side);
        let (_, along) = closest_on_segment(a, b, last_inside);
        origin = map.apply(a + (b - a) * along);
        target = map.apply(target);
        chart = side.adjacent_chart;
        m_path = map.m * m_path;
        jumps += 1;
    }
}

/// The last point of the march from `origin` towards `target` in one-texel steps that is still
/// in `chart`, before the first step outside it (DESIGN.md §1.5); `None` when no step leaves it.
pub fn last_inside(atlas: &Atlas, origin: DVec2, target: DVec2, chart: i32) -> Option<DVec2> {
    let offset = target - origin;
    let steps = (offset.abs().max_element() * atlas.resolution() as f64).ceil().max(1.0);
    let step = offset / steps;
    let exit = first_exit(atlas, origin, step, steps as usize, chart)?;
    Some(origin + step * (exit - 1) as f64)
}

/// First `k` in `1..=steps` with `origin + k step` outside `chart` (DESIGN.md §1.5 march), skipping
/// ahead by the chart distance of the current texel: the points skipped are provably inside.
fn first_exit(atlas: &Atlas, origin: DVec2, step: DVec2, steps: usize, chart: i32) -> Option<usize> {
    let coverage = atlas.coverage();
    let mut k = 0;
    loop {
        let here = atlas.texel_coordinates(origin + step * k as f64);
        let skip = here
            .filter(|&(i, j)| coverage.chart[j * coverage.resolution + i] == chart)
            .map_or(1, |(i, j)| coverage.chart_distance.at(i, j).max(2) - 1);
        k += usize::from(skip);
        if k > steps {
            return None;
        }
        if atlas.chart_at(origin + step * k as f64) != chart {
            return Some(k);
        }
    }
}

/// The border texel of `chart` at `uv`, else the one of its 3x3 neighbourhood closest to `uv`.
pub fn border_texel(atlas: &Atlas, uv: DVec2, chart: i32) -> Option<usize> {
    let coverage = atlas.coverage();
    atlas.nearest_texel(uv, |t| coverage.chart[t] == chart && coverage.border_side[t] >= 0)
}

/// A parametric point carried across a seam.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// Chart on the other side.
    pub chart: i32,
    /// The point in that chart's parametric frame.
    pub uv: DVec2,
    /// Linear part of the transition map used.
    pub m: DMat2,
    /// Boundary side whose map was used; its `reverse` side maps back exactly.
    pub side: usize,
}

/// Maps `uv`, which must lie in (or next to) a border texel of `chart` with a seam across, to the
/// chart on the other side with that texel's transition map (DESIGN.md §1.3.4 `ADJ`).
pub fn cross_seam(atlas: &Atlas, uv: DVec2, chart: i32) -> Option<Crossing> {
    let texel = border_texel(atlas, uv, chart)?;
    let side = atlas.coverage().border_side[texel] as usize;
    let map = atlas.seam_maps()[side]?;
    Some(Crossing { chart: atlas.topology.sides[side].adjacent_chart, uv: map.apply(uv), m: map.m, side })
}
