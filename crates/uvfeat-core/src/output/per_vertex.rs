//! Per-vertex values (DESIGN.md §1.9): chart-masked bilinear lookup of the feature maps at every corner
//! UV of a vertex, averaged over its corners; direct evaluation where no texel is usable.

use super::feature_map::FeatureMaps;
use crate::atlas::Atlas;
use crate::evaluation::{evaluate_point, prepare, Patterns};
use crate::features::CurvatureMethod;
use crate::mesh::NO_CORNER;
use crate::sampling::Placement;
use crate::settings::{ComputeSettings, VertexQuery};
use glam::DVec2;
use rayon::prelude::*;

/// Distinct `(uv, chart)` corners of every geometric vertex: the atlas corners, which are
/// numbered in order of their vertex, so vertex `g` has corners `offsets[g]..offsets[g + 1]`.
/// (Flat, not a list per vertex: those lists took 140 bytes per vertex, the peak of a 5M-face run.)
fn corners(atlas: &Atlas) -> (Vec<usize>, Vec<(DVec2, i32)>) {
    let topology = &atlas.topology;
    let mut corners = vec![(DVec2::ZERO, -1); topology.n_corners];
    let mut counts = vec![0usize; topology.n_geometric() + 1];
    for (((tri, walk), &chart), groups) in
        topology.faces.iter().zip(&topology.walk_faces).zip(&topology.face_chart).zip(&topology.corner_groups)
    {
        for k in (0..3).filter(|&k| groups[k] != NO_CORNER) {
            let corner = &mut corners[groups[k] as usize];
            if corner.1 < 0 {
                *corner = (walk.corners[k], chart);
                counts[tri[k] as usize + 1] += 1;
            }
        }
    }
    let mut offsets = counts;
    for g in 1..offsets.len() {
        offsets[g] += offsets[g - 1];
    }
    (offsets, corners)
}

/// Bilinear lookup of every map at `uv`, using only texels of `chart` with accepted samples.
/// `None` when no such texel is among the four nearest.
fn lookup(maps: &FeatureMaps, uv: DVec2, chart: i32) -> Option<Vec<f64>> {
    let w = maps.resolution as i64;
    let (x, y) = (uv.x * w as f64 - 0.5, uv.y * w as f64 - 0.5);
    let (i0, j0) = (x.floor() as i64, y.floor() as i64);
    let (fx, fy) = (x - i0 as f64, y - j0 as f64);
    let mut sums = vec![0.0; maps.values.len()];
    let mut weights = vec![0.0; maps.values.len()];
    let mut any = false;
    for (di, dj, weight) in
        [(0, 0, (1.0 - fx) * (1.0 - fy)), (1, 0, fx * (1.0 - fy)), (0, 1, (1.0 - fx) * fy), (1, 1, fx * fy)]
    {
        let (i, j) = (i0 + di, j0 + dj);
        if i < 0 || j < 0 || i >= w || j >= w {
            continue;
        }
        let t = (j * w + i) as usize;
        if maps.chart[t] != chart || maps.n_valid[t] == 0 {
            continue;
        }
        any = true;
        for (f, map) in maps.values.iter().enumerate() {
            let v = f64::from(map[t]);
            if v.is_finite() {
                sums[f] += weight * v;
                weights[f] += weight;
            }
        }
    }
    any.then(|| sums.iter().zip(&weights).map(|(s, w)| if *w > 0.0 { s / w } else { f64::NAN }).collect())
}

/// Per-vertex values of every map, one `Vec` per feature with one value per *input* vertex
/// (vertices the file split at seams get the value of their welded vertex).
pub fn per_vertex(atlas: &Atlas, maps: &FeatureMaps, settings: &ComputeSettings, query: VertexQuery) -> Vec<Vec<f32>> {
    let (offsets, corners) = corners(atlas);
    let patterns = Patterns::new(settings);
    prepare(atlas, settings);
    let n_features = maps.features.len();
    let mut geometric = vec![f64::NAN; (offsets.len() - 1) * n_features];
    geometric.par_chunks_mut(n_features.max(1)).enumerate().for_each_init(Vec::new, |scratch, (vertex, out)| {
        let list = &corners[offsets[vertex]..offsets[vertex + 1]];
        let mut found: Vec<Vec<f64>> = Vec::new();
        if query == VertexQuery::Texture {
            found.extend(list.iter().filter_map(|&(uv, chart)| lookup(maps, uv, chart)));
        }
        if found.is_empty() {
            let placement = Placement::of_vertex(vertex as u32, settings.seed);
            found.extend(list.iter().map(|&(uv, _)| {
                let result = evaluate_point(atlas, uv, placement, settings, &patterns, scratch);
                maps.features.iter().map(|f| f64::from(result.values[f.index()])).collect()
            }));
        }
        for (f, slot) in out.iter_mut().enumerate() {
            let finite: Vec<f64> = found.iter().map(|v| v[f]).filter(|x| x.is_finite()).collect();
            if !finite.is_empty() {
                *slot = finite.iter().sum::<f64>() / finite.len() as f64;
            }
        }
    });
    let ids = &atlas.topology.vertex_ids;
    (0..n_features).map(|f| ids.iter().map(|&g| geometric[g as usize * n_features + f] as f32).collect()).collect()
}

/// Every atlas corner's UV and geometric vertex and, per feature, its chart-masked bilinear
/// lookup (the value [`per_vertex`] averages over a vertex's corners; NaN where no texel of the
/// corner's chart with samples is among the four nearest): what a texture read at that UV should
/// give, which a bake's gutters are fitted to.
pub fn per_corner(atlas: &Atlas, maps: &FeatureMaps) -> (Vec<DVec2>, Vec<u32>, Vec<Vec<f32>>) {
    let (offsets, corners) = corners(atlas);
    let values: Vec<Option<Vec<f64>>> = corners.par_iter().map(|&(uv, chart)| lookup(maps, uv, chart)).collect();
    let per_feature = (0..maps.features.len())
        .map(|f| values.iter().map(|v| v.as_ref().map_or(f32::NAN, |v| v[f] as f32)).collect())
        .collect();
    let vertex =
        offsets.windows(2).enumerate().flat_map(|(g, range)| std::iter::repeat_n(g as u32, range[1] - range[0]));
    (corners.iter().map(|&(uv, _)| uv).collect(), vertex.collect(), per_feature)
}

/// Principal directions `[d1, d2]` of the quadric fit at every *input* vertex, evaluated directly
/// at one corner UV of the vertex (a line field has no sign, so texels cannot be averaged
/// bilinearly like scalar maps); NaN where the fit failed.
pub fn per_vertex_directions(atlas: &Atlas, settings: &ComputeSettings) -> Vec<[[f32; 3]; 2]> {
    let settings = ComputeSettings { method: CurvatureMethod::Fit, standard_errors: false, ..settings.clone() };
    let patterns = Patterns::new(&settings);
    prepare(atlas, &settings);
    let (offsets, corners) = corners(atlas);
    let geometric: Vec<[[f32; 3]; 2]> = (0..offsets.len() - 1)
        .into_par_iter()
        .map_init(Vec::new, |scratch, vertex| {
            // The first corner where the fit succeeds: a corner UV on a chart's edge may fall on
            // a gutter texel of the raster, which has no centre.
            let placement = Placement::of_vertex(vertex as u32, settings.seed);
            corners[offsets[vertex]..offsets[vertex + 1]]
                .iter()
                .map(|&(uv, _)| evaluate_point(atlas, uv, placement, &settings, &patterns, scratch).directions)
                .find(|d| d[0][0].is_finite())
                .unwrap_or([[f32::NAN; 3]; 2])
        })
        .collect();
    atlas.topology.vertex_ids.iter().map(|&g| geometric[g as usize]).collect()
}
