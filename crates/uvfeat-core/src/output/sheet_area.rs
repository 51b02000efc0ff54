//! The area one sheet of the surface holds in a ball, texel by texel, in units of `pi r^2`: the
//! unit in which the several-sheets flag reads a neighbourhood's area ratio. One smooth sheet
//! holds `pi r^2` at any curvature; one rough sheet about its facets' mean roughness times that
//! ([`crate::frame::FaceMap::roughness`]). Read in `pi r^2` alone, half the texels of the noisy
//! 200K lat-long sphere of docs/PEERS.md and all of the noisy torus's held "several sheets" at
//! r = 2 %.

use crate::atlas::Atlas;
use crate::evaluation::texel_uv;
use rayon::prelude::*;

/// Per texel of the `w`² computation texture on a chart (`chart[t] >= 0`), the mean roughness of
/// the faces under the texels within about `radius` texels of it (a square window, which may take
/// in a neighbouring chart's texels); NaN off the charts. The faces are read every `radius / 2`
/// texels (25 or more a window) and at most 128 times along a side: the mean changes at the
/// ball's scale, and reading the face of every texel (random loads from the coverage) cost 2 % of
/// a 200K sphere's features. The roughness is computed here, for the faces read, and not per
/// frame: every face's was 8 % of a 200K-face `Atlas.update`.
pub fn sheet_area(atlas: &Atlas, chart: &[i32], w: usize, radius: usize) -> Vec<f32> {
    let stride = (radius / 2).max(w / 128).max(1);
    let (cells, reach) = (w.div_ceil(stride), radius.div_ceil(stride));
    let roughness: Vec<f64> = (0..cells * cells)
        .into_par_iter()
        .map(|c| {
            let at = |k: usize| (k * stride + stride / 2).min(w - 1);
            let uv = texel_uv(at(c / cells) * w + at(c % cells), w);
            let face = atlas.texel_at(uv).and_then(|texel| u32::try_from(atlas.coverage().face[texel]).ok());
            face.map_or(f64::NAN, |face| atlas.frame.face_map(&atlas.topology, face).map_or(1.0, |map| map.roughness()))
        })
        .collect();
    let sums = summed_area(&roughness, cells, |x| if x.is_nan() { 0.0 } else { x });
    let counts = summed_area(&roughness, cells, |x| if x.is_nan() { 0.0 } else { 1.0 });
    let means: Vec<f32> = (0..cells * cells)
        .into_par_iter()
        .map(|c| {
            let (i, j) = (c % cells, c / cells);
            let bounds = (
                i.saturating_sub(reach),
                j.saturating_sub(reach),
                (i + reach + 1).min(cells),
                (j + reach + 1).min(cells),
            );
            let count = window_sum(&counts, cells, bounds);
            if count > 0.0 {
                (window_sum(&sums, cells, bounds) / count) as f32
            } else {
                1.0
            }
        })
        .collect();
    (0..w * w)
        .into_par_iter()
        .map(|t| if chart[t] < 0 { f32::NAN } else { means[(t / w / stride) * cells + (t % w) / stride] })
        .collect()
}

/// The `(w + 1)`² summed-area table of `value` over the `w`² grid `grid`: entry `(j, i)` holds
/// the sum over the rows below `j` and the columns below `i`.
fn summed_area(grid: &[f64], w: usize, value: impl Fn(f64) -> f64) -> Vec<f64> {
    let mut table = vec![0.0; (w + 1) * (w + 1)];
    for j in 0..w {
        let mut row = 0.0;
        for i in 0..w {
            row += value(grid[j * w + i]);
            table[(j + 1) * (w + 1) + i + 1] = table[j * (w + 1) + i + 1] + row;
        }
    }
    table
}

/// The sum over columns `i0..i1` and rows `j0..j1` of the grid whose `(w + 1)`² summed-area
/// table is `table`.
fn window_sum(table: &[f64], w: usize, (i0, j0, i1, j1): (usize, usize, usize, usize)) -> f64 {
    table[j1 * (w + 1) + i1] - table[j0 * (w + 1) + i1] - table[j1 * (w + 1) + i0] + table[j0 * (w + 1) + i0]
}

#[cfg(test)]
mod tests {
    use super::{sheet_area, summed_area, window_sum};
    use crate::evaluation::texel_uv;
    use crate::mesh::{Topology, TriangleMesh};
    use crate::shapes::uv_sphere;
    use crate::{Atlas, AtlasOptions};
    use std::sync::Arc;

    /// The median over the charts' texels of the sheet area of a lat-long sphere whose vertices
    /// are moved along the radius by up to `noise` (relative, a fixed scatter).
    fn median_sheet_area(noise: f64) -> f32 {
        let mut shape = uv_sphere(1.0, 96, 48);
        for (k, p) in shape.positions.iter_mut().enumerate() {
            let scatter = ((k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40) as f64 / (1u64 << 24) as f64;
            *p = p.map(|x| x * (1.0 + noise * (2.0 * scatter - 1.0)));
        }
        let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
        let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
        let atlas =
            Atlas::new(topology, &mesh.positions, &AtlasOptions { resolution: 256, ..Default::default() }).unwrap();
        let w = 128;
        let chart: Vec<i32> = (0..w * w).map(|t| atlas.chart_at(texel_uv(t, w))).collect();
        let mut areas: Vec<f32> = sheet_area(&atlas, &chart, w, 6).into_iter().filter(|a| !a.is_nan()).collect();
        assert!(areas.len() > w * w / 2);
        areas.sort_by(f32::total_cmp);
        areas[areas.len() / 2]
    }

    /// One sheet of a smooth surface holds `pi r^2`; the scattered sphere's tilted facets hold
    /// more, by about the mean of `1 / cos` of their tilts (measured 1.0001 and 1.32).
    #[test]
    fn a_rough_sheet_holds_more_area_than_a_smooth_one() {
        let smooth = median_sheet_area(0.0);
        assert!((smooth - 1.0).abs() < 1e-3, "{smooth}");
        let rough = median_sheet_area(0.05);
        assert!(rough > 1.2 && rough < 3.0, "{rough}");
    }

    #[test]
    fn a_summed_area_table_sums_every_window() {
        let w = 5;
        let grid: Vec<f64> = (0..w * w).map(|k| (k * 7 % 11) as f64).collect();
        let table = summed_area(&grid, w, |x| x);
        for (i0, j0, i1, j1) in [(0, 0, 5, 5), (1, 2, 4, 3), (3, 3, 4, 4)] {
            let direct: f64 = (j0..j1).flat_map(|j| (i0..i1).map(move |i| (i, j))).map(|(i, j)| grid[j * w + i]).sum();
            assert_eq!(window_sum(&table, w, (i0, j0, i1, j1)), direct);
        }
    }
}
