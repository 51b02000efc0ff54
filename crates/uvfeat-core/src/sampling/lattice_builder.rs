//! Placing and locating the points of a tile's lattice (`sampling/lattice.rs`): the cells some
//! texel's domain holds, first those well inside the centre's chart (one table load each), then
//! the others from the centre outwards, each continuing the route of its neighbour one cell nearer
//! the centre.

use super::lattice::{LatticeDomain, LostPoint, TileLattice, TilePlane};
use super::located::locate_target;
use super::pattern::pcg_hash;
use super::reach::{Reach, DIRECTIONS};
use super::settings::SamplerSettings;
use crate::atlas::Atlas;
use crate::mesh::compressed_rows;
use crate::raster::FacePatch;
use crate::relocation::{interior_of_chart, locate_with, Home, Located, Relocation};
use glam::{DMat2, IVec2, Vec2, Vec3};

/// How a located lattice point was reached from the centre: the face it lies in and the seams'
/// linear maps on the way, which its neighbours farther out continue.
#[derive(Debug, Clone, Copy)]
struct Route {
    home: Home,
    m_path: DMat2,
    jumps: u32,
}

/// What became of a cell of the lattice's box: eight bytes, where the routes themselves (64) made
/// the cells of a lattice at r = 2 % 80 KB to clear and write, more than the L1 cache holds.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Cell {
    /// Not located (yet, or never: no domain holds it).
    Waiting,
    /// Located well inside the centre's chart, on this face: its route is the straight one.
    Interior(u32),
    /// Located with the route `routes[k]`, which its neighbours farther out continue.
    Routed(u32),
    /// Lost, or evaluated where no route leads on.
    Ended,
    /// Even a walk from the centre could not reach it (out of seam jumps: round a pole's fan of
    /// seams); a walk to a cell beyond it would only go farther, so none is tried.
    GivenUp,
}

/// Where the lattice's points lie in their cells: the same offset for every tile, drawn from the
/// seed (a Cranley–Patterson shift of the whole lattice), so that runs with other seeds measure
/// the quadrature's own error.
fn lattice_offset(seed: u64) -> Vec2 {
    let h = pcg_hash(seed as u32 ^ pcg_hash((seed >> 32) as u32 ^ 0x5eed));
    Vec2::new((h & 0xffff) as f32, (h >> 16) as f32) / 65_536.0
}

/// Points ahead of the one evaluated whose face's patch is fetched.
const PREFETCH_AHEAD: usize = 8;

/// Asks the CPU to bring `patch` into the cache (a hint: nothing where there is no such instruction).
#[inline(always)]
fn prefetch(patch: Option<&FacePatch>) {
    #[cfg(target_arch = "x86_64")]
    if let Some(patch) = patch {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let start: *const i8 = (patch as *const FacePatch).cast();
        // SAFETY: a prefetch never faults and reads nothing the program sees (SSE is part of
        // x86_64); both addresses lie in the patch, which spans two cache lines.
        unsafe {
            _mm_prefetch::<_MM_HINT_T0>(start);
            _mm_prefetch::<_MM_HINT_T0>(start.add(64));
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = patch;
}

/// Texels' worth of cells a lattice may hold beyond one pattern per texel (see [`LatticeBuilder::new`]).
const SMALL_GROUP: usize = 8;

impl TileLattice {
    /// Places and locates the lattice covering `domain` for texels at `places` in the plane of its
    /// centre, with `samples` points per domain; `None` where it would hold more cells than
    /// `samples` per texel and a few more.
    pub fn build(
        atlas: &Atlas,
        plane: &TilePlane,
        places: &[Vec2],
        domain: LatticeDomain,
        samples: usize,
        seed: u64,
        settings: &SamplerSettings,
    ) -> Option<Self> {
        let mut builder = LatticeBuilder::new(atlas, plane, places, domain, samples, seed, settings)?;
        builder.locate();
        Some(builder.finish())
    }
}

/// Distance in cells (maximum norm) from the centre's cell from which a cell whose walk from the
/// centre failed gives up the cells beyond it without a walk. At a pole of a patchwork sphere at
/// r = 0.8, the walk to the point in the centre's own cell went round the pole's fan of slits
/// until it ran out of seam jumps, and the whole lattice was given up: six texels had no samples,
/// where the exact path's own walks reached 110 points each.
const HANDS_DOWN_FAILURE: i32 = 3;

/// A tile's lattice while its points are located.
struct LatticeBuilder<'a> {
    atlas: &'a Atlas,
    plane: &'a TilePlane,
    settings: &'a SamplerSettings,
    lattice: TileLattice,
    /// The box of the texels' places (both zero for a grown domain, which lies around the centre).
    low: Vec2,
    high: Vec2,
    reach: Reach,
    /// Narrowest and widest margin of the reach, and the farthest texel's distance from the centre.
    narrowest: f32,
    widest: f32,
    widening: f32,
    /// The place of cell (0, 0) less the offset, in cells, and the offset.
    first: Vec2,
    offset: Vec2,
    columns: i32,
    rows: i32,
    /// The parametric area of a cell.
    cell_uv_area: f64,
    cells: Vec<Cell>,
    routes: Vec<Route>,
    /// The line of cells across the lattice's axis of each point kept (see [`Self::sort`]).
    lines: Vec<u32>,
}

impl<'a> LatticeBuilder<'a> {
    /// The empty lattice (see [`TileLattice::build`]).
    fn new(
        atlas: &'a Atlas,
        plane: &'a TilePlane,
        places: &[Vec2],
        domain: LatticeDomain,
        samples: usize,
        seed: u64,
        settings: &'a SamplerSettings,
    ) -> Option<Self> {
        let (mut low, mut high) =
            places.iter().fold((Vec2::INFINITY, Vec2::NEG_INFINITY), |(l, h), &w| (l.min(w), h.max(w)));
        let (reach, widening) = match domain {
            LatticeDomain::Disks(margin) => (Reach::uniform(margin), 0.0),
            LatticeDomain::Grown(reach) => {
                (low, high) = (Vec2::ZERO, Vec2::ZERO);
                (reach, places.iter().map(|w| w.length()).fold(0.0, f32::max))
            }
        };
        let margins = (0..DIRECTIONS).map(|k| reach.margin(k) as f32);
        let (narrowest, widest) = (margins.clone().fold(f32::MAX, f32::min), margins.fold(0.0, f32::max));
        let margin = widest + widening;
        // `samples` points per domain, as the per-texel pattern spreads its points over a grown one.
        let domain_area =
            std::f64::consts::PI * (0..DIRECTIONS).map(|k| reach.margin(k).powi(2)).sum::<f64>() / DIRECTIONS as f64;
        let spacing = (domain_area / samples as f64).sqrt() as f32;
        let first = ((low - margin) / spacing).floor();
        let cells = ((high + margin) / spacing).ceil() - first;
        // Where the texels lie far apart against their balls (a radius below the texel spacing),
        // one lattice over them would locate far more points than the texels' own patterns. A
        // few texels (a chart's corner in a tile) still share one: their patterns' domains are
        // as large at large radii, and each texel alone gathers twice and probes.
        if !(f64::from(cells.x) * f64::from(cells.y) <= (samples * (places.len() + SMALL_GROUP)) as f64) {
            return None;
        }
        let axis = usize::from(high.y - low.y > high.x - low.x);
        // About the disk's share of the box of cells is kept (the points' columns are pushed to).
        let expected = (f64::from(cells.x) * f64::from(cells.y) * 0.8) as usize + TileLattice::PADDING;
        let column = || Vec::with_capacity(expected);
        let lattice = TileLattice {
            w: [column(), column()],
            q: [column(), column(), column()],
            normal: if settings.with_normals { [column(), column(), column()] } else { Default::default() },
            area: column(),
            axis,
            lost: Vec::new(),
            lost_at_border: 0,
            domain,
            margin,
            spacing,
        };
        let (columns, rows) = (cells.x as i32, cells.y as i32);
        Some(Self {
            atlas,
            plane,
            settings,
            lattice,
            low,
            high,
            reach,
            narrowest,
            widest,
            widening,
            first,
            offset: lattice_offset(seed),
            columns,
            rows,
            cell_uv_area: f64::from(spacing * spacing) * plane.ellipse.determinant().abs(),
            cells: vec![Cell::Waiting; (columns * rows) as usize],
            routes: Vec::new(),
            lines: Vec::with_capacity(expected),
        })
    }

    fn index(&self, cell: IVec2) -> usize {
        (cell.y * self.columns + cell.x) as usize
    }

    fn place(&self, cell: IVec2) -> Vec2 {
        (self.first + cell.as_vec2() + self.offset) * self.lattice.spacing
    }

    /// `true` for points some texel's domain holds: within the margin of the places' box, or
    /// within the grown domain of the centre.
    fn held(&self, w: Vec2) -> bool {
        let out = w - w.clamp(self.low, self.high);
        let distance = out.length();
        distance < self.narrowest + self.widening
            || (distance < self.widest + self.widening
                && distance < self.reach.at(f64::from(out.y.atan2(out.x))) as f32 + self.widening)
    }

    /// The route a located cell's neighbours farther out continue.
    fn route(&self, cell: IVec2) -> Option<Route> {
        match self.cells[self.index(cell)] {
            Cell::Interior(face) => {
                let point = self.plane.uv(self.place(cell));
                Some(Route { home: Home { face, point }, m_path: DMat2::IDENTITY, jumps: 0 })
            }
            Cell::Routed(k) => Some(self.routes[k as usize]),
            Cell::Waiting | Cell::Ended | Cell::GivenUp => None,
        }
    }

    /// Locates the points some domain holds: first those in the centre's chart, row by row (in
    /// cache order), then the others from the centre outwards (L1 order), so that the neighbour
    /// one cell towards the centre has been located and its route can be continued.
    fn locate(&mut self) {
        let mut crossing = self.locate_interior();
        let origin = (-self.first - self.offset)
            .round()
            .as_ivec2()
            .clamp(IVec2::ZERO, IVec2::new(self.columns - 1, self.rows - 1));
        crossing.sort_by_key(|cell| (*cell - origin).abs().element_sum());
        for cell in crossing {
            let towards_centre = origin - cell;
            let step = if towards_centre.x.abs() >= towards_centre.y.abs() {
                IVec2::new(towards_centre.x.signum(), 0)
            } else {
                IVec2::new(0, towards_centre.y.signum())
            };
            let w = self.place(cell);
            let from = self.route(cell + step).map(|route| (route, self.place(cell + step)));
            // The staircase of cells funnels a wide angle through a cell near the centre's (the
            // centre's own cell, every other): a walk that failed there says nothing of the
            // cells beyond it.
            let near_centre = (cell + step - origin).abs().max_element() < HANDS_DOWN_FAILURE;
            let given_up = self.cells[self.index(cell + step)] == Cell::GivenUp && !near_centre;
            let located = if given_up { Located::Missing } else { self.locate_from(w, from) };
            let gives_up = given_up || (from.is_none() && located == Located::Missing);
            let route = self.keep(cell, located);
            let at = self.index(cell);
            self.cells[at] = match route {
                _ if gives_up => Cell::GivenUp,
                Some(route) => {
                    self.routes.push(route);
                    Cell::Routed(self.routes.len() as u32 - 1)
                }
                None => Cell::Ended,
            };
        }
    }

    /// Keeps the held points that lie well inside the centre's chart (the fast path's shortcut:
    /// one table load, no walk), row by row (in cache order), and returns the other held cells.
    /// The table is read in a pass of its own, and each face's patch is fetched a few points
    /// ahead: the loads no longer wait on each other (one loop of place, load, evaluate spent a
    /// quarter of the lattice's building on the table's load).
    fn locate_interior(&mut self) -> Vec<IVec2> {
        let (atlas, chart) = (self.atlas, self.plane.centre.chart);
        let table = &atlas.coverage().interior_face;
        let mut held = Vec::with_capacity(self.cells.len());
        for cell in (0..self.rows).flat_map(|b| (0..self.columns).map(move |a| IVec2::new(a, b))) {
            let w = self.place(cell);
            if self.held(w) {
                let slot = atlas.texel_coordinates(self.plane.uv(w)).map(|(i, j)| table.index(i, j));
                held.push((cell, slot.unwrap_or(usize::MAX)));
            }
        }
        let faces: Vec<u32> = held.iter().map(|&(_, slot)| table.get(slot).copied().unwrap_or(u32::MAX)).collect();
        let mut crossing = Vec::new();
        let patches = &atlas.patches().faces;
        for (k, (&(cell, _), &face)) in held.iter().zip(&faces).enumerate() {
            if let Some(&ahead) = faces.get(k + PREFETCH_AHEAD) {
                prefetch(patches.get(ahead as usize));
            }
            let Some(face) = interior_of_chart(atlas, face, chart) else {
                crossing.push(cell);
                continue;
            };
            let w = self.place(cell);
            let uv = self.plane.uv(w);
            let at = self.index(cell);
            let located = Located::Inside { chart, uv, m_path: DMat2::IDENTITY, jumps: 0, face: Some(face) };
            // A face without a patch (degenerate) was evaluated by the lookup: no route leads on.
            self.cells[at] = match self.keep(cell, located) {
                Some(_) => Cell::Interior(face),
                None => Cell::Ended,
            };
        }
        crossing
    }

    /// The lattice of the points located: sorted, and padded.
    fn finish(mut self) -> TileLattice {
        self.sort();
        for _ in 0..TileLattice::PADDING {
            self.push(Vec2::INFINITY, 0, Vec3::ZERO, Vec3::ZERO, 0.0);
        }
        self.lattice
    }

    /// Locates the lattice point `w` off the centre's chart interior: it continues the route of
    /// `from`, its neighbour one cell towards the centre, by one lattice step (a walk of a face or
    /// so instead of one from the centre), or walks from the centre when the neighbour has no route.
    fn locate_from(&self, w: Vec2, from: Option<(Route, Vec2)>) -> Located {
        let (atlas, plane, settings) = (self.atlas, self.plane, self.settings);
        match from {
            Some((route, w_from)) => {
                // The relocation of a target from the neighbour's point, in the chart its route
                // reached: the interior shortcut, else the walk.
                let target = route.home.point + route.m_path * (plane.ellipse * (w - w_from).as_dvec2());
                let chart = atlas.topology.face_chart[route.home.face as usize];
                let left = settings.max_jumps.saturating_sub(route.jumps);
                match locate_with(atlas, Relocation::Walk, route.home.point, Some(&route.home), chart, target, left) {
                    Located::Inside { chart, uv, m_path, jumps, face } => {
                        Located::Inside { chart, uv, m_path: m_path * route.m_path, jumps: jumps + route.jumps, face }
                    }
                    other => other,
                }
            }
            None => locate_target(atlas, &plane.centre, plane.uv(w), settings),
        }
    }

    /// Keeps the surface point of the lattice point of `cell` located at `located` (or counts it
    /// lost) and returns its route.
    fn keep(&mut self, cell: IVec2, located: Located) -> Option<Route> {
        let (atlas, settings) = (self.atlas, self.settings);
        let (w, line) = (self.place(cell), cell[self.lattice.axis] as u32);
        let patches = atlas.patches();
        match located {
            Located::Inside { uv, m_path, face: Some(face), jumps, .. } if patches.faces[face as usize].chart >= 0 => {
                let patch = &patches.faces[face as usize];
                let local = uv.as_vec2() - Vec2::from_array(patch.uv0);
                let area = f64::from(patch.area_element) * self.cell_uv_area * m_path.determinant().abs();
                let normal = if settings.with_normals { patch.normal_at(local) } else { Vec3::ZERO };
                self.push(w, line, patch.position_at(local), normal, area as f32);
                Some(Route { home: Home { face, point: uv }, m_path, jumps })
            }
            Located::Inside { chart, uv, m_path, face, .. } => {
                match settings.lookup.evaluate(atlas, face, uv, chart) {
                    Some(point) => {
                        let area = point.area_element * self.cell_uv_area * m_path.determinant().abs();
                        let relative = (point.position - patches.origin).as_vec3();
                        self.push(w, line, relative, point.normal.as_vec3(), area as f32);
                    }
                    None => self.lattice.lost.push(LostPoint { w, border: false }),
                }
                None
            }
            Located::Border => {
                self.lattice.lost.push(LostPoint { w, border: true });
                None
            }
            Located::Missing => {
                self.lattice.lost.push(LostPoint { w, border: false });
                None
            }
        }
    }

    /// Adds a point to the lattice's columns; `line` is its cell's index along the lattice's axis.
    fn push(&mut self, w: Vec2, line: u32, relative: Vec3, normal: Vec3, area: f32) {
        self.lines.push(line);
        let lattice = &mut self.lattice;
        lattice.w[0].push(w.x);
        lattice.w[1].push(w.y);
        for (column, value) in lattice.q.iter_mut().zip(relative.to_array()) {
            column.push(value);
        }
        if self.settings.with_normals {
            for (column, value) in lattice.normal.iter_mut().zip(normal.to_array()) {
                column.push(value);
            }
        }
        lattice.area.push(area);
    }

    /// Sorts the points so that a texel's domain is one run of them: by `w[axis]` for disks (the
    /// lost points too), by `q[axis]` along the points' widest spread for a grown domain, which
    /// every texel shares and whose points in its ball lie within the ball's width along that
    /// axis. The points of one line of cells across `w[axis]` share it, so the disks' points are
    /// counted into their lines (in the order they were located) instead of compared.
    fn sort(&mut self) {
        let order =
            if let LatticeDomain::Grown(_) = self.lattice.domain { self.grown_order() } else { self.line_order() };
        let lattice = &mut self.lattice;
        let permute = |column: &mut Vec<f32>| {
            if !column.is_empty() {
                *column = order.iter().map(|&k| column[k as usize]).collect();
            }
        };
        lattice.w.iter_mut().chain(&mut lattice.q).chain(&mut lattice.normal).for_each(permute);
        permute(&mut lattice.area);
        let axis = lattice.axis;
        if let LatticeDomain::Disks(_) = lattice.domain {
            lattice.lost.sort_unstable_by(|a, b| a.w[axis].total_cmp(&b.w[axis]));
        }
        lattice.lost_at_border = lattice.lost.iter().filter(|lost| lost.border).count() as u32;
    }

    /// The points' order by their lines of cells along `w[axis]`, in the order they were kept.
    fn line_order(&self) -> Vec<u32> {
        let lines = if self.lattice.axis == 0 { self.columns } else { self.rows };
        compressed_rows(lines as usize, self.lines.iter().enumerate().map(|(k, &line)| (line, k as u32))).1
    }

    /// The points' order along the coordinate of `q` of widest spread, which becomes the axis.
    fn grown_order(&mut self) -> Vec<u32> {
        let q = &self.lattice.q;
        let spread = |column: &Vec<f32>| {
            let (low, high) = column.iter().fold((f32::MAX, f32::MIN), |(l, h), &x| (l.min(x), h.max(x)));
            high - low
        };
        let axis = (0..3).max_by(|&a, &b| spread(&q[a]).total_cmp(&spread(&q[b]))).unwrap_or(0);
        let key = &q[axis];
        let mut order: Vec<u32> = (0..key.len() as u32).collect();
        order.sort_unstable_by(|&a, &b| key[a as usize].total_cmp(&key[b as usize]));
        self.lattice.axis = axis;
        order
    }
}
