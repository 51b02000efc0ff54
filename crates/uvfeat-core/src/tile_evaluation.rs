//! Stage 5 on a tile of texels at once (`sampling = "shared"`, issue 12): the texels of each chart
//! in the tile share one located lattice of samples (`sampling/lattice.rs`) and each sums its own
//! domain of it (`features/lattice_statistics.rs`). A texel the lattice cannot serve is evaluated
//! on its own by [`evaluate_point`], with the per-texel fast path: one the tile's centre does not
//! reach without a crossing (another arm of a non-convex chart), and the texels of a tile whose
//! lattice would hold more points than their patterns (balls smaller than the texel spacing). Where balls reach the rim of their
//! domains, the coverage check grows the domain once for the tile, and those texels sum a second
//! lattice over it.

use crate::atlas::Atlas;
use crate::evaluation::{evaluate_point, Patterns, PixelResult};
use crate::features::{lattice_statistics, CurvatureMethod, VolumeWeighting};
use crate::relocation::{walk, Located};
use crate::sampling::{
    centre_at, fast_path_applies, grown_reach, Centre, LatticeTexel, LatticeDomain, Overlaps, Placement, Sample,
    SamplingPath, TileLattice, TilePlane, DIRECTIONS, EDGE_RADIUS,
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
        let plane = TilePlane::new(centre, &sampler);
        let texels: Vec<(usize, LatticeTexel)> = shared
            .iter()
            .map(|(k, member)| {
                let place = plane.place(member.uv);
                let position = (member.position - atlas.patches.origin).as_vec3();
                (*k, LatticeTexel { place, position, normal: member.normal.as_vec3() })
            })
            .collect();
        let places: Vec<Vec2> = texels.iter().map(|(_, texel)| texel.place).collect();
        let disks = LatticeDomain::Disks(sampler.margin);
        let Some(lattice) =
            TileLattice::build(atlas, &plane, &places, disks, settings.samples, settings.seed, &sampler)
        else {
            alone.extend(texels.into_iter().map(|(k, _)| k));
            continue;
        };
        let mut rim = Vec::new();
        let mut marked = [false; DIRECTIONS];
        let centre_texel = LatticeTexel {
            place: Vec2::ZERO,
            position: (centre.position - atlas.patches.origin).as_vec3(),
            normal: centre.normal.as_vec3(),
        };
        let sums = |lattice: &TileLattice, texel: &LatticeTexel, shift: f64| {
            lattice_statistics(lattice, texel, &stats_settings, EDGE_RADIUS as f32, sampler.with_normals, shift)
        };
        let at_centre = sums(&lattice, &centre_texel, 0.0);
        let shift = Some(at_centre.stats.normal_curvature.mean()).filter(|k| k.is_finite()).unwrap_or(0.0);
        let mut mark = |texel: &LatticeTexel| {
            let directions = lattice.rim_directions(texel, settings.radius, EDGE_RADIUS as f32);
            marked.iter_mut().zip(directions).for_each(|(m, d)| *m |= d);
        };
        if at_centre.rim && settings.grow_margin {
            // The ball reaches past the disk at the centre already (large radii): every texel of
            // the tile samples the grown domain, without a pass over the disk first.
            mark(&centre_texel);
            rim = texels;
        } else {
            for (k, texel) in texels {
                let hood = sums(&lattice, &texel, shift);
                if hood.rim && settings.grow_margin {
                    mark(&texel);
                    rim.push((k, texel));
                } else {
                    results[k] = PixelResult::estimated(&hood.stats, None, hood.counts, settings);
                }
            }
        }
        if rim.is_empty() {
            continue;
        }
        // Where the balls reached the rim, the domain grows as the coverage check grows a single
        // texel's, from the tile's centre, and the rim texels sum a lattice over that domain.
        let reach = grown_reach(atlas, &centre, &sampler, &marked);
        let places: Vec<Vec2> = rim.iter().map(|(_, texel)| texel.place).collect();
        let grown = LatticeDomain::Grown(reach);
        let Some(lattice) =
            TileLattice::build(atlas, &plane, &places, grown, settings.samples, settings.seed, &sampler)
        else {
            alone.extend(rim.into_iter().map(|(k, _)| k));
            continue;
        };
        for (k, texel) in rim {
            let hood = sums(&lattice, &texel, shift);
            results[k] = PixelResult::estimated(&hood.stats, None, hood.counts, settings);
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
