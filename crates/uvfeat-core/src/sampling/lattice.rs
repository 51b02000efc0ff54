//! One sample set shared by a tile of texels (issue 12, `sampling = "shared"`, DESIGN.md §1.4.7).
//!
//! The per-texel samplers draw `N` points for every texel, although the neighbourhoods of nearby
//! texels cover nearly the same surface: at r = 4 % of a 100K-face torus a texel's ellipse holds
//! about 800 computation texels, so every surface point was located and evaluated for hundreds of
//! texels. Here the points are placed once per group of texels, on a regular lattice in the
//! sampling plane of the group's centre `c` (its metric ellipse `E`, so that a lattice cell stands
//! for the same surface area in every direction), and located once: the same interior shortcut as
//! the fast path, and for the others a short walk continuing the route of the neighbour one cell
//! nearer `c`. Every texel `t` then keeps the points of its own sampling domain, the disk of
//! radius `m` (the margin) around its place `w_t = E^-1 (s_t - c)`, which the lattice's spacing
//! fills with `N` points on average, as the per-texel pattern has; or, where the coverage check
//! grew the domain, the grown domain around `c` that the whole group shares.
//!
//! Each texel still sums the same integrand with the same weights `dA = J |det M_path| a`; only the
//! points are shared with the neighbours instead of turned per texel. The texels differ only in
//! the ball test and the sums, which run over structure-of-arrays f32 columns sorted along the
//! lattice's longer side, so that a texel reads one contiguous run of them
//! (`features/lattice_statistics.rs`).

use super::centre::Centre;
use super::located::locate_target;
use super::pattern::pcg_hash;
use super::reach::{Reach, DIRECTIONS};
use super::sample::unit_ellipse;
use super::settings::SamplerSettings;
use crate::atlas::Atlas;
use crate::relocation::{interior_face, locate_with, Home, Located, Relocation};
use glam::{DMat2, DVec2, IVec2, Vec2, Vec3};

/// How a located lattice point was reached from the centre: the face it lies in and the seams'
/// linear maps on the way, which its neighbours farther out continue.
#[derive(Debug, Clone, Copy)]
struct Route {
    home: Home,
    m_path: DMat2,
    jumps: u32,
}

/// A lattice point that reached no surface: the path met a mesh border, or no way was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LostPoint {
    /// Its place in the sampling plane.
    pub w: Vec2,
    /// `true` at a mesh border, `false` when the relocation failed.
    pub border: bool,
}

/// The located lattice points of one tile, column by column (f32), sorted by `w[axis]`.
#[derive(Debug, Clone)]
pub struct TileLattice {
    /// Place of each point in the sampling plane of the tile's centre (pattern units: the centre's
    /// ball has radius about 1 there).
    pub w: [Vec<f32>; 2],
    /// Surface point, relative to the patches' origin.
    pub q: [Vec<f32>; 3],
    /// Unit normal (empty unless the settings ask for normals).
    pub normal: [Vec<f32>; 3],
    /// Surface area the point stands for.
    pub area: Vec<f32>,
    /// The column of `w` the points are sorted by.
    pub axis: usize,
    /// Points that reached no surface.
    pub lost: Vec<LostPoint>,
    /// The domains it covers.
    pub domain: LatticeDomain,
    /// The radius of a texel's disk, or of the grown domain around the centre.
    pub margin: f32,
    /// Side of a lattice cell, in pattern units.
    pub spacing: f32,
}

/// A texel as its tile's lattice sees it.
#[derive(Debug, Clone, Copy)]
pub struct LatticeTexel {
    /// Its place in the lattice's sampling plane.
    pub place: Vec2,
    /// Its centre `p`, relative to the patches' origin.
    pub position: Vec3,
    /// Its unit normal.
    pub normal: Vec3,
}

/// The sampling plane of a tile: where its texels lie in the pattern units of its centre.
#[derive(Debug, Clone, Copy)]
pub struct TilePlane {
    /// The tile's centre.
    pub centre: Centre,
    /// Parametric offset from the centre to pattern units, `E^-1`.
    pub to_pattern: DMat2,
    ellipse: DMat2,
}

impl TilePlane {
    /// The plane of `centre` with the sampler's radius.
    pub fn new(centre: Centre, settings: &SamplerSettings) -> Self {
        let ellipse = unit_ellipse(&centre, settings);
        Self { centre, to_pattern: ellipse.inverse(), ellipse }
    }

    /// The place of the parametric point `uv` of the centre's chart.
    pub fn place(&self, uv: DVec2) -> Vec2 {
        (self.to_pattern * (uv - self.centre.uv)).as_vec2()
    }

    /// The parametric point of the centre's chart at place `w`.
    fn uv(&self, w: Vec2) -> DVec2 {
        self.centre.uv + self.ellipse * w.as_dvec2()
    }
}

/// Where the lattice's points lie in their cells: the same offset for every tile, drawn from the
/// seed (a Cranley–Patterson shift of the whole lattice), so that runs with other seeds measure
/// the quadrature's own error.
fn lattice_offset(seed: u64) -> Vec2 {
    let h = pcg_hash(seed as u32 ^ pcg_hash((seed >> 32) as u32 ^ 0x5eed));
    Vec2::new((h & 0xffff) as f32, (h >> 16) as f32) / 65_536.0
}

/// Texels' worth of cells a lattice may hold beyond one pattern per texel (see `build`).
const SMALL_GROUP: usize = 8;

/// The sampling domains a lattice covers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LatticeDomain {
    /// Every texel's own disk of this radius (the margin) around its place.
    Disks(f64),
    /// One star-shaped domain around the tile's centre for every texel, grown by the coverage
    /// check (see [`Reach`]), widened by the farthest texel's distance from the centre so that it
    /// holds that texel's ball wherever the centre's does.
    Grown(Reach),
}

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
        let cell_uv_area = f64::from(spacing * spacing) * plane.ellipse.determinant().abs();
        // About the disk's share of the box of cells is kept (the points' columns are pushed to).
        let expected = (f64::from(cells.x) * f64::from(cells.y) * 0.8) as usize + Self::PADDING;
        let column = || Vec::with_capacity(expected);
        let mut lattice = Self {
            w: [column(), column()],
            q: [column(), column(), column()],
            normal: if settings.with_normals { [column(), column(), column()] } else { Default::default() },
            area: column(),
            axis,
            lost: Vec::new(),
            domain,
            margin,
            spacing,
        };
        let offset = lattice_offset(seed);
        let (columns, rows) = (cells.x as i32, cells.y as i32);
        let index = |cell: IVec2| (cell.y * columns + cell.x) as usize;
        let place = |cell: IVec2| (first + cell.as_vec2() + offset) * spacing;
        // Only points some texel's domain holds: within the margin of the places' box, or within
        // the grown domain of the centre.
        let held = |w: Vec2| {
            let out = w - w.clamp(low, high);
            let distance = out.length();
            distance < narrowest + widening
                || (distance < widest + widening
                    && distance < reach.at(f64::from(out.y.atan2(out.x))) as f32 + widening)
        };
        // First the points in the centre's chart, row by row (in cache order), then the others from
        // the centre outwards (L1 order), so that the neighbour one cell towards the centre has
        // been located and its route can be continued.
        let mut routes: Vec<Option<Route>> = vec![None; (columns * rows) as usize];
        let mut given_up = vec![false; (columns * rows) as usize];
        let mut crossing = Vec::new();
        for cell in (0..rows).flat_map(|b| (0..columns).map(move |a| IVec2::new(a, b))) {
            let w = place(cell);
            if held(w) {
                match lattice.interior(atlas, plane, w, cell_uv_area, settings) {
                    Some(route) => routes[index(cell)] = Some(route),
                    None => crossing.push(cell),
                }
            }
        }
        let origin = (-first - offset).round().as_ivec2().clamp(IVec2::ZERO, IVec2::new(columns - 1, rows - 1));
        crossing.sort_by_key(|cell| (*cell - origin).abs().element_sum());
        for cell in crossing {
            let towards_centre = origin - cell;
            let step = if towards_centre.x.abs() >= towards_centre.y.abs() {
                IVec2::new(towards_centre.x.signum(), 0)
            } else {
                IVec2::new(0, towards_centre.y.signum())
            };
            let (w, nearer) = (place(cell), index(cell + step));
            // Past a point that even a walk from the centre could not reach (out of seam jumps:
            // round a pole's fan of seams), the walk would only go farther: no walk at all.
            let from = routes[nearer].map(|route| (route, place(cell + step)));
            let located =
                if given_up[nearer] { Located::Missing } else { Self::locate(atlas, plane, w, from, settings) };
            given_up[index(cell)] = given_up[nearer] || (from.is_none() && located == Located::Missing);
            routes[index(cell)] = lattice.keep(atlas, w, located, cell_uv_area, settings);
        }
        lattice.sort();
        lattice.pad(settings);
        Some(lattice)
    }

    /// Inert points after the last one, so that a pass reading [`Self::PADDING`] points at a time
    /// never reads past the columns: far off every domain, at the origin, with no area.
    pub const PADDING: usize = 8;

    fn pad(&mut self, settings: &SamplerSettings) {
        for _ in 0..Self::PADDING {
            self.push_f32(Vec2::INFINITY, Vec3::ZERO, Vec3::ZERO, 0.0, settings);
        }
    }

    /// Keeps the lattice point `w` when it lies well inside the centre's chart (the fast path's
    /// shortcut: one table load, no walk), with its route; `None` when it may lie elsewhere.
    fn interior(
        &mut self,
        atlas: &Atlas,
        plane: &TilePlane,
        w: Vec2,
        uv_area: f64,
        settings: &SamplerSettings,
    ) -> Option<Route> {
        let (uv, chart) = (plane.uv(w), plane.centre.chart);
        let face = interior_face(atlas, uv, chart)?;
        let inside = Located::Inside { chart, uv, m_path: DMat2::IDENTITY, jumps: 0, face: Some(face) };
        self.keep(atlas, w, inside, uv_area, settings)
    }

    /// Locates the lattice point `w` off the centre's chart interior: it continues the route of
    /// `from`, its neighbour one cell towards the centre, by one lattice step (a walk of a face or
    /// so instead of one from the centre), or walks from the centre when the neighbour has no route.
    fn locate(
        atlas: &Atlas,
        plane: &TilePlane,
        w: Vec2,
        from: Option<(Route, Vec2)>,
        settings: &SamplerSettings,
    ) -> Located {
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

    /// Keeps the surface point of the lattice point `w` located at `located` (or counts it lost)
    /// and returns its route.
    fn keep(
        &mut self,
        atlas: &Atlas,
        w: Vec2,
        located: Located,
        uv_area: f64,
        settings: &SamplerSettings,
    ) -> Option<Route> {
        let patches = &atlas.patches.faces;
        match located {
            Located::Inside { uv, m_path, face: Some(face), jumps, .. } if patches[face as usize].chart >= 0 => {
                let patch = &patches[face as usize];
                let local = uv.as_vec2() - Vec2::from_array(patch.uv0);
                let area = f64::from(patch.area_element) * uv_area * m_path.determinant().abs();
                let normal = if settings.with_normals { patch.normal_at(local) } else { Vec3::ZERO };
                self.push_f32(w, patch.position_at(local), normal, area as f32, settings);
                Some(Route { home: Home { face, point: uv }, m_path, jumps })
            }
            Located::Inside { chart, uv, m_path, face, .. } => {
                match settings.lookup.evaluate(atlas, face, uv, chart) {
                    Some(point) => {
                        let area = point.area_element * uv_area * m_path.determinant().abs();
                        let relative = (point.position - atlas.patches.origin).as_vec3();
                        self.push_f32(w, relative, point.normal.as_vec3(), area as f32, settings);
                    }
                    None => self.lost.push(LostPoint { w, border: false }),
                }
                None
            }
            Located::Border => {
                self.lost.push(LostPoint { w, border: true });
                None
            }
            Located::Missing => {
                self.lost.push(LostPoint { w, border: false });
                None
            }
        }
    }

    fn push_f32(&mut self, w: Vec2, relative: Vec3, normal: Vec3, area: f32, settings: &SamplerSettings) {
        self.w[0].push(w.x);
        self.w[1].push(w.y);
        for (column, value) in self.q.iter_mut().zip(relative.to_array()) {
            column.push(value);
        }
        if settings.with_normals {
            for (column, value) in self.normal.iter_mut().zip(normal.to_array()) {
                column.push(value);
            }
        }
        self.area.push(area);
    }

    /// Sorts the points by `w[axis]`, so that a texel's domain is one run of them.
    fn sort(&mut self) {
        let mut order: Vec<u32> = (0..self.area.len() as u32).collect();
        let key = &self.w[self.axis];
        order.sort_unstable_by(|&a, &b| key[a as usize].total_cmp(&key[b as usize]));
        let permute = |column: &mut Vec<f32>| {
            if !column.is_empty() {
                *column = order.iter().map(|&k| column[k as usize]).collect();
            }
        };
        self.w.iter_mut().chain(&mut self.q).chain(&mut self.normal).for_each(permute);
        permute(&mut self.area);
    }

    /// The run of points whose `w[axis]` lies within the margin of `place` (every point of a grown
    /// domain, which all texels share).
    pub fn run(&self, place: Vec2) -> std::ops::Range<usize> {
        if let LatticeDomain::Grown(_) = self.domain {
            return 0..self.len();
        }
        let key = &self.w[self.axis];
        let at = place[self.axis];
        let start = key.partition_point(|&x| x <= at - self.margin);
        let end = key.partition_point(|&x| x < at + self.margin);
        start..end.max(start)
    }

    /// The directions (see [`Reach`]) in which points of `texel`'s disk domain that lie in the ball
    /// of `radius` reach `rim_fraction` of the margin or more: where its domain must grow.
    pub fn rim_directions(&self, texel: &LatticeTexel, radius: f64, rim_fraction: f32) -> [bool; DIRECTIONS] {
        let mut marked = [false; DIRECTIONS];
        let (outer, rim) = ((radius * radius) as f32, (rim_fraction * self.margin).powi(2));
        for k in self.run(texel.place) {
            let dw = Vec2::new(self.w[0][k], self.w[1][k]) - texel.place;
            let q = Vec3::new(self.q[0][k], self.q[1][k], self.q[2][k]);
            let dw2 = dw.length_squared();
            if dw2 >= rim && dw2 < self.margin * self.margin && q.distance_squared(texel.position) < outer {
                let (below, above, _) = Reach::bracket(f64::from(dw.y.atan2(dw.x)));
                marked[below] = true;
                marked[above] = true;
            }
        }
        marked
    }

    /// Points located.
    pub fn len(&self) -> usize {
        self.area.len().saturating_sub(Self::PADDING)
    }

    /// `true` when no point reached the surface.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
