//! Fragments merged into a chart beside them (DESIGN.md §1.1.1).
//!
//! On a rough scan a few faces here and there still fold in every chart's projection, even on the
//! smoothed surface, and the growth leaves each such spot a chart of its own: the noisy 200K sphere
//! of docs/PEERS.md came out as 20 charts and 255 fragments of a median of 10 faces, 152 of them
//! holes in one chart. Each is a seam in the middle of the surface: the sampler's points walk round
//! it and the coverage check grows the domains near it, so that the features took 0.66 s on those
//! charts against 0.27 s on the same sphere's single lat-long chart.
//!
//! A chart's UVs need only be injective (every face's metric undoes the map, §1.3.3), so a
//! fragment joins a chart beside it: the vertices the chart holds keep their UVs, those on the
//! fragment's border with other charts take their projection onto the chart's plane, and the inner
//! ones are placed at the mean of their neighbours (Tutte's embedding, here by a few hundred
//! Gauss–Seidel sweeps over a few vertices). The merge is kept only where every merged face turns
//! the chart's way with some area and, where the fragment is not a hole in the chart, overlaps
//! none of the chart's faces nor another merged face; a hole that would fold widens by rings of the
//! chart's own faces, which are placed anew with it. Elsewhere the fragment stays a chart.

use super::segment::{boxes_apart, interiors_overlap, uv_box, Charts, FaceGraph, NO_FACE};
use crate::cancel;
use crate::mesh::{compressed_rows, has_repeated_corner};
use glam::DVec2;

/// Fragments (connected groups of small charts) of at most this many faces may be merged.
const MAX_FRAGMENT_FACES: usize = 64;

/// Charts of at most this many faces are fragments.
const SMALL_CHART: usize = 32;

/// Sweeps of the inner vertices' mean placement.
const SWEEPS: usize = 200;

/// Rings of the enclosing chart's faces a hole may widen by (see [`widen`]).
const WIDENINGS: usize = 2;

/// What the merges read: each face's chart, each vertex's faces and each chart's faces, kept up
/// to date as fragments join charts.
struct Layout {
    face_chart: Vec<u32>,
    vertex_faces: (Vec<u32>, Vec<u32>),
    chart_faces: Vec<Vec<u32>>,
}

impl Layout {
    fn new(graph: &FaceGraph, charts: &Charts) -> Self {
        let face_chart: Vec<u32> = (0..graph.faces.len())
            .map(|f| {
                if has_repeated_corner(graph.faces[f]) {
                    u32::MAX
                } else {
                    charts.uv_chart[charts.uv_faces[f][0] as usize]
                }
            })
            .collect();
        let corners = graph.faces.iter().enumerate().flat_map(|(f, t)| t.iter().map(move |&v| (v, f as u32)));
        let vertex_faces = compressed_rows(graph.positions.len(), corners);
        let mut chart_faces = vec![Vec::new(); charts.n_charts];
        for (f, &c) in face_chart.iter().enumerate().filter(|(_, &c)| c != u32::MAX) {
            chart_faces[c as usize].push(f as u32);
        }
        Self { face_chart, vertex_faces, chart_faces }
    }

    /// Records that the faces of `region` now belong to `chart`.
    fn merged(&mut self, region: &[u32], chart: u32) {
        for &f in region {
            if self.face_chart[f as usize] != chart {
                self.face_chart[f as usize] = chart;
                self.chart_faces[chart as usize].push(f);
            }
        }
    }

    fn faces_of_vertex(&self, v: u32) -> &[u32] {
        let (starts, faces) = &self.vertex_faces;
        &faces[starts[v as usize] as usize..starts[v as usize + 1] as usize]
    }

    fn faces_of_chart(&self, chart: u32) -> &[u32] {
        &self.chart_faces[chart as usize]
    }
}

/// Merges the fragments into a chart beside them where it stays injective, and numbers the charts
/// and UV vertices anew without the merged ones.
pub(super) fn merge_fragments(graph: &FaceGraph, charts: &mut Charts) {
    let mut layout = Layout::new(graph, charts);
    let size: Vec<usize> = layout.chart_faces.iter().map(Vec::len).collect();
    // Read from the charts as grown: a fragment merged earlier is no longer a small chart's.
    let grown = layout.face_chart.clone();
    let small = |f: usize| grown[f] != u32::MAX && size[grown[f] as usize] <= SMALL_CHART;
    let mut merged = false;
    let mut visited = vec![false; graph.faces.len()];
    for seed in 0..graph.faces.len() {
        if cancel::requested() {
            return;
        }
        if visited[seed] || !small(seed) {
            continue;
        }
        // The fragment: the faces of small charts connected to the seed across edges, and the
        // charts across its border (once per edge).
        let mut fragment = vec![seed as u32];
        visited[seed] = true;
        let mut beside = Vec::new();
        let mut open = false;
        let mut k = 0;
        while k < fragment.len() {
            let f = fragment[k] as usize;
            k += 1;
            for &g in &graph.neighbours[f] {
                if g == NO_FACE {
                    open = true;
                } else if small(g as usize) {
                    if !visited[g as usize] {
                        visited[g as usize] = true;
                        fragment.push(g);
                    }
                } else {
                    beside.push(layout.face_chart[g as usize]);
                }
            }
        }
        if open || beside.is_empty() || fragment.len() > MAX_FRAGMENT_FACES {
            continue;
        }
        beside.sort_unstable();
        // The charts beside it, those it shares most edges with first.
        let mut candidates: Vec<(usize, u32)> = beside.chunk_by(|a, b| a == b).map(|run| (run.len(), run[0])).collect();
        candidates.sort_by_key(|&(edges, chart)| (std::cmp::Reverse(edges), chart));
        if let [(_, chart)] = candidates[..] {
            // Where the hole's border bends too much for the mean placement, the hole widens by
            // rings of the chart's own faces, whose UVs are placed anew with the fragment's.
            let mut region = fragment;
            for ring in 0..=WIDENINGS {
                if merge(graph, charts, &layout, &region, chart) {
                    layout.merged(&region, chart);
                    merged = true;
                    break;
                }
                if ring < WIDENINGS && !widen(graph, &layout.face_chart, &mut region, chart) {
                    break;
                }
            }
        } else if let Some(&(_, chart)) =
            candidates.iter().find(|&&(_, chart)| merge(graph, charts, &layout, &fragment, chart))
        {
            layout.merged(&fragment, chart);
            merged = true;
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

/// Merges `region` (the faces of a fragment, and of `chart` where a hole widened) into `chart`;
/// `false`, and nothing changed, where the merged faces would not be injective or a hole is not a
/// disk.
fn merge(graph: &FaceGraph, charts: &mut Charts, layout: &Layout, region: &[u32], chart: u32) -> bool {
    let face_chart = &layout.face_chart;
    let mut sorted = region.to_vec();
    sorted.sort_unstable();
    let in_region = |g: u32| sorted.binary_search(&g).is_ok();
    let of_chart = |g: u32| g != NO_FACE && face_chart[g as usize] == chart && !in_region(g);
    let mut vertices: Vec<u32> = region.iter().flat_map(|&f| graph.faces[f as usize]).collect();
    vertices.sort_unstable();
    vertices.dedup();
    let at = |v: u32| vertices.binary_search(&v).expect("a vertex of the region");
    // The region's edges, its vertices on its border (with the chart or another), and whether the
    // chart is across every edge of that border: then the region is a hole in the chart.
    let mut edges = Vec::new();
    let mut on_border = vec![false; vertices.len()];
    let mut enclosed = true;
    for &f in region {
        let corners = graph.faces[f as usize];
        for (k, &g) in graph.neighbours[f as usize].iter().enumerate() {
            let (a, b) = (corners[k], corners[(k + 1) % 3]);
            edges.push((a.min(b), a.max(b)));
            if g == NO_FACE || !in_region(g) {
                on_border[at(a)] = true;
                on_border[at(b)] = true;
                enclosed &= of_chart(g);
            }
        }
    }
    edges.sort_unstable();
    edges.dedup();
    // The chart's UV of each vertex it holds, and its turning sense, from its faces at them.
    let orientation = |t: [DVec2; 3]| (t[1] - t[0]).perp_dot(t[2] - t[0]);
    let chart_uvs = |g: u32| charts.uv_faces[g as usize].map(|k| charts.uvs[k as usize]);
    let mut held: Vec<Option<u32>> = vec![None; vertices.len()];
    let (mut sense, mut scale) = (0.0f64, 0.0f64);
    for (i, &v) in vertices.iter().enumerate() {
        for &g in layout.faces_of_vertex(v).iter().filter(|&&g| of_chart(g)) {
            let corner = graph.faces[g as usize].iter().position(|&w| w == v).expect("a face of the vertex");
            held[i] = Some(charts.uv_faces[g as usize][corner]);
            let area = orientation(chart_uvs(g));
            (sense, scale) = (area.signum(), scale.max(area.abs()));
        }
    }
    if sense == 0.0 {
        return false;
    }
    // A hole must be a disk (V - E + F = 1), so that its fixed border makes it injective.
    if enclosed && vertices.len() + region.len() != edges.len() + 1 {
        return false;
    }
    // Placed: the held vertices where the chart has them, the others of the border projected onto
    // the chart's plane, the inner ones at the mean of their neighbours.
    let frame = charts.frames[chart as usize];
    let mut uv: Vec<DVec2> = vertices
        .iter()
        .zip(&held)
        .map(|(&v, held)| held.map_or_else(|| frame.project(graph.positions[v as usize]), |k| charts.uvs[k as usize]))
        .collect();
    let fixed: Vec<usize> = (0..vertices.len()).filter(|&i| on_border[i]).collect();
    let start = fixed.iter().map(|&i| uv[i]).sum::<DVec2>() / fixed.len().max(1) as f64;
    let inner: Vec<usize> = (0..vertices.len()).filter(|&i| !on_border[i]).collect();
    inner.iter().for_each(|&i| uv[i] = start);
    let rings: Vec<Vec<usize>> = inner
        .iter()
        .map(|&i| {
            let v = vertices[i];
            edges.iter().filter_map(|&(a, b)| (a == v).then_some(b).or((b == v).then_some(a))).map(at).collect()
        })
        .collect();
    mean_placement(&mut uv, &inner, &rings);
    let placed = |f: u32| graph.faces[f as usize].map(|v| uv[at(v)]);
    if !region.iter().all(|&f| sense * orientation(placed(f)) > 1e-6 * scale) {
        return false;
    }
    if !enclosed && overlaps(charts, layout, region, chart, &placed, &of_chart) {
        return false;
    }
    let index: Vec<u32> = held
        .iter()
        .zip(&uv)
        .map(|(held, &point)| {
            held.unwrap_or_else(|| {
                charts.uvs.push(point);
                charts.uv_chart.push(chart);
                charts.uvs.len() as u32 - 1
            })
        })
        .collect();
    for &f in region {
        charts.uv_faces[f as usize] = graph.faces[f as usize].map(|v| index[at(v)]);
    }
    true
}

/// Moves each vertex `inner[k]` of `uv` to the mean of its neighbours `rings[k]`, [`SWEEPS`]
/// times over (Gauss–Seidel on Tutte's embedding, the others fixed).
fn mean_placement(uv: &mut [DVec2], inner: &[usize], rings: &[Vec<usize>]) {
    for _ in 0..SWEEPS {
        for (&i, ring) in inner.iter().zip(rings) {
            uv[i] = ring.iter().map(|&j| uv[j]).sum::<DVec2>() / ring.len() as f64;
        }
    }
}

/// Whether a face of `region`, placed by `placed`, overlaps another or a face of `chart` (those
/// `of_chart` says are the chart's own).
fn overlaps(
    charts: &Charts,
    layout: &Layout,
    region: &[u32],
    chart: u32,
    placed: &dyn Fn(u32) -> [DVec2; 3],
    of_chart: &dyn Fn(u32) -> bool,
) -> bool {
    let triangles: Vec<[DVec2; 3]> = region.iter().map(|&f| placed(f)).collect();
    let region_box = uv_box(triangles.iter().flatten().copied());
    let across_region =
        triangles.iter().enumerate().any(|(i, a)| triangles[i + 1..].iter().any(|b| interiors_overlap(a, b)));
    across_region
        || layout.faces_of_chart(chart).iter().filter(|&&g| of_chart(g)).any(|&g| {
            let other = charts.uv_faces[g as usize].map(|k| charts.uvs[k as usize]);
            !boxes_apart(uv_box(other), region_box) && triangles.iter().any(|t| interiors_overlap(t, &other))
        })
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
    let frames = charts.frames.iter().zip(&chart_used).filter(|(_, &u)| u).map(|(frame, _)| *frame).collect();
    (charts.uvs, charts.uv_chart, charts.n_charts, charts.frames) = (uvs, uv_chart, n_charts as usize, frames);
}

#[cfg(test)]
mod tests;
