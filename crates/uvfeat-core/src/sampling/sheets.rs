//! Each surface point of a neighbourhood counted once. Across seams the sampling domain is carried
//! by the seams' hinge maps, which develop the surface into the centre's parametric plane: around
//! a convex region the developed domain overlaps itself (angle deficit), so a chart can be reached
//! along two routes that cover the same surface. Every route into a chart is an affine map from
//! the centre's plane, a *sheet*; a sample is kept only when no sheet of its chart with fewer seam
//! crossings (or as many, with a smaller key) reaches the same point.

use super::centre::Centre;
use super::domain::Domain;
use super::located::locate_target;
use super::sample::Sample;
use super::settings::SamplerSettings;
use crate::atlas::Atlas;
use crate::relocation::Located;
use glam::{DMat2, DVec2};

/// An affine map `u = m x + shift` from the centre's parametric plane into `chart`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Sheet {
    chart: i32,
    m: DMat2,
    shift: DVec2,
    jumps: u32,
}

impl Sheet {
    fn same(&self, other: &Sheet) -> bool {
        self.chart == other.chart
            && (self.m - other.m).to_cols_array().iter().all(|d| d.abs() < 1e-9)
            && (self.shift - other.shift).abs().max_element() < 1e-9
    }

    /// Orders the routes into one chart: fewer crossings first, then by the map's shift.
    fn precedes(&self, other: &Sheet) -> bool {
        (self.jumps, self.shift.x, self.shift.y) < (other.jumps, other.shift.x, other.shift.y)
    }
}

/// Drops the samples of `out[first..]` whose surface point a preceding sheet of their chart also
/// reaches, and returns how many; `pattern` is the pattern the samples' `pattern_index` refers to.
pub(super) fn keep_first_routes(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    domain: &Domain,
    settings: &SamplerSettings,
    first: usize,
    out: &mut Vec<Sample>,
) -> u32 {
    let identity = Sheet { chart: centre.chart, m: DMat2::IDENTITY, shift: centre.uv, jumps: 0 };
    let mut sheets = vec![identity];
    // (sample, sheet, landing uv) of the samples that crossed a seam
    let mut crossed = Vec::new();
    for (k, sample) in out[first..].iter().enumerate() {
        let offset = domain.offset(pattern[sample.pattern_index as usize]).uv;
        let Located::Inside { chart, uv, m_path, jumps, .. } =
            locate_target(atlas, centre, centre.uv + offset, settings)
        else {
            continue;
        };
        if jumps == 0 {
            continue;
        }
        let sheet = Sheet { chart, m: m_path, shift: uv - m_path * offset, jumps };
        let id = match sheets.iter().position(|s| s.same(&sheet)) {
            Some(id) => id,
            None => {
                sheets.push(sheet);
                sheets.len() - 1
            }
        };
        crossed.push((first + k, id, uv));
    }
    if sheets.len() == 1 {
        return 0;
    }
    let mut dropped = vec![false; out.len()];
    for &(index, id, uv) in &crossed {
        let own = sheets[id];
        let reached_first = sheets.iter().filter(|s| s.chart == own.chart && s.precedes(&own)).any(|s| {
            let offset = s.m.inverse() * (uv - s.shift);
            if !domain.contains(offset) {
                return false;
            }
            match locate_target(atlas, centre, centre.uv + offset, settings) {
                Located::Inside { chart, uv: there, jumps, .. } => {
                    chart == own.chart && jumps == s.jumps && (there - uv).abs().max_element() < 1e-7
                }
                _ => false,
            }
        });
        dropped[index] = reached_first;
    }
    let before = out.len();
    let mut k = 0;
    out.retain(|_| {
        k += 1;
        !dropped[k - 1]
    });
    (before - out.len()) as u32
}
