//! One sample set shared by a tile of texels (`sampling = "shared"`, DESIGN.md §1.4.7).
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
use super::reach::{Reach, DIRECTIONS};
use super::sample::unit_ellipse;
use super::settings::SamplerSettings;
use glam::{DMat2, DVec2, Vec2, Vec3};

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
    /// The column the points are sorted by: of `w` for disks, of `q` for a grown domain.
    pub axis: usize,
    /// Points that reached no surface, sorted by `w[axis]`.
    pub lost: Vec<LostPoint>,
    /// How many of them met a mesh border.
    pub lost_at_border: u32,
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
    pub(super) ellipse: DMat2,
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
    pub(super) fn uv(&self, w: Vec2) -> DVec2 {
        self.centre.uv + self.ellipse * w.as_dvec2()
    }
}

/// A point given to [`TileLattice::from_points`]: `(w, q, normal, area)`.
pub type PointRecord = (Vec2, Vec3, Vec3, f32);

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
    /// Inert points after the last one, so that a pass reading up to [`Self::PADDING`] points at a
    /// time (16 with AVX-512) never reads past the columns: far off every domain, at the origin,
    /// with no area.
    pub const PADDING: usize = 16;

    /// A lattice of the given points with disk domains of radius `margin`, sorted along `w.x` and
    /// padded as the builder does: for tests and benchmarks of the sums, which need no atlas.
    /// Points are `(w, q, normal, area)`; `with_normals` keeps the normals' columns.
    pub fn from_points(points: &[PointRecord], margin: f32, spacing: f32, with_normals: bool) -> Self {
        let mut sorted = points.to_vec();
        sorted.sort_by(|a, b| a.0.x.total_cmp(&b.0.x));
        let inert = (Vec2::INFINITY, Vec3::ZERO, Vec3::ZERO, 0.0);
        sorted.extend(std::iter::repeat_n(inert, Self::PADDING));
        let column = |get: &dyn Fn(&PointRecord) -> f32| sorted.iter().map(get).collect::<Vec<f32>>();
        let normal = |k: usize| if with_normals { column(&|p| p.2[k]) } else { Vec::new() };
        Self {
            w: [column(&|p| p.0.x), column(&|p| p.0.y)],
            q: [column(&|p| p.1.x), column(&|p| p.1.y), column(&|p| p.1.z)],
            normal: [normal(0), normal(1), normal(2)],
            area: column(&|p| p.3),
            axis: 0,
            lost: Vec::new(),
            lost_at_border: 0,
            domain: LatticeDomain::Disks(f64::from(margin)),
            margin,
            spacing,
        }
    }

    /// The run of points that may lie in `texel`'s domain: those whose `w[axis]` lies within the
    /// margin of its place, or, on a grown domain (which every texel shares), whose `q[axis]` lies
    /// within `ball` of its point (the run then holds every point of the domain within `ball`).
    pub fn run(&self, texel: &LatticeTexel, ball: f32) -> std::ops::Range<usize> {
        let (key, at, half_width) = match self.domain {
            LatticeDomain::Disks(_) => (&self.w[self.axis], texel.place[self.axis], self.margin),
            // Widened a little so that rounding in `at -/+ ball` never drops a point of the ball.
            LatticeDomain::Grown(_) => (&self.q[self.axis], texel.position[self.axis], ball * (1.0 + 1e-4) + 1e-6),
        };
        let start = key[..self.len()].partition_point(|&x| x <= at - half_width);
        let end = key[..self.len()].partition_point(|&x| x < at + half_width);
        start..end.max(start)
    }

    /// The directions (see [`Reach`]) in which points of `texel`'s disk domain that lie in the ball
    /// of `radius` reach `rim_fraction` of the margin or more: where its domain must grow.
    pub fn rim_directions(&self, texel: &LatticeTexel, radius: f64, rim_fraction: f32) -> [bool; DIRECTIONS] {
        let mut marked = [false; DIRECTIONS];
        let (outer, rim) = ((radius * radius) as f32, (rim_fraction * self.margin).powi(2));
        for k in self.run(texel, 0.0) {
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

    /// The lost points of the domain of the texel at `place`: at a mesh border, and missing (all
    /// those of a grown domain, which every texel shares).
    pub fn lost_in_domain(&self, place: Vec2) -> (u32, u32) {
        if let LatticeDomain::Grown(_) = self.domain {
            return (self.lost_at_border, self.lost.len() as u32 - self.lost_at_border);
        }
        let at = place[self.axis];
        let start = self.lost.partition_point(|lost| lost.w[self.axis] <= at - self.margin);
        let in_disk = self.lost[start..]
            .iter()
            .take_while(|lost| lost.w[self.axis] < at + self.margin)
            .filter(|lost| (lost.w - place).length_squared() < self.margin * self.margin);
        in_disk.fold(
            (0, 0),
            |(border, missing), lost| if lost.border { (border + 1, missing) } else { (border, missing + 1) },
        )
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
