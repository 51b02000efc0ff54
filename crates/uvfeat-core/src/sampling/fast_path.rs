//! The sampler's fast path. A pattern point whose target texel lies well inside the
//! centre's chart (see [`crate::relocation::interior_face`]) is reached without crossing anything,
//! and the exact path then evaluates the face that texel shows. The fast path does the same with
//! one load of [`Coverage::interior_face`] and one compact f32 [`FacePatch`], no walk, no search
//! and no f64 face map. Every other point is located by the exact path's relocation, and where
//! that ends in a known face (the walk always does), the patch of that face is evaluated too. So
//! both paths keep the same samples, the same faces and the same weights; they differ by f32
//! rounding only (compared in `tests/it/fast_path.rs`).
//!
//! On x86-64 CPUs with AVX2 and FMA the gathering runs in a copy compiled for them, chosen at run
//! time (rounding instructions instead of library calls, wider vectors for the batched stages);
//! elsewhere in the portable copy. Both evaluate the same operations in the same order, so their
//! results are the same.
//!
//! [`Coverage::interior_face`]: crate::raster::Coverage::interior_face
//! [`FacePatch`]: crate::raster::FacePatch

use super::centre::Centre;
use super::domain::Domain;
use super::geodesic::{arc_distance, Geodesic};
use super::located::{locate_target, located_sample};
use super::sample::{unit_ellipse_area, Sample, SampleCounts};
use super::settings::{SamplerSettings, SamplingPath};
use crate::atlas::Atlas;
use crate::lookup::Lookup;
use crate::raster::{FacePatch, Precision};
use crate::relocation::{Located, Relocation};
use glam::{DVec2, DVec3, Vec2, Vec3};

/// `true` when the fast path serves `settings` on `atlas`: the choices whose interior samples it
/// reproduces (triangle lookup, walk or march relocation, arc geodesics, f32 buffers).
pub fn applies(atlas: &Atlas, settings: &SamplerSettings) -> bool {
    settings.path != SamplingPath::Exact
        && settings.lookup == Lookup::Triangle
        && settings.relocation != Relocation::PerChart
        && settings.geodesic == Geodesic::Arc
        && atlas.precision == Precision::F32
}

/// Pattern points handled per batch: each stage runs over a whole batch, so that the loads of the
/// face ids and then of the patches are independent of each other and overlap in the memory
/// system (one point after the other, a point's loads waited on the previous point's).
const BATCH: usize = 64;

/// One neighbourhood to gather: the atlas, its centre, the shared pattern and the centre's
/// sampling domain.
struct Gathering<'a> {
    atlas: &'a Atlas,
    centre: &'a Centre,
    pattern: &'a [DVec2],
    domain: &'a Domain<'a>,
}

/// As [`super::gather`] over `domain`, with interior samples on the fast path.
pub(super) fn gather(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    domain: &Domain,
    out: &mut Vec<Sample>,
) -> SampleCounts {
    let gathering = Gathering { atlas, centre, pattern, domain };
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU has the features `gather_avx2` is compiled for (checked just above).
        return unsafe { gather_avx2(&gathering, out) };
    }
    gather_batches(&gathering, out)
}

/// [`gather_batches`] compiled for AVX2 and FMA: a function of its own, so that the whole of it is
/// inlined here and compiled with these features (a closure passed to a generic wrapper was not).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn gather_avx2(gathering: &Gathering, out: &mut Vec<Sample>) -> SampleCounts {
    gather_batches(gathering, out)
}

/// A centre as the patches see it: positions relative to the patches' origin, in f32.
struct Kernel<'a> {
    patches: &'a [FacePatch],
    origin: DVec3,
    p: Vec3,
    normal: Vec3,
    /// `r^2` and `(1e-6 r)^2`: the ball test on squared distances.
    outer: f32,
    inner: f32,
    settings: &'a SamplerSettings,
}

/// A surface point evaluated on a patch: its offset `local` from the patch's `uv0`, and
/// `relative = q - p` with its squared length.
#[derive(Debug, Clone, Copy, Default)]
struct Evaluated {
    local: Vec2,
    relative: Vec3,
    squared: f32,
}

impl Evaluated {
    #[inline(always)]
    fn new(patch: &FacePatch, uv: Vec2, p: Vec3) -> Self {
        let local = uv - Vec2::from_array(patch.uv0);
        let relative = patch.position_at(local) - p;
        Self { local, relative, squared: relative.length_squared() }
    }
}

impl Kernel<'_> {
    /// Appends the sample `point` of `patch` when it lies in the ball; `true` if it did.
    #[inline(always)]
    fn accept(
        &self,
        patch: &FacePatch,
        point: Evaluated,
        uv_area: f64,
        pattern_index: u32,
        out: &mut Vec<Sample>,
    ) -> bool {
        let Evaluated { local, relative, squared } = point;
        if !(squared > self.inner && squared < self.outer) {
            return false;
        }
        let distance = squared.sqrt();
        let sin_alpha = f64::from(self.normal.dot(relative) / distance);
        let distance = f64::from(distance);
        out.push(Sample {
            position: (relative + self.p).as_dvec3() + self.origin,
            normal: if self.settings.with_normals { patch.normal_at(local).as_dvec3() } else { DVec3::NAN },
            area: f64::from(patch.area_element) * uv_area,
            distance,
            sin_alpha,
            geodesic: if self.settings.with_geodesic { arc_distance(distance, sin_alpha) } else { f64::NAN },
            pattern_index,
        });
        true
    }

    /// Evaluates `face` at `uv` and appends the sample when it lies in the ball.
    #[inline(always)]
    fn accept_at(&self, face: u32, uv: Vec2, uv_area: f64, pattern_index: u32, out: &mut Vec<Sample>) -> bool {
        let patch = &self.patches[face as usize];
        self.accept(patch, Evaluated::new(patch, uv, self.p), uv_area, pattern_index, out)
    }
}

/// Where the points of one batch land, computed lane by lane in f32 (vectorised): the parametric
/// target, the factor `m(phi)^2` of its cell area, and where the interior face of the geometry
/// texel under it is stored (`u32::MAX` off the domain).
struct Landing {
    u: [f32; BATCH],
    v: [f32; BATCH],
    area_scale: [f64; BATCH],
    texel: [u32; BATCH],
}

impl Landing {
    #[inline(always)]
    fn new(atlas: &Atlas, centre: &Centre, domain: &Domain, points: &[DVec2]) -> Self {
        let mut landing = Self { u: [0.0; BATCH], v: [0.0; BATCH], area_scale: [0.0; BATCH], texel: [u32::MAX; BATCH] };
        let len = points.len();
        let (mut wx, mut wy) = ([0.0f32; BATCH], [0.0f32; BATCH]);
        let shift = domain.placement.shift() as f32;
        for k in 0..len {
            // Placement::place in f32: the area radius shifted modulo 1, the point moved along its ray.
            let (dx, dy) = (points[k].x as f32, points[k].y as f32);
            let area_radius = dx * dx + dy * dy;
            let shifted = area_radius + shift;
            let shifted = if shifted >= 1.0 { shifted - 1.0 } else { shifted };
            let scale = if area_radius > 0.0 { (shifted / area_radius).sqrt() } else { 0.0 };
            (wx[k], wy[k]) = (dx * scale, dy * scale);
        }
        let mut margins = [0.0f64; BATCH];
        match domain.uniform {
            Some(margin) => margins[..len].fill(margin),
            None => {
                for (margin, &disk) in margins.iter_mut().zip(points) {
                    let w = domain.placement.place(disk);
                    *margin = domain.reach.at(w.y.atan2(w.x));
                }
            }
        }
        let to_uv = (domain.ellipse * domain.placement.turn()).as_mat2();
        let (cu, cv) = (centre.uv.x as f32, centre.uv.y as f32);
        let interior = &atlas.coverage().interior_face;
        let side = atlas.resolution() as f32;
        for k in 0..len {
            let margin = margins[k] as f32;
            let u = cu + margin * (to_uv.x_axis.x * wx[k] + to_uv.y_axis.x * wy[k]);
            let v = cv + margin * (to_uv.x_axis.y * wx[k] + to_uv.y_axis.y * wy[k]);
            let (x, y) = (u * side, v * side);
            let on_domain = x >= 0.0 && y >= 0.0 && x < side && y < side;
            landing.texel[k] = if on_domain { interior.index(x as usize, y as usize) as u32 } else { u32::MAX };
            (landing.u[k], landing.v[k]) = (u, v);
            landing.area_scale[k] = margins[k] * margins[k];
        }
        landing
    }
}

/// The gathering of the fast path, batch after batch of [`BATCH`] pattern points.
#[inline(always)]
fn gather_batches(gathering: &Gathering, out: &mut Vec<Sample>) -> SampleCounts {
    let Gathering { atlas, centre, pattern, domain } = *gathering;
    let settings = domain.settings;
    let cell_area = unit_ellipse_area(centre, settings) / pattern.len() as f64;
    let patches = &atlas.patches();
    let interior = &atlas.coverage().interior_face;
    let r = settings.radius as f32;
    let kernel = Kernel {
        patches: &patches.faces,
        origin: patches.origin,
        p: (centre.position - patches.origin).as_vec3(),
        normal: centre.normal.as_vec3(),
        outer: r * r,
        inner: (1e-6 * r) * (1e-6 * r),
        settings,
    };
    let mut counts = SampleCounts::default();
    for (batch, points) in pattern.chunks(BATCH).enumerate() {
        let first = batch * BATCH;
        let landing = Landing::new(atlas, centre, domain, points);
        let mut faces = [u32::MAX; BATCH];
        for (face, &texel) in faces.iter_mut().zip(&landing.texel[..points.len()]) {
            if let Some(&interior) = interior.get(texel as usize) {
                *face = interior;
            }
        }
        let mut evaluated = [Evaluated::default(); BATCH];
        for k in 0..points.len() {
            let Some(patch) = kernel.patches.get(faces[k] as usize).filter(|patch| patch.chart == centre.chart) else {
                faces[k] = u32::MAX;
                continue;
            };
            evaluated[k] = Evaluated::new(patch, Vec2::new(landing.u[k], landing.v[k]), kernel.p);
        }
        for k in 0..points.len() {
            let pattern_index = (first + k) as u32;
            let accepted = if faces[k] == u32::MAX {
                // Off the fast path: the exact path's offset and relocation.
                let offset = domain.offset(points[k]);
                let uv_area = cell_area * offset.area_scale;
                match locate_target(atlas, centre, centre.uv + offset.uv, settings) {
                    Located::Inside { uv, m_path, face: Some(face), .. }
                        if kernel.patches[face as usize].chart >= 0 =>
                    {
                        let uv_area = uv_area * m_path.determinant().abs();
                        kernel.accept_at(face, uv.as_vec2(), uv_area, pattern_index, out)
                    }
                    located => {
                        located_sample(atlas, centre, located, uv_area, pattern_index, settings, out, &mut counts);
                        false
                    }
                }
            } else {
                let patch = &kernel.patches[faces[k] as usize];
                let uv_area = cell_area * landing.area_scale[k];
                kernel.accept(patch, evaluated[k], uv_area, pattern_index, out)
            };
            counts.valid += u32::from(accepted);
        }
    }
    counts
}
