//! The sampler's fast path (issue 12). A pattern point whose target texel lies well inside the
//! centre's chart (see [`crate::relocation::well_inside`]) is reached without crossing anything,
//! and the exact path then evaluates the face that texel shows. The fast path does the same with
//! one load of [`Coverage::interior_face`] and one compact f32 [`FacePatch`], no walk, no search
//! and no f64 face map; every other point goes through the exact per-sample path. So both paths
//! keep the same samples, the same faces and the same weights; they differ by f32 rounding only
//! (compared in `tests/it/fast_path.rs`).
//!
//! [`Coverage::interior_face`]: crate::raster::Coverage::interior_face
//! [`FacePatch`]: crate::raster::FacePatch

use super::gather::{exact_sample, offsets};
use super::geodesic::{arc_distance, Geodesic};
use super::neighbourhood::{unit_ellipse_area, Centre, Sample, SampleCounts, SamplerSettings};
use super::pattern::Placement;
use super::reach::Reach;
use crate::atlas::Atlas;
use crate::lookup::Lookup;
use crate::raster::Precision;
use crate::relocation::Relocation;
use glam::{DVec2, DVec3, Vec2, Vec3};

/// Which sampler runs: the fast path where it keeps the exact path's answers, or the exact path
/// everywhere (the reference of the fast one).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SamplingPath {
    /// Interior samples straight from the face-id buffer and the f32 patches (default).
    #[default]
    Fast,
    /// Every sample located and evaluated on its own, in f64.
    Exact,
}

/// `true` when the fast path serves `settings` on `atlas`: the choices whose interior samples it
/// reproduces (triangle lookup, walk or march relocation, arc geodesics, f32 buffers).
pub fn applies(atlas: &Atlas, settings: &SamplerSettings) -> bool {
    settings.path == SamplingPath::Fast
        && settings.lookup == Lookup::Triangle
        && settings.relocation != Relocation::PerChart
        && settings.geodesic == Geodesic::Arc
        && atlas.precision == Precision::F32
}

/// Pattern points handled per batch: each stage runs over a whole batch, so that the loads of the
/// face ids and then of the patches are independent of each other and overlap in the memory
/// system (one point after the other, a point's loads waited on the previous point's).
const BATCH: usize = 64;

/// As [`super::gather`], with interior samples on the fast path.
pub fn gather(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    placement: Placement,
    reach: &Reach,
    settings: &SamplerSettings,
    out: &mut Vec<Sample>,
) -> SampleCounts {
    let cell_area = unit_ellipse_area(centre, settings) / pattern.len() as f64;
    let patches = &atlas.patches;
    let interior = &atlas.coverage.interior_face;
    let origin = patches.origin;
    let p = (centre.position - origin).as_vec3();
    let normal = centre.normal.as_vec3();
    let r = settings.radius as f32;
    let (outer, inner) = (r * r, (1e-6 * r) * (1e-6 * r));
    let mut counts = SampleCounts::default();
    let mut offsets = offsets(centre, pattern, placement, reach, settings);
    let mut first = 0;
    while first < pattern.len() {
        let len = BATCH.min(pattern.len() - first);
        let mut targets = [DVec2::ZERO; BATCH];
        let mut area_scales = [0.0f64; BATCH];
        let mut faces = [u32::MAX; BATCH];
        for k in 0..len {
            let offset = offsets.next().expect("one offset per pattern point");
            targets[k] = centre.uv + offset.uv;
            area_scales[k] = offset.area_scale;
            if let Some(t) = atlas.texel_at(targets[k]) {
                faces[k] = interior[t];
            }
        }
        let mut relative = [Vec3::ZERO; BATCH];
        let mut squared = [0.0f32; BATCH];
        let mut local = [Vec2::ZERO; BATCH];
        for k in 0..len {
            let Some(patch) = patches.faces.get(faces[k] as usize).filter(|patch| patch.chart == centre.chart) else {
                faces[k] = u32::MAX;
                continue;
            };
            local[k] = targets[k].as_vec2() - Vec2::from_array(patch.uv0);
            relative[k] = patch.position_at(local[k]) - p;
            squared[k] = relative[k].length_squared();
        }
        for k in 0..len {
            let pattern_index = (first + k) as u32;
            let uv_area = cell_area * area_scales[k];
            if faces[k] == u32::MAX {
                exact_sample(atlas, centre, targets[k], uv_area, pattern_index, settings, out, &mut counts);
                continue;
            }
            if !(squared[k] > inner && squared[k] < outer) {
                continue;
            }
            let patch = &patches.faces[faces[k] as usize];
            let distance = squared[k].sqrt();
            let sin_alpha = f64::from(normal.dot(relative[k]) / distance);
            let distance = f64::from(distance);
            out.push(Sample {
                position: (relative[k] + p).as_dvec3() + origin,
                normal: if settings.with_normals { patch.normal_at(local[k]).as_dvec3() } else { DVec3::NAN },
                area: f64::from(patch.area_element) * uv_area,
                distance,
                sin_alpha,
                geodesic: if settings.with_geodesic { arc_distance(distance, sin_alpha) } else { f64::NAN },
                pattern_index,
            });
            counts.valid += 1;
        }
        first += len;
    }
    counts
}
