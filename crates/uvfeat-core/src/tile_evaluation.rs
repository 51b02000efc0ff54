//! Stage 5 on a tile of texels at once (`sampling = "shared"`, issue 12): the texels of each chart
//! in the tile share one located lattice of samples (`sampling/lattice.rs`) and each sums its own
//! domain of it (`features/lattice_statistics.rs`). A texel the lattice cannot serve is evaluated
//! on its own by [`evaluate_point`], with the per-texel fast path: one the tile's centre does not
//! reach without a crossing (another arm of a non-convex chart), and one whose ball reached the
//! rim of its domain, where the coverage check grows the domain per direction.

use crate::atlas::Atlas;
use crate::evaluation::{evaluate_point, Patterns, PixelResult};
use crate::features::{lattice_statistics, CurvatureMethod, LatticeTexel, VolumeWeighting};
use crate::relocation::{walk, Located};
use crate::sampling::{
    centre_at, fast_path_applies, Centre, Overlaps, Placement, Sample, SamplingPath, TileLattice,
    TilePlane, EDGE_RADIUS,
};
use crate::settings::ComputeSettings;
use glam::{DVec2, Vec2};

/// `true` when the shared lattice serves `settings` on `atlas`: the fast path's choices, with the
/// integral estimators over the whole pattern at once (no adaptive stages, no batch errors, no
/// fit), the distance weighting, no geodesic distances, and overlaps kept.
pub fn shared_lattice_applies(atlas: &Atlas, settings: &ComputeSettings) -> bool {
    let sampler = settings.sampler();
    settings.sampling == SamplingPath::Shared
        && fast_path_applies(atlas, &sampler)
        && !settings.adaptive
        && !settings.standard_errors
        && settings.method == CurvatureMethod::Integral
        && settings.volume_weighting == VolumeWeighting::Distance
        && settings.overlaps == Overlaps::Keep
        && !sampler.with_geodesic
}

/// The parametric location of texel `t` of a `w`² texture.
pub fn texel_uv(t: usize, w: usize) -> DVec2 {
    DVec2::new(((t % w) as f64 + 0.5) / w as f64, ((t / w) as f64 + 0.5) / w as f64)
}

/// Evaluates the texels `texels` (indices into the `w`² computation texture) of tile `tile`.
pub fn evaluate_tile(
    atlas: &Atlas,
    settings: &ComputeSettings,
    patterns: &Patterns,
    texels: &[usize],
    scratch: &mut Vec<Sample>,
) -> Vec<PixelResult> {
    let w = settings.resolution;
    let sampler = settings.sampler();
    let stats_settings = settings.stats();
    let centres: Vec<Option<Centre>> =
        texels.iter().map(|&t| centre_at(atlas, texel_uv(t, w), settings.lookup)).collect();
    let mut results = vec![PixelResult::EMPTY; texels.len()];
    let mut alone = Vec::new();
    let mut charts: Vec<i32> = centres.iter().flatten().map(|c| c.chart).collect();
    charts.sort_unstable();
    charts.dedup();
    for chart in charts {
        let members: Vec<(usize, Centre)> =
            centres.iter().enumerate().filter_map(|(k, c)| c.filter(|c| c.chart == chart).map(|c| (k, c))).collect();
        let centre = tile_centre(&members);
        let (shared, unreached): (Vec<_>, Vec<_>) = members.into_iter().partition(|(_, member)| {
            member.uv == centre.uv
                || matches!(
                    walk(atlas, &centre.home, member.uv, sampler.max_jumps),
                    Located::Inside { jumps: 0, chart, .. } if chart == centre.chart
                )
        });
        alone.extend(unreached.into_iter().map(|(k, _)| k));
        let plane = TilePlane::new(&centre, &sampler);
        let places: Vec<Vec2> = shared.iter().map(|(_, member)| plane.place(&centre, member.uv)).collect();
        let lattice = TileLattice::build(atlas, &centre, &plane, &places, settings.samples, settings.seed, &sampler);
        let origin = atlas.patches.origin;
        for ((k, member), place) in shared.into_iter().zip(places) {
            let texel = LatticeTexel {
                place,
                position: (member.position - origin).as_vec3(),
                normal: member.normal.as_vec3(),
            };
            let hood = lattice_statistics(&lattice, &texel, &stats_settings, EDGE_RADIUS as f32, sampler.with_normals);
            if hood.rim && settings.grow_margin {
                alone.push(k);
            } else {
                results[k] = PixelResult::estimated(&hood.stats, None, hood.counts, settings);
            }
        }
    }
    for k in alone {
        let t = texels[k];
        let placement = Placement::of_pixel((t % w) as u32, (t / w) as u32, settings.seed);
        results[k] = evaluate_point(atlas, texel_uv(t, w), placement, settings, patterns, scratch);
    }
    results
}

/// The member nearest the members' mean location: the centre of the tile's sampling plane.
fn tile_centre(members: &[(usize, Centre)]) -> Centre {
    let mean = members.iter().map(|(_, c)| c.uv).sum::<DVec2>() / members.len() as f64;
    members.iter().map(|(_, c)| *c).min_by(|a, b| a.uv.distance_squared(mean).total_cmp(&b.uv.distance_squared(mean))).unwrap()
}
