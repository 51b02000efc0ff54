//! Stage 5 on a tile of texels at once (`sampling = "shared"`). The texels of one chart
//! in a tile form groups, each of the texels its centre reaches without a crossing (several where
//! a non-convex chart has arms in the tile); a group shares one located lattice of samples
//! (`sampling/lattice.rs`) and each texel sums its own domain of it
//! (`features/lattice_statistics.rs`). Where balls reach the rim of their domains, the coverage
//! check grows the domain once for the group, and those texels sum a second lattice over it. A
//! texel no lattice serves is evaluated on its own by [`evaluate_point`] with the per-texel fast
//! path: those of a group whose lattice would hold far more points than their patterns (balls
//! smaller than the texel spacing), and those left after a few groups of one chart.

use super::{evaluate_point, Patterns, PixelResult};
use crate::atlas::Atlas;
use crate::distortion::Distortion;
use crate::features::{lattice_statistics, LatticeNeighbourhood, SumsKernel};
use crate::relocation::{walk, walk_across, Home, Located, Seams};
use crate::sampling::{
    grow_marked, probed_reach, secant_distortion, texel_point, Centre, LatticeDomain, LatticeTexel, Placement, Reach,
    Sample, TexelPoint, TileLattice, TilePlane, DIRECTIONS, EDGE_RADIUS,
};
use crate::settings::ComputeSettings;
use glam::{DVec2, Vec2};

/// The parametric location of texel `t` of a `w`² texture.
pub fn texel_uv(t: usize, w: usize) -> DVec2 {
    DVec2::new(((t % w) as f64 + 0.5) / w as f64, ((t / w) as f64 + 0.5) / w as f64)
}

/// Groups of one chart a tile is split into at most (each reaches its texels from its centre).
/// With 16, the 18-chart xatlas torus at r = 16 % left 414 texels (arms of a chart in its 64-texel
/// tiles, often one texel each; most were probably gutter texels, which have joined their groups
/// since) to the per-texel path at 0.8 ms each, a fifth of its features: a group of one texel
/// costs less there, and small radii never reach this many.
const MAX_GROUPS: usize = 64;

/// Evaluates the texels `texels` (indices into the `w`² computation texture) of one tile.
pub fn evaluate_tile(
    atlas: &Atlas,
    settings: &ComputeSettings,
    patterns: &Patterns,
    texels: &[usize],
    scratch: &mut Vec<Sample>,
) -> Vec<PixelResult> {
    let w = settings.resolution;
    let sampler = settings.sampler();
    let points: Vec<Option<TexelPoint>> = texels.iter().map(|&t| texel_point(atlas, texel_uv(t, w))).collect();
    let mut results = vec![PixelResult::EMPTY; texels.len()];
    let mut alone = Vec::new();
    // Balls reach past their disks at the centres of all a tile's groups or of few: the previous
    // group tells the next one (in the tile's fixed order, so every thread count gives the same).
    let mut rim_likely = false;
    let mut charts: Vec<i32> = points.iter().flatten().map(|p| p.chart).collect();
    charts.sort_unstable();
    charts.dedup();
    for chart in charts {
        let mut members: Vec<(usize, TexelPoint)> =
            points.iter().enumerate().filter_map(|(k, p)| p.filter(|p| p.chart == chart).map(|p| (k, p))).collect();
        // The texels the group's centre reaches without a crossing share its lattice; the others
        // (another arm of a non-convex chart) form the next group.
        for _ in 0..MAX_GROUPS {
            let Some(centre) = group_centre(atlas, &members, settings) else { break };
            let (shared, unreached): (Vec<_>, Vec<_>) =
                members.into_iter().partition(|(_, member)| reaches(atlas, &centre, member, sampler.max_jumps));
            members = unreached;
            let Group { results: done, alone: left, centre_rim } =
                evaluate_group(atlas, settings, centre, &shared, rim_likely);
            rim_likely = centre_rim;
            done.into_iter().for_each(|(k, result)| results[k] = result);
            alone.extend(left);
        }
        alone.extend(members.into_iter().map(|(k, _)| k));
    }
    for k in alone {
        let t = texels[k];
        let placement = Placement::of_pixel((t % w) as u32, (t / w) as u32, settings.seed);
        results[k] = evaluate_point(atlas, texel_uv(t, w), placement, settings, patterns, scratch);
    }
    results
}

/// What a group's lattices gave: results by texel, the texels they could not serve, and whether
/// the centre's ball reached the rim of its disk.
struct Group {
    results: Vec<(usize, PixelResult)>,
    alone: Vec<usize>,
    centre_rim: bool,
}

/// `true` when `centre` reaches `member` within their chart without crossing a seam: straight, or,
/// where the straight path crosses only seams with the chart on both sides (the slits between a
/// lat-long pole's fan triangles), along the texture's axes round them. Round any other gap (a
/// concavity whose edges are seams to other charts, on Spot) a member would sum a lattice that
/// the centre unfolds beyond the member's own boundary from the wrong side (the baked seams'
/// error, `test_bake` at its former 128² texture and one seed, 1.5 -> 3.3 % of the range); at the poles the groups of a tile row of the
/// 200K sphere at r = 4 % fall from 14-16 per tile to 6-7.
fn reaches(atlas: &Atlas, centre: &Centre, member: &TexelPoint, max_jumps: u32) -> bool {
    let within = |from: &Home, target: DVec2| match walk(atlas, from, target, max_jumps) {
        Located::Inside { jumps: 0, chart, uv, face: Some(face), .. } if chart == centre.chart => {
            Some(Home { face, point: uv })
        }
        _ => None,
    };
    if member.uv == centre.uv || within_clear_texels(atlas, centre.home.point, member.home.point) {
        return true;
    }
    // A texel centre in a slit or in the gutter has its home on an edge of its face, where a walk
    // may end on either side of the edge: the walks aim a hair inside the face. Aimed at the edge,
    // the rounding left about half the gutter texels unreached, each then a group of its own with
    // its own lattice and probes: on the xatlas torus at r = 16 %, 1,390 groups of one texel out of
    // 1,640. (A home face of no parametric area keeps the old aim: its centroid lies on the edge.)
    let corners = atlas.topology.corner_uvs(member.home.face as usize);
    let inside = (corners[0] + corners[1] + corners[2]) / 3.0;
    let target = member.home.point + 1e-3 * (inside - member.home.point);
    // Within the chart, the walk ends in the centre's chart or not at all.
    match walk_across(atlas, &centre.home, target, max_jumps, Seams::WithinChart) {
        Located::Inside { jumps: 0, .. } => true,
        Located::Inside { .. } => {
            [DVec2::new(target.x, centre.home.point.y), DVec2::new(centre.home.point.x, target.y)]
                .into_iter()
                .any(|corner| within(&centre.home, corner).is_some_and(|turn| within(&turn, target).is_some()))
        }
        _ => false,
    }
}

/// `true` when the straight path from `from` to `to` crosses only texels of one chart that no
/// chart boundary touches, read from the coverage's chart distance at `from`: the walk would
/// arrive without a crossing. Most groups lie inside their chart, and the walks cost 4 % of the
/// features.
fn within_clear_texels(atlas: &Atlas, from: DVec2, to: DVec2) -> bool {
    let (Some((i, j)), Some((k, l))) = (atlas.texel_coordinates(from), atlas.texel_coordinates(to)) else {
        return false;
    };
    // The path's texels lie in the box of its ends' texels, within this (Chebyshev) distance of
    // `from`'s; those closer than the chart distance less one are clear (`Coverage::chart_distance`),
    // and one texel more is kept for ends that lie on a texel's edge.
    let apart = i.abs_diff(k).max(j.abs_diff(l));
    usize::from(atlas.coverage().chart_distance.at(i, j)) > apart + 2
}

/// Evaluates the texels `members` of one chart around `centre`, which reaches them all;
/// `rim_likely` where the tile's previous group's centre reached the rim of its disk.
fn evaluate_group(
    atlas: &Atlas,
    settings: &ComputeSettings,
    centre: Centre,
    members: &[(usize, TexelPoint)],
    rim_likely: bool,
) -> Group {
    let sampler = settings.sampler();
    let stats_settings = settings.stats();
    let mut group = Group { results: Vec::with_capacity(members.len()), alone: Vec::new(), centre_rim: false };
    let plane = TilePlane::new(Centre { distortion: plane_metric(atlas, &centre, settings), ..centre }, &sampler);
    let texel = |member: &TexelPoint| LatticeTexel {
        place: plane.place(member.uv),
        position: member.position,
        normal: member.normal,
    };
    let texels: Vec<(usize, LatticeTexel)> = members.iter().map(|(k, member)| (*k, texel(member))).collect();
    let build = |texels: &[(usize, LatticeTexel)], domain: LatticeDomain| {
        let places: Vec<Vec2> = texels.iter().map(|(_, texel)| texel.place).collect();
        TileLattice::build(atlas, &plane, &places, domain, settings.samples, settings.seed, &sampler)
    };
    let kernel = SumsKernel::detected();
    let sums = |lattice: &TileLattice, texel: &LatticeTexel, shift: f64| {
        lattice_statistics(kernel, lattice, texel, &stats_settings, EDGE_RADIUS as f32, sampler.with_normals, shift)
    };
    let centre_texel = texel(&centre.texel_point(atlas.patches().origin));
    let mut marked = [false; DIRECTIONS];
    let (mut shift, mut probed) = (None, None);
    // The coverage check's probes first where the tile's previous group's ball reached past its
    // disk at the centre (large radii): where they grow the centre's reach, every texel of the
    // group samples the grown domain, and no disk is located (at r = 16 % of the xatlas torus,
    // half the points located). Probing first in every group sent groups whose disks hold their
    // balls to the grown domain wherever a probe's point lay in the ball (clean lat-long sphere
    // at 8 %: 1.5x the H error).
    if settings.grow_margin && rim_likely {
        probed = Some(probed_reach(atlas, &centre, &sampler));
    }
    let rim = if probed.is_some_and(|reach| reach != Reach::uniform(sampler.margin)) {
        group.centre_rim = true;
        texels
    } else {
        let Some(lattice) = build(&texels, LatticeDomain::Disks(sampler.margin)) else {
            group.alone.extend(members.iter().map(|(k, _)| *k));
            return group;
        };
        let at_centre = sums(&lattice, &centre_texel, 0.0);
        let centre_shift = centre_shift(&at_centre);
        shift = Some(centre_shift);
        if at_centre.rim && settings.grow_margin {
            // Every texel of the group samples the grown domain, without a pass over the disks.
            group.centre_rim = true;
            marked = lattice.rim_directions(&centre_texel, settings.radius, EDGE_RADIUS as f32);
            texels
        } else {
            let mut rim = Vec::new();
            for (k, texel) in texels {
                let hood = sums(&lattice, &texel, centre_shift);
                if hood.rim && settings.grow_margin {
                    let directions = lattice.rim_directions(&texel, settings.radius, EDGE_RADIUS as f32);
                    marked.iter_mut().zip(directions).for_each(|(m, d)| *m |= d);
                    rim.push((k, texel));
                } else {
                    group.results.push((k, PixelResult::estimated(&hood.stats, None, hood.counts, settings)));
                }
            }
            rim
        }
    };
    if rim.is_empty() {
        return group;
    }
    // Where the balls reached the rim, the domain grows as the coverage check grows a single
    // texel's, from the group's centre, and the rim texels sum a lattice over that domain.
    let probed = probed.unwrap_or_else(|| probed_reach(atlas, &centre, &sampler));
    let Some(lattice) = build(&rim, LatticeDomain::Grown(grow_marked(probed, &sampler, &marked))) else {
        group.alone.extend(rim.into_iter().map(|(k, _)| k));
        return group;
    };
    let shift = shift.unwrap_or_else(|| centre_shift(&sums(&lattice, &centre_texel, 0.0)));
    for (k, texel) in rim {
        let hood = sums(&lattice, &texel, shift);
        group.results.push((k, PixelResult::estimated(&hood.stats, None, hood.counts, settings)));
    }
    group
}

/// The value the group's normal curvatures are summed about (see [`lattice_statistics`]): the
/// mean at its centre.
fn centre_shift(at_centre: &LatticeNeighbourhood) -> f64 {
    Some(at_centre.stats.normal_curvature.mean()).filter(|k| k.is_finite()).unwrap_or(0.0)
}

/// Ball radius in computation texels below which a group's plane may take the metric at the
/// ball's scale. At 8 % (balls of about 40 texels) the face's metric with its grown domains gave
/// the noisy lat-long sphere's and ellipsoid's poles 5 % less H error.
const SECANT_BALL: f64 = 32.0;

/// Area element of the centre's face over the secant metric's above which the face is taken to be
/// tilted by noise. Smooth meshes keep their faces' metric: with the chords everywhere, the coarse
/// Spot's maps moved enough across its seams to fail the texture-baking test (`test_bake` at its
/// former 128² texture and one seed: max seam error 1.4 -> 7.7 % of the range).
const ROUGH_FACE: f64 = 1.1;

/// The metric of the plane of the group around `centre`: the surface's at the scale of the ball
/// ([`secant_distortion`]) where the centre's face is rough (its area element over the secant's
/// above [`ROUGH_FACE`]) and the ball spans fewer than [`SECANT_BALL`] texels, else the face's own.
/// On the noisy 200K surfaces of docs/PEERS.md it spares most texels their grown lattice
/// (features at r = 2 %: 0.5-0.6 -> 0.25-0.35 s); smooth surfaces keep their faces' metric.
fn plane_metric(atlas: &Atlas, centre: &Centre, settings: &ComputeSettings) -> Distortion {
    let face = centre.distortion;
    let ball_texels = |metric: &Distortion| settings.radius / metric.area_element().sqrt() * settings.resolution as f64;
    // A secant the face is rough against spans more texels than the face's ball by sqrt(ROUGH_FACE)
    // at least: where that is past SECANT_BALL already (large radii), no chord is walked.
    if ROUGH_FACE.sqrt() * ball_texels(&face) >= SECANT_BALL {
        return face;
    }
    secant_distortion(atlas, centre, &settings.sampler())
        .filter(|secant| face.area_element() > ROUGH_FACE * secant.area_element() && ball_texels(secant) < SECANT_BALL)
        .unwrap_or(face)
}

/// The centre at the member nearest the members' mean location: the centre of the group's
/// sampling plane (`None` without members).
fn group_centre(atlas: &Atlas, members: &[(usize, TexelPoint)], settings: &ComputeSettings) -> Option<Centre> {
    let mean = members.iter().map(|(_, p)| p.uv).sum::<DVec2>() / members.len().max(1) as f64;
    let nearest = members.iter().min_by(|a, b| a.1.uv.distance_squared(mean).total_cmp(&b.1.uv.distance_squared(mean)));
    nearest?.1.centre(atlas, settings.lookup)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lookup::Lookup;
    use crate::mesh::{Topology, TriangleMesh};
    use crate::sampling::centre_at;
    use crate::shapes::uv_sphere;
    use crate::AtlasOptions;
    use std::sync::Arc;

    /// Where the chart distance says the path is clear, the walk arrives without a crossing: on a
    /// lat-long sphere (a seam, and the poles' fans of slits) and on a plane cut in two charts.
    #[test]
    fn clear_texels_are_reached_without_a_crossing() {
        for shape in [uv_sphere(1.0, 64, 32), crate::shapes::split_plane(24, false)] {
            let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
            let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
            let atlas =
                Atlas::new(topology, &mesh.positions, &AtlasOptions { resolution: 256, ..Default::default() }).unwrap();
            let (mut clear, mut pairs) = (0, 0);
            for j in (0..256).step_by(5) {
                for i in (0..256).step_by(5) {
                    let from = DVec2::new((i as f64 + 0.5) / 256.0, (j as f64 + 0.5) / 256.0);
                    let Some(centre) = centre_at(&atlas, from, Lookup::default()) else { continue };
                    for (di, dj) in [(9.3, -4.1), (-13.7, 2.2), (3.1, 15.9), (-6.0, -11.4)] {
                        let to = from + DVec2::new(di, dj) / 256.0;
                        pairs += 1;
                        if within_clear_texels(&atlas, centre.home.point, to) {
                            clear += 1;
                            let walked = walk_across(&atlas, &centre.home, to, 32, Seams::WithinChart);
                            assert!(
                                matches!(walked, Located::Inside { jumps: 0, chart, .. } if chart == centre.chart),
                                "{from} -> {to}: {walked:?}"
                            );
                        }
                    }
                }
            }
            assert!(clear > pairs / 3 && clear < pairs, "{clear} of {pairs}");
        }
    }

    /// The texels in the gutter round a convex chart share the lattice of a centre inside it: their
    /// homes lie on the chart's boundary edges, which a walk aimed at the edge itself may cross.
    #[test]
    fn the_gutter_texels_of_a_convex_chart_are_reached_from_inside_it() {
        let shape = crate::shapes::split_plane(24, false);
        let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
        let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
        let atlas =
            Atlas::new(topology, &mesh.positions, &AtlasOptions { resolution: 512, ..Default::default() }).unwrap();
        // The plane's halves are two rectangles: [0.05, 0.45] x [0.05, 0.95] and one turned by 30
        // degrees round (0.7, 0.35), whose edges' points the walks meet with rounding.
        for middle in [DVec2::new(0.25, 0.5), DVec2::new(0.733, 0.542)] {
            let centre = centre_at(&atlas, middle, Lookup::default()).unwrap();
            // Texel centres in the gutter, at the coverage's own resolution.
            let w = 512;
            let gutter: Vec<TexelPoint> = (0..w * w)
                .filter_map(|t| texel_point(&atlas, texel_uv(t, w)))
                .filter(|member| member.chart == centre.chart && member.uv != member.home.point)
                .collect();
            let unreached = gutter.iter().filter(|member| !reaches(&atlas, &centre, member, 32)).count();
            assert!(gutter.len() > 200, "{} gutter texels", gutter.len());
            assert_eq!(unreached, 0, "{unreached} of {} gutter texels unreached from {middle}", gutter.len());
        }
    }

    #[test]
    fn a_pole_fan_triangle_is_reached_round_the_slits_from_the_next_row_but_not_from_another_fan_triangle() {
        let (n_lon, n_lat) = (64.0, 32.0);
        let shape = uv_sphere(1.0, n_lon as usize, n_lat as usize);
        let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
        let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
        let atlas =
            Atlas::new(topology, &mesh.positions, &AtlasOptions { resolution: 512, ..Default::default() }).unwrap();
        // Places in units of the grid's cells (the shape's uvs keep a margin round the unit square).
        let margin = shape.uvs[0][0];
        let uv_of =
            |lon: f64, lat: f64| DVec2::splat(margin) + DVec2::new(lon / n_lon, lat / n_lat) * (1.0 - 2.0 * margin);
        let centre_of = |lon: f64, lat: f64| centre_at(&atlas, uv_of(lon, lat), Lookup::default()).unwrap();
        let member_of = |lon: f64, lat: f64| texel_point(&atlas, uv_of(lon, lat)).unwrap();
        // A point inside fan triangle 20 (corners (20, 0) at the pole, (21, 1), (20, 1)), from the
        // quad row above it three triangles to the side: the straight path enters triangle 21 and
        // crosses the slit between them.
        let centre = centre_of(23.5, 1.5);
        let in_fan = member_of(20.3, 0.6);
        assert!(!matches!(walk(&atlas, &centre.home, in_fan.home.point, 32), Located::Inside { jumps: 0, .. }));
        assert!(reaches(&atlas, &centre, &in_fan, 32));
        assert!(reaches(&atlas, &centre, &member_of(23.0, 3.0), 32));
        // From one fan triangle, every way to another crosses a slit.
        assert!(!reaches(&atlas, &centre_of(20.3, 0.6), &member_of(23.3, 0.6), 32));
    }
}
