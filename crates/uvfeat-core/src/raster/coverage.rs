//! Which surface point every texel shows (DESIGN.md §1.3.1–§1.3.2, §1.3.4). Coverage depends on UVs
//! only, so it is built once per topology and resolution; each frame then evaluates positions,
//! normals and metrics from it (DESIGN.md §1.9, animation).

use super::blocked::Blocked;
use super::boundary::{closest_on_segment, rasterise_edge, EdgeHit};
use super::triangles::{rasterise_triangle, TriangleHit};
use crate::cancel;
use crate::mesh::{uv_barycentric, Topology};
use glam::DVec2;
use rayon::prelude::*;

/// Counts that describe a rasterisation.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CoverageDiagnostics {
    /// Texels whose centre lies in a UV triangle.
    pub covered_texels: usize,
    /// Texels touched by a boundary edge of their chart (they carry adjacency).
    pub border_texels: usize,
    /// Uncovered texels claimed by a boundary edge (the gutter ring around charts).
    pub gutter_texels: usize,
    /// Texels claimed by boundary edges of two or more charts (advice: more gutter or resolution).
    pub conflicts: usize,
    /// Texels whose centre lies in several UV triangles (overlapping UVs); the first face wins.
    pub overlapping_texels: usize,
    /// Charts that cover no texel centre at this resolution (smaller than a texel).
    pub charts_without_texels: usize,
}

/// Per-texel surface source of a `resolution`² geometry buffer; texel `(i, j)` is at index
/// `j * resolution + i` and centred at `((i + 0.5) / R, (j + 0.5) / R)` (v up).
#[derive(Debug, Clone)]
pub struct Coverage {
    /// Texels per side.
    pub resolution: usize,
    /// Face shown by the texel (for gutter texels: the face of the closest boundary edge); -1 = empty.
    pub face: Vec<i32>,
    /// Chart id; -1 = empty.
    pub chart: Vec<i32>,
    /// Boundary side (index into `Topology::sides`) closest to a border texel; -1 = not a border texel.
    pub border_side: Vec<i32>,
    /// Chebyshev distance (texels, capped at 65535) to the nearest texel that a chart boundary
    /// touches or that borders another chart, the empty space or the domain edge: every texel
    /// closer than `distance - 1` shares this texel's chart and no boundary crosses it, so a march
    /// or a walk may jump that far at once (the relocation's speed-up at large radii).
    /// Stored in blocks: the walks' long skips read it at random.
    pub chart_distance: Blocked<u16>,
    /// The face of each texel deep enough in its chart that a parametric point in it is reached
    /// from anywhere in the chart's texels around it without crossing a boundary (chart distance
    /// at least 2, not a border texel: [`crate::relocation::interior_face`]); `u32::MAX` elsewhere.
    /// The sampler's fast path reads a sample's face from it with one load; stored in blocks, as
    /// the samples read it at random over whole neighbourhoods.
    pub interior_face: Blocked<u32>,
    /// Counts for reports.
    pub diagnostics: CoverageDiagnostics,
}

/// Centre of texel `t` of a `resolution`² grid in parametric coordinates.
pub fn texel_centre(t: usize, resolution: usize) -> DVec2 {
    let r = resolution as f64;
    DVec2::new(((t % resolution) as f64 + 0.5) / r, ((t / resolution) as f64 + 0.5) / r)
}

impl Coverage {
    /// Rasterises the charts of `topology` into a `resolution`² grid.
    pub fn build(topology: &Topology, resolution: usize) -> Self {
        let mut coverage = Self::unfilled(resolution);
        // A stop request leaves the coverage unfinished: the atlas it was for is not returned.
        coverage.rasterise_triangles(topology);
        if cancel::requested() {
            return coverage;
        }
        coverage.rasterise_boundaries(topology);
        if cancel::requested() {
            return coverage;
        }
        let distance = chart_distance(&coverage.chart, &coverage.border_side, resolution);
        coverage.chart_distance = Blocked::from_rows(&distance, resolution, 0);
        let interior_face: Vec<u32> = (0..resolution * resolution)
            .into_par_iter()
            .map(|t| {
                let interior = distance[t] >= INTERIOR_DISTANCE && coverage.border_side[t] < 0;
                u32::try_from(coverage.face[t]).ok().filter(|_| interior).unwrap_or(u32::MAX)
            })
            .collect();
        coverage.interior_face = Blocked::from_rows(&interior_face, resolution, u32::MAX);
        coverage
    }

    /// A `resolution`² grid with no texel covered (all tables in place).
    pub fn empty(resolution: usize) -> Self {
        let n = resolution * resolution;
        Self {
            chart_distance: Blocked::from_rows(&vec![0; n], resolution, 0),
            interior_face: Blocked::from_rows(&vec![u32::MAX; n], resolution, u32::MAX),
            ..Self::unfilled(resolution)
        }
    }

    /// Every texel empty, its tables not yet laid out.
    fn unfilled(resolution: usize) -> Self {
        let n = resolution * resolution;
        Self {
            resolution,
            face: vec![-1; n],
            chart: vec![-1; n],
            border_side: vec![-1; n],
            chart_distance: Blocked::default(),
            interior_face: Blocked::default(),
            diagnostics: CoverageDiagnostics::default(),
        }
    }

    /// The face a texel shows and the UV of the point it shows: the texel centre where it lies in
    /// the face, else (a gutter texel) the closest point of its closest boundary side. Recomputed,
    /// not stored: 8 bytes per texel were 32 MiB at 2048².
    pub fn anchor(&self, topology: &Topology, t: usize) -> Option<(u32, DVec2)> {
        let face = u32::try_from(self.face[t]).ok()?;
        let centre = texel_centre(t, self.resolution);
        let inside = || uv_barycentric(&topology.corner_uvs(face as usize), centre).iter().all(|&b| b >= -1e-12);
        match usize::try_from(self.border_side[t]).ok() {
            Some(side) if !inside() => {
                let (_, [a, b]) = topology.side_endpoints(&topology.sides[side]);
                let (_, along) = closest_on_segment(a, b, centre);
                Some((face, a + (b - a) * along))
            }
            _ => Some((face, centre)),
        }
    }

    fn rasterise_triangles(&mut self, topology: &Topology) {
        let resolution = self.resolution;
        let hits: Vec<TriangleHit> = (0..topology.faces.len())
            .into_par_iter()
            .filter(|&f| topology.face_chart[f] >= 0)
            .fold(Vec::new, |mut out, f| {
                rasterise_triangle(f as u32, topology.corner_uvs(f), resolution, &mut out);
                out
            })
            .flatten_iter()
            .collect();
        let mut charts_seen = vec![false; topology.n_charts];
        for hit in hits {
            let t = hit.texel as usize;
            if self.face[t] >= 0 {
                self.diagnostics.overlapping_texels += 1;
                continue;
            }
            let chart = topology.face_chart[hit.face as usize];
            self.face[t] = hit.face as i32;
            self.chart[t] = chart;
            charts_seen[chart as usize] = true;
            self.diagnostics.covered_texels += 1;
        }
        self.diagnostics.charts_without_texels = charts_seen.iter().filter(|&&seen| !seen).count();
    }

    /// Triangle coverage has priority; an uncovered texel goes to the closest boundary edge.
    fn rasterise_boundaries(&mut self, topology: &Topology) {
        let resolution = self.resolution;
        let mut hits: Vec<EdgeHit> = topology
            .sides
            .par_iter()
            .enumerate()
            .filter(|(_, side)| side.chart >= 0)
            .fold(Vec::new, |mut out, (s, side)| {
                let (_, [a, b]) = topology.side_endpoints(side);
                rasterise_edge(s as u32, a, b, resolution, &mut out);
                out
            })
            .flatten_iter()
            .collect();
        hits.par_sort_unstable_by(|x, y| {
            (x.texel, x.distance, x.side).partial_cmp(&(y.texel, y.distance, y.side)).expect("finite distances")
        });
        for group in hits.chunk_by(|x, y| x.texel == y.texel) {
            let t = group[0].texel as usize;
            let chart_of = |h: &EdgeHit| topology.sides[h.side as usize].chart;
            let first_chart = chart_of(&group[0]);
            if group.iter().any(|h| chart_of(h) != first_chart) {
                self.diagnostics.conflicts += 1;
            }
            if self.face[t] < 0 {
                let closest = &group[0];
                let side = &topology.sides[closest.side as usize];
                self.face[t] = side.face as i32;
                self.chart[t] = side.chart;
                self.border_side[t] = closest.side as i32;
                self.diagnostics.gutter_texels += 1;
                self.diagnostics.border_texels += 1;
            } else if let Some(own) = group.iter().find(|h| chart_of(h) == self.chart[t]) {
                self.border_side[t] = own.side as i32;
                self.diagnostics.border_texels += 1;
            }
        }
    }

    /// Approximate bytes per texel of coverage plus one frame of buffers, for memory checks.
    pub const BYTES_PER_TEXEL: u64 = 26 + 36 + 24;
}

/// Chart distance from which a texel is interior (see [`Coverage::interior_face`]).
const INTERIOR_DISTANCE: u16 = 2;

/// Two-pass chamfer transform (exact for the Chebyshev metric with 8-neighbour propagation) from
/// the border texels and the texels next to another chart. Row by row: a row takes its three
/// neighbours in the previous row at once (vectorised), then its left neighbour in a scan.
fn chart_distance(chart: &[i32], border_side: &[i32], r: usize) -> Vec<u16> {
    let mut d = vec![u16::MAX; r * r];
    d.par_chunks_mut(r).enumerate().for_each(|(j, row)| {
        let charts = |y: Option<usize>| y.filter(|&y| y < r).map(|y| &chart[y * r..(y + 1) * r]);
        let (above, own, below) = (charts(j.checked_sub(1)), &chart[j * r..(j + 1) * r], charts(Some(j + 1)));
        for (i, d) in row.iter_mut().enumerate() {
            let c = own[i];
            let differs = |line: Option<&[i32]>| {
                line.is_none_or(|line| line[i.saturating_sub(1)..(i + 2).min(r)].iter().any(|&x| x != c))
            };
            let edge = i == 0 || i + 1 == r || own[i - 1] != c || own[i + 1] != c || differs(above) || differs(below);
            if edge || border_side[j * r + i] >= 0 {
                *d = 1;
            }
        }
    });
    for j in 0..r {
        let (done, rest) = d.split_at_mut(j * r);
        let row = &mut rest[..r];
        if j > 0 {
            take_from_row(row, &done[(j - 1) * r..]);
        }
        scan(row.iter_mut());
    }
    for j in (0..r).rev() {
        let (head, below) = d.split_at_mut((j + 1) * r);
        let row = &mut head[j * r..];
        if j + 1 < r {
            take_from_row(row, &below[..r]);
        }
        scan(row.iter_mut().rev());
    }
    d
}

/// A chamfer pass's step along a row: each texel takes the one before it (the running value
/// stays in a register).
fn scan<'a>(row: impl Iterator<Item = &'a mut u16>) {
    let mut running = u16::MAX;
    for d in row {
        running = (*d).min(running.saturating_add(1));
        *d = running;
    }
}

/// A chamfer pass's step between rows: every texel of `row` takes its three neighbours in the
/// `done` row (above in the forward pass, below in the backward one), which no longer changes.
fn take_from_row(row: &mut [u16], done: &[u16]) {
    let n = row.len();
    let step = |d: &mut u16, near: u16| *d = (*d).min(near.saturating_add(1));
    if n < 3 {
        let nearest = done[..n].iter().copied().min().unwrap_or(u16::MAX);
        row.iter_mut().for_each(|d| step(d, nearest));
        return;
    }
    step(&mut row[0], done[0].min(done[1]));
    step(&mut row[n - 1], done[n - 2].min(done[n - 1]));
    let (left, centre, right) = (&done[..n - 2], &done[1..n - 1], &done[2..]);
    for (i, d) in row[1..n - 1].iter_mut().enumerate() {
        step(d, left[i].min(centre[i]).min(right[i]));
    }
}

#[cfg(test)]
mod tests {
    use super::chart_distance;

    #[test]
    fn chart_distance_is_the_chebyshev_distance_to_another_chart_or_a_boundary() {
        let r = 9;
        let mut chart = vec![0; r * r];
        chart[4 * r + 6] = 1;
        let mut border_side = vec![-1; r * r];
        border_side[6 * r + 2] = 0;
        let d = chart_distance(&chart, &border_side, r);
        assert_eq!(d[4 * r + 5], 1); // next to the other chart
        assert_eq!(d[4 * r + 3], 3); // 3 columns away: texels at distance < 3 are all chart 0... and the edge
        assert_eq!(d[0], 1); // domain edge
        assert_eq!(d[2 * r + 2], 3);
        assert_eq!(d[6 * r + 2], 1); // a boundary touches it
        assert_eq!(d[6 * r + 3], 2); // 3 without that boundary
    }

    #[test]
    fn chart_distance_equals_a_brute_force_search() {
        let r = 37;
        let mut state = 7u32;
        let mut next = |n: u32| {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) % n
        };
        // Blocks of charts with a few scattered texels of other charts and boundaries.
        let mut chart: Vec<i32> = (0..r * r).map(|t| ((t % r) / 13 + 3 * ((t / r) / 11)) as i32).collect();
        for _ in 0..15 {
            chart[next((r * r) as u32) as usize] = 99;
        }
        let border_side: Vec<i32> = (0..r * r).map(|_| if next(60) == 0 { 0 } else { -1 }).collect();
        let at = |i: i64, j: i64| (0..r as i64).contains(&i) && (0..r as i64).contains(&j);
        let seed = |i: i64, j: i64| {
            let c = chart[j as usize * r + i as usize];
            border_side[j as usize * r + i as usize] >= 0
                || (-1..=1).any(|dj| {
                    (-1..=1).any(|di| !at(i + di, j + dj) || chart[(j + dj) as usize * r + (i + di) as usize] != c)
                })
        };
        let seeds: Vec<(i64, i64)> =
            (0..r as i64).flat_map(|j| (0..r as i64).map(move |i| (i, j))).filter(|&(i, j)| seed(i, j)).collect();
        let d = chart_distance(&chart, &border_side, r);
        for j in 0..r as i64 {
            for i in 0..r as i64 {
                let nearest = seeds.iter().map(|&(x, y)| (x - i).abs().max((y - j).abs())).min().unwrap();
                assert_eq!(i64::from(d[j as usize * r + i as usize]), nearest + 1, "texel ({i}, {j})");
            }
        }
    }
}
