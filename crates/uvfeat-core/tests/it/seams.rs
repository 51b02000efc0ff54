//! DESIGN.md §1.2.5, §1.3.4, §1.5: adjacency and transition maps carry points across seams and back.

use crate::support::atlas;
use glam::{DVec2, DVec3};
use uvfeat_core::lookup::surface_point;
use uvfeat_core::relocation::{cross_seam, locate, Located};
use uvfeat_core::shapes::{split_plane, torus, uv_sphere};
use uvfeat_core::Atlas;

#[derive(Debug)]
struct RoundTrip {
    crossed: usize,
    /// Largest distance (texels) between a point and its image across the seam and back.
    worst_uv_texels: f64,
    /// Largest 3D distance between the two sides, in units of the texel's 3D size.
    worst_position_texels: f64,
    /// Fraction of crossings whose image lies on a texel of the adjacent chart (or next to one).
    landed: f64,
}

/// Maps every border texel centre with a seam across to the other side and back through the
/// reverse side's map.
fn round_trip(atlas: &Atlas) -> RoundTrip {
    let r = atlas.resolution() as f64;
    let mut out = RoundTrip { crossed: 0, worst_uv_texels: 0.0, worst_position_texels: 0.0, landed: 0.0 };
    let mut landed = 0usize;
    for t in 0..atlas.coverage().chart.len() {
        let (chart, side) = (atlas.coverage().chart[t], atlas.coverage().border_side[t]);
        if side < 0 || atlas.seam_maps()[side as usize].is_none() {
            continue;
        }
        let x = atlas.texel_centre(t);
        let across = cross_seam(atlas, x, chart).expect("border texel with a seam");
        let reverse = atlas.topology.sides[across.side].reverse as usize;
        let back = atlas.seam_maps()[reverse].expect("reverse side has a map").apply(across.uv);
        assert_eq!(atlas.topology.sides[reverse].chart, across.chart);
        out.crossed += 1;
        out.worst_uv_texels = out.worst_uv_texels.max(back.distance(x) * r);
        let here = surface_point(atlas, x, chart).expect("surface here");
        if let Some(there) = surface_point(atlas, across.uv, across.chart) {
            landed += 1;
            let texel_size = atlas.frame.distortion[here.face as usize].sigma1 / r;
            out.worst_position_texels =
                out.worst_position_texels.max(here.position.distance(there.position) / texel_size);
        }
    }
    out.landed = landed as f64 / out.crossed.max(1) as f64;
    out
}

fn assert_round_trip(name: &str, atlas: &Atlas) {
    let trip = round_trip(atlas);
    eprintln!("{name}: {trip:?}");
    assert!(trip.crossed > 100, "{name}: only {} seam texels", trip.crossed);
    assert!(trip.worst_uv_texels < 1e-6, "{name}: round trip off by {} texels", trip.worst_uv_texels);
    assert!(trip.landed > 0.99, "{name}: only {:.3} of crossings land next to the adjacent chart", trip.landed);
    assert!(trip.worst_position_texels < 1.0, "{name}: 3D mismatch {} texel sizes", trip.worst_position_texels);
}

#[test]
fn split_plane_seams_round_trip_with_rotation_anisotropy_and_mirroring() {
    for mirrored in [false, true] {
        let atlas = atlas(&split_plane(16, mirrored), 512);
        assert_eq!(atlas.topology.n_charts, 2);
        assert_eq!(atlas.topology.diagnostics.mirrored_uv_faces > 0, mirrored);
        let seam = atlas.seam_maps().iter().flatten().next().expect("a seam").m;
        assert_eq!(seam.determinant() < 0.0, mirrored, "det M sign");
        assert_round_trip(if mirrored { "mirrored plane" } else { "rotated plane" }, &atlas);
    }
}

#[test]
fn self_adjacent_seams_round_trip_on_torus_and_sphere() {
    let torus = atlas(&torus(2.0, 0.5, 64, 32), 512);
    assert_eq!(torus.topology.n_charts, 1);
    assert!(torus.topology.sides.iter().all(|s| s.adjacent_chart == 0));
    assert_round_trip("torus", &torus);
    assert_round_trip("sphere", &atlas(&uv_sphere(1.0, 64, 32), 512));
}

#[test]
fn transition_map_is_an_isometry_of_the_flat_plane() {
    // On a plane, a 3D offset crossing the seam must keep its length (DESIGN.md §3.5 check).
    let atlas = atlas(&split_plane(16, true), 1024);
    let start = DVec2::new(0.05 + 0.8 * 0.45, 0.05 + 0.9 * 0.5); // 3D (0.45, 0.5)
    let p = surface_point(&atlas, start, 0).unwrap().position;
    for (dx, dy) in [(0.1, 0.0), (0.08, 0.05), (0.12, -0.04)] {
        // Offset in uv of the left chart for a 3D offset (dx, dy).
        let target = start + DVec2::new(0.8 * dx, 0.9 * dy);
        let Located::Inside { chart, uv, jumps, .. } = locate(&atlas, start, 0, target, 3) else {
            panic!("sample lost");
        };
        assert_eq!((chart, jumps), (1, 1));
        let q = surface_point(&atlas, uv, chart).unwrap().position;
        let expected = p + DVec3::new(dx, dy, 0.0);
        assert!(q.distance(expected) < 1e-9, "crossed to {q}, expected {expected}");
    }
}

#[test]
fn locate_walks_around_the_torus_across_its_self_adjacent_seam() {
    // A long step in u wraps across the seam at u = 0 / 1 and lands at the analytic place.
    let atlas = atlas(&torus(2.0, 0.5, 128, 64), 1024);
    let margin = 0.02;
    let start = DVec2::new(margin + 0.01, 0.5);
    let target = start - DVec2::new(0.05, 0.0);
    let Located::Inside { chart, uv, jumps, m_path, .. } = locate(&atlas, start, 0, target, 3) else {
        panic!("sample lost");
    };
    assert_eq!((chart, jumps), (0, 1));
    // The hinge map unfolds one triangle pair, so on a curved surface a long offset lands within a
    // fraction of a texel of the analytic place.
    assert!(uv.distance(DVec2::new(1.0 - margin - 0.04, 0.5)) < 0.5 / 1024.0, "landed at {uv}");
    assert!((m_path.determinant() - 1.0).abs() < 0.01, "det M = {}", m_path.determinant());
}

#[test]
fn a_walk_within_the_chart_crosses_a_chart_s_own_seam_but_no_other() {
    use uvfeat_core::relocation::{home, walk_across, Seams};
    // The torus's wrap-around seam has its one chart on both sides.
    let atlas_torus = atlas(&torus(2.0, 0.5, 128, 64), 1024);
    let start = DVec2::new(0.03, 0.5);
    let from = home(&atlas_torus, start, 0).unwrap();
    let target = start - DVec2::new(0.05, 0.0);
    for seams in [Seams::Any, Seams::WithinChart] {
        assert!(matches!(
            walk_across(&atlas_torus, &from, target, 3, seams),
            Located::Inside { chart: 0, jumps: 1, .. }
        ));
    }
    // The split plane's seam has another chart across.
    let plane = atlas(&split_plane(16, false), 512);
    let (start, target) = (DVec2::new(0.3, 0.5), DVec2::new(0.7, 0.5));
    let chart = plane.chart_at(start);
    let from = home(&plane, start, chart).unwrap();
    let Located::Inside { chart: across, jumps: 1, .. } = walk_across(&plane, &from, target, 3, Seams::Any) else {
        panic!("the walk did not cross the seam");
    };
    assert_ne!(across, chart);
    assert_eq!(walk_across(&plane, &from, target, 3, Seams::WithinChart), Located::Missing);
}

#[test]
fn locate_reports_the_mesh_border() {
    let atlas = atlas(&split_plane(16, false), 512);
    let start = DVec2::new(0.1, 0.5);
    assert_eq!(locate(&atlas, start, 0, DVec2::new(-0.2, 0.5), 3), Located::Border);
}

/// A plane whose every triangle is its own chart, shrunk to half size about its centroid (so every
/// edge is a seam and the transition maps are exact similarities).
fn exploded_plane(n: usize) -> uvfeat_core::shapes::ShapeMesh {
    let mut mesh = uvfeat_core::shapes::plane(1.0, n);
    let mut uvs = Vec::with_capacity(3 * mesh.faces.len());
    for (face, uv_face) in mesh.faces.iter().zip(mesh.uv_faces.iter_mut()) {
        let corners = face.map(|v| DVec2::new(mesh.positions[v as usize][0], mesh.positions[v as usize][1]));
        let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
        let base = uvs.len() as i64;
        uvs.extend(corners.map(|c| (0.02 + 0.96 * (centroid + 0.5 * (c - centroid))).to_array()));
        *uv_face = [base, base + 1, base + 2];
    }
    mesh.uvs = uvs;
    mesh
}

#[test]
fn the_walk_crosses_charts_smaller_than_a_texel_exactly() {
    // 40 x 40 quads at 64^2 texels: triangles a third of a texel wide, whole charts inside one
    // texel. The texel march cannot find border texels there; the walk crosses every seam exactly.
    let atlas = atlas(&exploded_plane(40), 64);
    let topology = &atlas.topology;
    let face = 40 * 20 * 2 + 2 * 20; // a face near the middle
    let corners = topology.corner_uvs(face);
    let start = (corners[0] + corners[1] + corners[2]) / 3.0;
    let chart = topology.face_chart[face];
    let p = surface_point_of(&atlas, start, chart);
    let mut marched_lost = 0;
    for k in 0..24 {
        let angle = k as f64 * std::f64::consts::TAU / 24.0;
        // A 3D offset of 0.2 (8 quads): 0.2 * 0.96 * 0.5 in the start chart's uv.
        let target = start + DVec2::from_angle(angle) * (0.2 * 0.96 * 0.5);
        let Located::Inside { chart: c, uv, face: Some(f), jumps, .. } = locate(&atlas, start, chart, target, 64)
        else {
            panic!("walk lost the sample at angle {angle}");
        };
        assert!(jumps >= 8, "only {jumps} seams crossed");
        assert_eq!(topology.face_chart[f as usize], c);
        let q = uvfeat_core::lookup::evaluate_face(&atlas, f, uv).unwrap().position;
        let expected = p + DVec3::new(angle.cos(), angle.sin(), 0.0) * 0.2;
        assert!(q.distance(expected) < 1e-9, "walked to {q}, expected {expected}");
        if !matches!(uvfeat_core::relocation::march(&atlas, start, chart, target, 64), Located::Inside { .. }) {
            marched_lost += 1;
        }
    }
    assert!(marched_lost > 0, "the march was expected to lose samples here");
}

fn surface_point_of(atlas: &Atlas, uv: DVec2, chart: i32) -> DVec3 {
    let home = uvfeat_core::relocation::home(atlas, uv, chart).unwrap();
    uvfeat_core::lookup::evaluate_face(atlas, home.face, home.point).unwrap().position
}

#[test]
fn per_vertex_values_are_the_mean_of_the_corner_lookups() {
    use uvfeat_core::output::{per_corner, per_vertex, FeatureMaps};
    use uvfeat_core::settings::{ComputeSettings, VertexQuery};
    // A patchwork sphere: most vertices on a seam have two to four corners in different charts.
    let atlas = crate::support::atlas(&crate::support::patchwork_sphere(4), 256);
    let mut settings = ComputeSettings::new(vec![uvfeat_core::features::Feature::MeanCurvature], 0.3);
    settings.resolution = 96;
    let maps = FeatureMaps::compute(&atlas, &settings).expect("valid settings");
    let (uvs, vertex, corners) = per_corner(&atlas, &maps);
    assert_eq!((uvs.len(), vertex.len()), (atlas.topology.n_corners, atlas.topology.n_corners));
    let values = per_vertex(&atlas, &maps, &settings, VertexQuery::Texture).unwrap();
    let n = atlas.topology.n_geometric();
    let (mut sums, mut counts) = (vec![0.0f64; n], vec![0usize; n]);
    for (&g, &v) in vertex.iter().zip(&corners[0]) {
        if v.is_finite() {
            sums[g as usize] += f64::from(v);
            counts[g as usize] += 1;
        }
    }
    let several = counts.iter().filter(|&&c| c > 1).count();
    assert!(several > 50, "{several} vertices with several corners");
    for (input, &g) in atlas.topology.vertex_ids.iter().enumerate() {
        if counts[g as usize] > 0 {
            let mean = sums[g as usize] / counts[g as usize] as f64;
            assert!((f64::from(values[0][input]) - mean).abs() < 1e-5, "vertex {input}");
        }
    }
}
