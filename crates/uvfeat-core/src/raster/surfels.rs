//! Surface elements ("surfels") of the atlas (DESIGN.md §1.4.8, `quadrature = "surfels"`): every
//! texel of the geometry grid holds, per chart, the exact part of the surface whose UVs fall in it
//! (each face's UV triangle clipped to the texel's square), as its 3D area, centroid and mean
//! normal. The surfels partition the surface: each surface point belongs to exactly one, whatever
//! the charts, seams or distortion, which is what a neighbourhood that counts surface once needs.
//!
//! A pyramid merges 2 x 2 texels per level, so that a neighbourhood of any radius can be summed
//! over a few hundred surfels. A coarse surfel is one *connected* piece of a chart in its texel:
//! two arms of a chart that meet in a coarse texel, or the two sides of a slit, stay apart (when
//! at least a finest texel apart), and coarse surfels are adjacent where their finer pieces are. At
//! the finest level, surfels of one chart in side-adjacent texels are adjacent where a face has
//! parts in both (the surface crosses their common side: two parts of a chart that only come
//! within a texel of each other in UV stay apart), and seams join the surfels on their two sides.
//! (Two parts of a chart in one texel are still one surfel.)

use super::morton::morton;
use super::surfel_fragments::{boundary_points, texel_sums, Fragment, SeamPoints, JOINS_BELOW, JOINS_LEFT};
use crate::cancel;
use crate::frame::Frame;
use crate::mesh::{find, union, Topology};
use glam::{DVec2, DVec3};
use rayon::prelude::*;
use std::sync::OnceLock;

/// Which surface the surfels (and their centres) lie on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Surface {
    /// The triangle lookup's smooth surface through the vertex normals (DESIGN.md §1.3.6), as the
    /// pattern's samples (default): closest to a smooth shape the mesh approximates.
    #[default]
    Smooth,
    /// The mesh's own flat facets, as the object-space reference and its refinements measure them.
    Facets,
}

/// The coarsest level has at most this many texels per side.
const SMALLEST_LEVEL: usize = 4;

/// Where a surfel is, how much surface it holds and how that surface spreads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfelPoint {
    /// Area centroid.
    pub position: DVec3,
    /// 3D area.
    pub area: f64,
    /// `sum dA |q - position|^2` over its surface: with it, sums of `dA |q - p|^2` over whole
    /// surfels are exact (`area |position - p|^2 + spread`).
    pub spread: f64,
}

/// The surfels of one level of the pyramid.
#[derive(Debug, Clone, Default)]
pub struct SurfelLevel {
    /// Texels per side.
    pub width: usize,
    /// Texel `j * width + i` of each surfel.
    pub texel: Vec<u32>,
    /// Chart of each surfel.
    pub chart: Vec<i32>,
    /// Area centroid and 3D area (together: the search reads both of every surfel it reaches).
    pub point: Vec<SurfelPoint>,
    /// Area-weighted mean of the unit normals, normalised.
    pub normal: Vec<DVec3>,
    /// A mesh border (or non-manifold edge) passes through the surfel.
    pub on_border: Vec<bool>,
    /// Coarser levels only: the surfel of this level that holds each surfel of the level below.
    pub finer_parent: Vec<u32>,
    /// Adjacent surfels of `s`: `adjacent[adjacent_first[s]..adjacent_first[s + 1]]`.
    adjacent_first: Vec<u32>,
    adjacent: Vec<u32>,
    /// Finest level only: the first surfel of texel `t` (its surfels are consecutive), `u32::MAX`
    /// where it holds none.
    by_texel: Vec<u32>,
}

impl SurfelLevel {
    /// Number of surfels.
    pub fn len(&self) -> usize {
        self.chart.len()
    }

    /// `true` when the level holds no surfel.
    pub fn is_empty(&self) -> bool {
        self.chart.is_empty()
    }

    /// Texel `(i, j)` of surfel `s`.
    pub fn texel(&self, s: u32) -> (i64, i64) {
        let t = self.texel[s as usize] as usize;
        ((t % self.width) as i64, (t / self.width) as i64)
    }

    /// The texel `(i, j)` of parametric point `uv`.
    pub fn texel_of(&self, uv: DVec2) -> (i64, i64) {
        let w = self.width as f64;
        ((uv.x * w).floor() as i64, (uv.y * w).floor() as i64)
    }

    /// Finest level only: the surfel of `chart` in texel `t` (`j * width + i`), if that texel holds
    /// part of it.
    pub fn at(&self, t: usize, chart: i32) -> Option<u32> {
        let first = *self.by_texel.get(t)?;
        (first as usize..self.len())
            .take_while(|&s| self.texel[s] as usize == t)
            .find(|&s| self.chart[s] == chart)
            .map(|s| s as u32)
    }

    /// The texel `j * width + i` of texel `(i, j)`, `None` off the grid.
    pub fn texel_index(&self, (i, j): (i64, i64)) -> Option<usize> {
        let w = self.width as i64;
        (i >= 0 && j >= 0 && i < w && j < w).then(|| (j * w + i) as usize)
    }

    /// Surfels adjacent to `s` on the surface.
    #[inline]
    pub fn neighbours(&self, s: u32) -> &[u32] {
        &self.adjacent[self.adjacent_first[s as usize] as usize..self.adjacent_first[s as usize + 1] as usize]
    }

    /// The finest level: the face fragments summed per texel and chart, adjacent within a chart
    /// where a face has parts in two side-adjacent texels (`Fragment::joins`) and across the
    /// seams. `None` when a stop was requested: each step takes 0.1-0.2 s at 1024² on 2 cores, so
    /// it is asked between them.
    fn finest(width: usize, sums: Vec<Fragment>, seams: &[SeamPoints], borders: &[(DVec2, i32)]) -> Option<Self> {
        let order = z_order(&sums, width);
        cancel::check().ok()?;
        let mut level = Self::of_sums(width, &sums, &order);
        level.index_texels();
        cancel::check().ok()?;
        let (pairs, on_border) = {
            let level = &level;
            let find =
                |(uv, chart): (DVec2, i32)| level.texel_index(level.texel_of(uv)).and_then(|t| level.at(t, chart));
            let mut pairs: Vec<(u32, u32)> =
                seams.par_iter().filter_map(|&(a, b)| Some((find(a)?, find(b)?))).collect();
            pairs.par_extend((0..level.len() as u32).into_par_iter().flat_map_iter(move |s| {
                let (i, j) = level.texel(s);
                let (chart, joins) = (level.chart[s as usize], sums[order[s as usize] as usize].joins);
                [(JOINS_LEFT, -1, 0), (JOINS_BELOW, 0, -1)]
                    .into_iter()
                    .filter(move |&(bit, ..)| joins & bit != 0)
                    .filter_map(move |(_, di, dj)| Some((s, level.at(level.texel_index((i + di, j + dj))?, chart)?)))
            }));
            (pairs, borders.iter().filter_map(|&point| find(point)).collect::<Vec<u32>>())
        };
        cancel::check().ok()?;
        level.set_adjacency(pairs);
        for s in on_border {
            level.on_border[s as usize] = true;
        }
        Some(level)
    }

    /// One surfel per texel sum, in `order` (each its own surfel, as [`SurfelLevel::summed`] would
    /// sum it, with no copy of the sums: sorting and merging them on one thread took 22-25 ms of
    /// the armadillo's 512² pyramid).
    fn of_sums(width: usize, sums: &[Fragment], order: &[u32]) -> Self {
        Self::laid_out(width, order.len(), |k| {
            let f = &sums[order[k] as usize];
            // As `absorb` into an empty sum: a piece without area leaves it empty.
            if f.area > 0.0 {
                *f
            } else {
                Fragment::empty(f.texel, f.chart)
            }
        })
    }

    /// The level of `n` surfels, surfel `k` the sum `sum(k)`, laid out in parallel.
    fn laid_out(width: usize, n: usize, sum: impl Fn(usize) -> Fragment + Sync) -> Self {
        let each = || (0..n).into_par_iter().map(&sum);
        Self {
            width,
            texel: each().map(|s| s.texel).collect(),
            chart: each().map(|s| s.chart).collect(),
            point: each().map(|s| SurfelPoint { position: s.centroid(), area: s.area, spread: s.spread }).collect(),
            normal: each().map(|s| s.normal.normalize_or_zero()).collect(),
            on_border: vec![false; n],
            ..Default::default()
        }
    }

    /// Surfels from fragments grouped by `owner` (consecutive ids from 0, in texel order).
    fn summed(width: usize, fragments: &[Fragment], owner: &[u32]) -> Self {
        let n = owner.last().map_or(0, |&o| o as usize + 1);
        let mut sums = vec![Fragment::empty(0, -1); n];
        for (f, &o) in fragments.iter().zip(owner) {
            let sum = &mut sums[o as usize];
            sum.texel = f.texel;
            sum.chart = f.chart;
            sum.absorb(f);
        }
        Self::laid_out(width, n, |k| sums[k])
    }

    /// Adjacency from pairs `(a, b)` (either order, repeats and `a == b` allowed), each list in
    /// ascending order. Counted into place rather than sorted as one list: the finest level of
    /// the 100K-face dragon at 512² has 346K pairs (22 ms sorted).
    fn set_adjacency(&mut self, pairs: Vec<(u32, u32)>) {
        let n = self.len();
        let links = || pairs.iter().filter(|(a, b)| a != b).flat_map(|&(a, b)| [(a, b), (b, a)]);
        let mut first = vec![0u32; n + 1];
        for (a, _) in links() {
            first[a as usize + 1] += 1;
        }
        for s in 0..n {
            first[s + 1] += first[s];
        }
        let mut next = first.clone();
        let mut adjacent = vec![0u32; first[n] as usize];
        for (a, b) in links() {
            adjacent[next[a as usize] as usize] = b;
            next[a as usize] += 1;
        }
        // Each list sorted and its repeats dropped, compacted towards the front in place.
        self.adjacent_first = Vec::with_capacity(n + 1);
        self.adjacent_first.push(0);
        let mut kept = 0;
        for s in 0..n {
            let (list, start) = (first[s] as usize..first[s + 1] as usize, kept);
            adjacent[list.clone()].sort_unstable();
            for k in list {
                if kept == start || adjacent[kept - 1] != adjacent[k] {
                    adjacent[kept] = adjacent[k];
                    kept += 1;
                }
            }
            self.adjacent_first.push(kept as u32);
        }
        adjacent.truncate(kept);
        self.adjacent = adjacent;
    }

    /// Sets `by_texel` (the surfels of a texel must be consecutive).
    fn index_texels(&mut self) {
        self.by_texel = vec![u32::MAX; self.width * self.width];
        for (s, &t) in self.texel.iter().enumerate().rev() {
            self.by_texel[t as usize] = s as u32;
        }
    }

    /// The surfels `range` (a block) as `(chart, component, surfel)` in that order, where the
    /// components join adjacent surfels of one chart, each named by its smallest surfel.
    fn joined(&self, range: std::ops::Range<usize>) -> Vec<(i32, u32, u32)> {
        // Union-find over the block's own surfels, numbered from its first.
        let first = range.start;
        let mut parent: Vec<u32> = (0..range.len() as u32).collect();
        for s in range.clone() {
            for &t in self.neighbours(s as u32) {
                if range.contains(&(t as usize)) && self.chart[s] == self.chart[t as usize] {
                    union(&mut parent, (s - first) as u32, t - first as u32);
                }
            }
        }
        let mut joined: Vec<(i32, u32, u32)> =
            range.map(|s| (self.chart[s], find(&mut parent, (s - first) as u32) + first as u32, s as u32)).collect();
        joined.sort_unstable();
        joined
    }

    /// The next level up: in each 2 x 2 block of texels, the surfels of one chart joined by
    /// adjacency form one surfel.
    fn coarser(&self) -> Self {
        let width = self.width.div_ceil(2);
        let up = |t: u32| {
            let (i, j) = (t as usize % self.width, t as usize / self.width);
            ((j / 2) * width + i / 2) as u32
        };
        let key = |s: usize| (up(self.texel[s]), self.chart[s]);
        // Surfels join only within their block, and a block's surfels are consecutive (Z order of
        // the texels, then chart): the blocks are joined apart, in parallel, and listed in the Z
        // order of the coarse texels, as the finest level (`z_order`).
        let bounds: Vec<usize> =
            (0..self.len()).filter(|&s| s == 0 || key(s).0 != key(s - 1).0).chain([self.len()]).collect();
        let order: Vec<(u64, i32, u32, u32)> = bounds
            .par_windows(2)
            .with_min_len(256)
            .flat_map_iter(|block| {
                let t = key(block[0]).0 as usize;
                let z = morton(t % width, t / width);
                self.joined(block[0]..block[1]).into_iter().map(move |(chart, root, s)| (z, chart, root, s))
            })
            .collect();
        let mut owner = vec![0u32; order.len()];
        for k in 1..order.len() {
            owner[k] = owner[k - 1] + u32::from(order[k].2 != order[k - 1].2);
        }
        let fragments: Vec<Fragment> = order
            .iter()
            .map(|&(_, chart, _, s)| {
                let texel = key(s as usize).0;
                let SurfelPoint { position, area, spread } = self.point[s as usize];
                Fragment {
                    texel,
                    chart,
                    area,
                    moment: position * area,
                    normal: self.normal[s as usize] * area,
                    spread,
                    joins: 0,
                }
            })
            .collect();
        let mut next = Self::summed(width, &fragments, &owner);
        let mut parent = vec![0; self.len()];
        for (&(.., s), &o) in order.iter().zip(&owner) {
            parent[s as usize] = o;
            next.on_border[o as usize] |= self.on_border[s as usize];
        }
        // Each link once (adjacency lists hold both directions) and only between parents: a
        // quarter of the pairs to sort (level 0 -> 1 of the 100K-face dragon at 512²: 41-49 ms before).
        let pairs = (0..self.len() as u32)
            .into_par_iter()
            .flat_map_iter(|s| self.neighbours(s).iter().filter(move |&&t| s < t).map(move |&t| (s, t)))
            .map(|(s, t)| (parent[s as usize], parent[t as usize]))
            .filter(|(a, b)| a != b)
            .collect();
        next.set_adjacency(pairs);
        next.finer_parent = parent;
        next
    }
}

/// The order of the texel sums (in texel order, then chart) along a Z (Morton) curve over their
/// texels, then chart: every level's surfels are numbered so (`SurfelLevel::coarser` keeps it), so
/// a ball's surfels lie in few cache lines, where in row order its rows are a level's width apart
/// (the search is bound by memory latency: the sums took 1.1-1.4x as long). A texel's sums are
/// consecutive and in chart order already: only the texels' runs are sorted (sorting the sums
/// themselves took 10-12 ms of the armadillo's 512² pyramid).
fn z_order(sums: &[Fragment], width: usize) -> Vec<u32> {
    let starts: Vec<u32> =
        (0..sums.len() as u32).filter(|&k| k == 0 || sums[k as usize].texel != sums[k as usize - 1].texel).collect();
    let mut runs: Vec<(u64, u32, u32)> = starts
        .par_iter()
        .enumerate()
        .map(|(r, &start)| {
            let t = sums[start as usize].texel as usize;
            (morton(t % width, t / width), start, starts.get(r + 1).copied().unwrap_or(sums.len() as u32))
        })
        .collect();
    runs.par_sort_unstable();
    runs.par_iter().flat_map_iter(|&(_, start, end)| start..end).collect()
}

/// The surfel pyramid of one frame; level 0 has the atlas's resolution.
#[derive(Debug, Clone, Default)]
pub struct Surfels {
    /// Finest first; level `k` has `ceil(W / 2^k)` texels per side. The finest is built with the
    /// pyramid, each coarser level on its first use ([`Surfels::level`]): a ball's level is fitted
    /// to the radius, and the values at the vertices of most meshes read the finest alone (the
    /// coarser levels were 16-21 ms of a 512² pyramid's 60-77 ms).
    levels: Vec<OnceLock<SurfelLevel>>,
}

impl Surfels {
    /// A pyramid without levels (a build cut short by a stop request).
    pub const fn empty() -> Self {
        Self { levels: Vec::new() }
    }

    /// Clips every face of the frame to the texels of a `width`² grid and builds the finest level,
    /// with centroids on `surface`.
    pub fn build(topology: &Topology, frame: &Frame, width: usize, surface: Surface) -> Self {
        let smooth = surface == Surface::Smooth;
        let sums = texel_sums(topology, frame, width, smooth);
        // A stopped build is dropped (`Atlas::surfels`): no step after a stop runs on.
        if cancel::requested() {
            return Self::default();
        }
        let (seams, borders) = boundary_points(topology, width);
        if cancel::requested() {
            return Self::default();
        }
        let Some(finest) = SurfelLevel::finest(width, sums, &seams, &borders) else {
            return Self::default();
        };
        let mut widths = vec![width];
        while let Some(&last) = widths.last().filter(|&&w| w > SMALLEST_LEVEL) {
            widths.push(last.div_ceil(2));
        }
        let levels = widths.iter().map(|_| OnceLock::new()).collect::<Vec<_>>();
        let _ = levels[0].set(finest);
        Self { levels }
    }

    /// Number of levels (the coarsest has at most 4 texels per side).
    pub fn n_levels(&self) -> usize {
        self.levels.len()
    }

    /// Level `k` (`k < n_levels()`), made from the level below on its first use (outside the
    /// cell, as `Atlas`'s other parts: two threads asking at once may both make it; one is kept).
    pub fn level(&self, k: usize) -> &SurfelLevel {
        let cell = &self.levels[k];
        if let Some(level) = cell.get() {
            return level;
        }
        let built = self.level(k - 1).coarser();
        cell.get_or_init(|| built)
    }

    /// The surfel of `level` that holds the finest surfel `s`.
    pub fn ancestor(&self, mut s: u32, level: usize) -> u32 {
        for k in 1..=level {
            s = self.level(k).finer_parent[s as usize];
        }
        s
    }
}

#[cfg(test)]
mod tests;
