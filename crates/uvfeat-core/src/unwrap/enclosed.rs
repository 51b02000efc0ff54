//! Fragments merged into the chart around them (DESIGN.md §1.1.1).
//!
//! On a rough scan a few faces here and there still fold in every chart's projection, even on the
//! smoothed surface, and the growth leaves each such spot a chart of its own: the noisy 200K sphere
//! of docs/PEERS.md came out as 20 charts and 255 fragments of a median of 10 faces, 152 of them
//! holes in one chart. Each is a seam in the middle of a chart: the sampler's points walk round it
//! and the coverage check grows the domains near it, so that the features took 0.66 s on those
//! charts against 0.27 s on the same sphere's single lat-long chart.
//!
//! A chart's UVs need only be injective (every face's metric undoes the map, §1.3.3), so a hole
//! is filled with the chart around it: the fragment's border vertices keep the chart's UVs, and
//! its inner vertices are placed at the mean of their neighbours (Tutte's embedding, here by a
//! few hundred Gauss–Seidel sweeps over a few vertices). The merge is kept only where every filled
//! face turns the chart's way with some area, which with the hole's border fixed makes the filled
//! disk injective; elsewhere the fragment stays a chart.

use super::segment::{Charts, FaceGraph, NO_FACE};
use crate::mesh::has_repeated_corner;
use glam::DVec2;
use std::collections::HashMap;

/// Fragments (connected groups of small charts) of at most this many faces may be merged.
const MAX_FRAGMENT_FACES: usize = 64;

/// Charts of at most this many faces are fragments.
const SMALL_CHART: usize = 32;

/// Sweeps of the inner vertices' mean placement.
const SWEEPS: usize = 200;

/// Rings of the enclosing chart's faces a hole may widen by (see [`widen`]).
const WIDENINGS: usize = 2;

/// Merges the fragments that exactly one chart encloses into it, and numbers the charts and UV
/// vertices anew without the merged ones.
pub(super) fn merge_enclosed_fragments(graph: &FaceGraph, charts: &mut Charts) {
    let face_chart: Vec<u32> = (0..graph.faces.len())
        .map(|f| {
            if has_repeated_corner(graph.faces[f]) {
                u32::MAX
            } else {
                charts.uv_chart[charts.uv_faces[f][0] as usize]
            }
        })
        .collect();
    let mut size = vec![0usize; charts.n_charts];
    face_chart.iter().filter(|&&c| c != u32::MAX).for_each(|&c| size[c as usize] += 1);
    let small = |c: u32| c != u32::MAX && size[c as usize] <= SMALL_CHART;
    let mut merged = false;
    let mut visited = vec![false; graph.faces.len()];
    for seed in 0..graph.faces.len() {
        if visited[seed] || !small(face_chart[seed]) {
            continue;
        }
        // The fragment: the faces of small charts connected to the seed across edges.
        let mut fragment = vec![seed as u32];
        visited[seed] = true;
        let mut around = Vec::new();
        let mut open = false;
        let mut k = 0;
        while k < fragment.len() {
            let f = fragment[k] as usize;
            k += 1;
            for &g in &graph.neighbours[f] {
                if g == NO_FACE {
                    open = true;
                } else if small(face_chart[g as usize]) {
                    if !visited[g as usize] {
                        visited[g as usize] = true;
                        fragment.push(g);
                    }
                } else {
                    around.push(face_chart[g as usize]);
                }
            }
        }
        around.sort_unstable();
        around.dedup();
        if open || around.len() != 1 || fragment.len() > MAX_FRAGMENT_FACES {
            continue;
        }
        // Where the hole's border bends too much for the mean placement, the hole widens by rings
        // of the chart's own faces, whose UVs are placed anew with the fragment's.
        let chart = around[0];
        let mut region = fragment;
        for ring in 0..=WIDENINGS {
            if fill(graph, charts, &face_chart, &region, chart) {
                merged = true;
                break;
            }
            if ring < WIDENINGS && !widen(graph, &face_chart, &mut region, chart) {
                break;
            }
        }
    }
    if merged {
        renumber(charts);
    }
}

/// Adds to `region` the faces of `chart` across its edges; `false` where it reaches another chart
/// or a border (the region would no longer be a hole in `chart`).
fn widen(graph: &FaceGraph, face_chart: &[u32], region: &mut Vec<u32>, chart: u32) -> bool {
    let mut ring: Vec<u32> = region.iter().flat_map(|&f| graph.neighbours[f as usize]).collect();
    ring.sort_unstable();
    ring.dedup();
    ring.retain(|g| !region.contains(g));
    if ring.iter().any(|&g| g == NO_FACE || face_chart[g as usize] != chart) {
        return false;
    }
    region.extend(ring);
    true
}

/// Fills the hole `fragment` (faces of small charts, and of `chart` once widened) in `chart`;
/// `false` (and nothing changed) where the filled faces would not be injective or the hole is not
/// a disk.
fn fill(graph: &FaceGraph, charts: &mut Charts, face_chart: &[u32], fragment: &[u32], chart: u32) -> bool {
    let mut sorted = fragment.to_vec();
    sorted.sort_unstable();
    // The chart's faces around the hole, which keep their UVs.
    let around = |g: u32| g != NO_FACE && face_chart[g as usize] == chart && sorted.binary_search(&g).is_err();
    // The chart's UV of each border vertex, from the chart's faces across the fragment's edges.
    let mut border: HashMap<u32, u32> = HashMap::new();
    let mut edges = Vec::new();
    for &f in fragment {
        let corners = graph.faces[f as usize];
        for (k, &g) in graph.neighbours[f as usize].iter().enumerate() {
            let (a, b) = (corners[k], corners[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b)));
            if around(g) {
                let other = graph.faces[g as usize];
                for v in [a, b] {
                    let at = other.iter().position(|&w| w == v).expect("neighbours share their edge");
                    border.insert(v, charts.uv_faces[g as usize][at]);
                }
            }
        }
    }
    edges.sort_unstable();
    edges.dedup();
    let mut vertices: Vec<u32> = fragment.iter().flat_map(|&f| graph.faces[f as usize]).collect();
    vertices.sort_unstable();
    vertices.dedup();
    // A disk: V - E + F = 1.
    if vertices.len() + fragment.len() != edges.len() + 1 {
        return false;
    }
    let inner: Vec<u32> = vertices.iter().copied().filter(|v| !border.contains_key(v)).collect();
    let mut uv: HashMap<u32, DVec2> = border.iter().map(|(&v, &k)| (v, charts.uvs[k as usize])).collect();
    // In the vertices' order, so that the sums, and the UVs, are the same on every run.
    let on_border: Vec<DVec2> =
        vertices.iter().filter_map(|v| border.get(v)).map(|&k| charts.uvs[k as usize]).collect();
    let start = on_border.iter().sum::<DVec2>() / on_border.len().max(1) as f64;
    inner.iter().for_each(|&v| {
        uv.insert(v, start);
    });
    let rings: Vec<Vec<u32>> = inner
        .iter()
        .map(|&v| edges.iter().filter_map(|&(a, b)| (a == v).then_some(b).or((b == v).then_some(a))).collect())
        .collect();
    for _ in 0..SWEEPS {
        for (v, ring) in inner.iter().zip(&rings) {
            let mean = ring.iter().map(|w| uv[w]).sum::<DVec2>() / ring.len() as f64;
            uv.insert(*v, mean);
        }
    }
    // The chart's turning sense, from one of its faces around the hole.
    let orientation = |t: [DVec2; 3]| (t[1] - t[0]).perp_dot(t[2] - t[0]);
    let Some(sense) = fragment.iter().flat_map(|&f| graph.neighbours[f as usize]).find_map(|g| {
        around(g).then(|| orientation(charts.uv_faces[g as usize].map(|k| charts.uvs[k as usize])).signum())
    }) else {
        return false;
    };
    let scale = fragment
        .iter()
        .flat_map(|&f| graph.neighbours[f as usize])
        .filter(|&g| around(g))
        .map(|g| orientation(charts.uv_faces[g as usize].map(|k| charts.uvs[k as usize])).abs())
        .fold(0.0, f64::max);
    let turns_right = |f: u32| sense * orientation(graph.faces[f as usize].map(|v| uv[&v])) > 1e-6 * scale;
    if !fragment.iter().all(|&f| turns_right(f)) {
        return false;
    }
    let mut index: HashMap<u32, u32> = border;
    for &v in &inner {
        index.insert(v, charts.uvs.len() as u32);
        charts.uvs.push(uv[&v]);
        charts.uv_chart.push(chart);
    }
    for &f in fragment {
        charts.uv_faces[f as usize] = graph.faces[f as usize].map(|v| index[&v]);
    }
    true
}

/// Drops the UV vertices no face uses and the charts left without any, keeping the order of both.
fn renumber(charts: &mut Charts) {
    let mut used = vec![false; charts.uvs.len()];
    charts.uv_faces.iter().flatten().for_each(|&k| used[k as usize] = true);
    let mut chart_used = vec![false; charts.n_charts];
    charts.uv_chart.iter().zip(&used).filter(|(_, &u)| u).for_each(|(&c, _)| chart_used[c as usize] = true);
    let mut chart_id = vec![u32::MAX; charts.n_charts];
    let mut n_charts = 0;
    for (c, _) in chart_used.iter().enumerate().filter(|(_, &u)| u) {
        chart_id[c] = n_charts;
        n_charts += 1;
    }
    let mut uv_id = vec![u32::MAX; charts.uvs.len()];
    let (mut uvs, mut uv_chart) = (Vec::new(), Vec::new());
    for (k, _) in used.iter().enumerate().filter(|(_, &u)| u) {
        uv_id[k] = uvs.len() as u32;
        uvs.push(charts.uvs[k]);
        uv_chart.push(chart_id[charts.uv_chart[k] as usize]);
    }
    charts.uv_faces.iter_mut().flatten().for_each(|k| *k = uv_id[*k as usize]);
    (charts.uvs, charts.uv_chart, charts.n_charts) = (uvs, uv_chart, n_charts as usize);
}

#[cfg(test)]
mod tests {
    use super::super::face_neighbours;
    use super::*;
    use crate::shapes::plane;
    use glam::DVec3;

    /// A flat 8x8-cell grid charted by its projection, except the faces around the vertex at
    /// `(column, row)`, which form a second chart of their own (UVs far away), and the chart of
    /// each face (`0` for the grid's, `1` for the fragment's; `2` for faces right of `split`).
    fn charted_grid(column: usize, row: usize, split: Option<f64>) -> (Vec<DVec3>, Vec<[u32; 3]>, Charts) {
        let shape = plane(1.0, 8);
        let positions: Vec<DVec3> = shape.positions.iter().map(|&p| DVec3::from_array(p)).collect();
        let faces: Vec<[u32; 3]> = shape.faces.iter().map(|t| t.map(|v| v as u32)).collect();
        let centre = (row * 9 + column) as u32;
        let chart_of = |t: &[u32; 3]| {
            let x = t.iter().map(|&v| positions[v as usize].x).sum::<f64>() / 3.0;
            if t.contains(&centre) {
                1
            } else if split.is_some_and(|s| x > s) {
                2
            } else {
                0
            }
        };
        let mut charts =
            Charts { uv_faces: vec![[0; 3]; faces.len()], uvs: Vec::new(), uv_chart: Vec::new(), n_charts: 0 };
        let mut uv_of: HashMap<(u32, u32), u32> = HashMap::new();
        for (f, t) in faces.iter().enumerate() {
            let chart = chart_of(t);
            charts.n_charts = charts.n_charts.max(chart as usize + 1);
            charts.uv_faces[f] = t.map(|v| {
                *uv_of.entry((chart, v)).or_insert_with(|| {
                    let shift = if chart == 1 { DVec2::splat(10.0) } else { DVec2::ZERO };
                    charts.uvs.push(positions[v as usize].truncate() + shift);
                    charts.uv_chart.push(chart);
                    charts.uvs.len() as u32 - 1
                })
            });
        }
        (positions, faces, charts)
    }

    fn merged(positions: &[DVec3], faces: &[[u32; 3]], charts: &mut Charts) {
        let neighbours = face_neighbours(faces);
        let flat = vec![DVec3::Z; faces.len()];
        let graph = FaceGraph {
            positions,
            faces,
            neighbours: &neighbours,
            normals: &flat,
            smoothed_normals: &flat,
            centroids: &flat,
            cell: 1.0,
        };
        merge_enclosed_fragments(&graph, charts);
    }

    #[test]
    fn a_fragment_inside_a_chart_is_filled_with_it() {
        let (positions, faces, mut charts) = charted_grid(3, 4, None);
        let before = charts.uvs.len();
        merged(&positions, &faces, &mut charts);
        assert_eq!(charts.n_charts, 1);
        assert!(charts.uv_chart.iter().all(|&c| c == 0));
        // The fragment's seven UV vertices gave way to one: its centre's, at the mean of its ring,
        // which on this grid is where it projects; every face is the chart's, turning its way.
        assert_eq!(charts.uvs.len(), before - 7 + 1);
        assert_eq!(charts.uvs.len(), positions.len());
        for (f, t) in faces.iter().enumerate() {
            let uv = charts.uv_faces[f].map(|k| charts.uvs[k as usize]);
            for (k, &v) in t.iter().enumerate() {
                assert!(uv[k].distance(positions[v as usize].truncate()) < 1e-9, "face {f}: {uv:?}");
            }
        }
    }

    #[test]
    fn fragments_between_two_charts_or_on_the_border_stay_charts() {
        for (column, row, split) in [(4, 4, Some(0.5)), (0, 4, None)] {
            let (positions, faces, mut charts) = charted_grid(column, row, split);
            let (uvs, uv_faces, n_charts) = (charts.uvs.clone(), charts.uv_faces.clone(), charts.n_charts);
            merged(&positions, &faces, &mut charts);
            assert_eq!((charts.uvs, charts.uv_faces, charts.n_charts), (uvs, uv_faces, n_charts));
        }
    }

    #[test]
    fn a_hole_the_mean_placement_would_fold_is_widened_until_it_fills() {
        let (positions, faces, mut charts) = charted_grid(3, 4, None);
        // The hole's border vertex right of its centre moves, in the chart around it, to the
        // centre's left: the faces of the fan next to it would turn the other way.
        let right = (4 * 9 + 4) as usize;
        let k = (0..charts.uvs.len())
            .find(|&k| charts.uv_chart[k] == 0 && charts.uvs[k] == positions[right].truncate())
            .expect("the chart's UV of the vertex");
        charts.uvs[k].x -= 0.2;
        let neighbours = face_neighbours(&faces);
        let flat = vec![DVec3::Z; faces.len()];
        let graph = FaceGraph {
            positions: &positions,
            faces: &faces,
            neighbours: &neighbours,
            normals: &flat,
            smoothed_normals: &flat,
            centroids: &flat,
            cell: 1.0,
        };
        let face_chart: Vec<u32> = charts.uv_faces.iter().map(|t| charts.uv_chart[t[0] as usize]).collect();
        let fragment: Vec<u32> = (0..faces.len() as u32).filter(|&f| face_chart[f as usize] == 1).collect();
        let (uvs, uv_faces) = (charts.uvs.clone(), charts.uv_faces.clone());
        assert!(!fill(&graph, &mut charts, &face_chart, &fragment, 0));
        assert_eq!((&charts.uvs, &charts.uv_faces), (&uvs, &uv_faces), "a refused fill changed the charts");
        merge_enclosed_fragments(&graph, &mut charts);
        assert_eq!(charts.n_charts, 1);
        let area = |f: usize| {
            let uv = charts.uv_faces[f].map(|k| charts.uvs[k as usize]);
            (uv[1] - uv[0]).perp_dot(uv[2] - uv[0])
        };
        assert!((0..faces.len()).all(|f| area(f) > 0.0), "a face turns the wrong way");
    }
}
