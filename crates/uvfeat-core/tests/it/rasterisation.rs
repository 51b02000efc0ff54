//! DESIGN.md §1.3.1–§1.3.2: coverage is exact at texel centres, complete and connected per chart.

use crate::support::{atlas, barycentric, interpolate, patchwork_sphere};
use glam::DVec3;
use uvfeat_core::shapes::{cylinder, split_plane, torus, uv_sphere};
use uvfeat_core::Atlas;

fn max_position_error(atlas: &Atlas) -> f64 {
    let mut worst = 0.0f64;
    for (t, &face) in atlas.coverage().face.iter().enumerate() {
        let Ok(face) = usize::try_from(face) else {
            continue;
        };
        let b = barycentric(atlas.topology.corner_uvs(face), atlas.texel_centre(t));
        if b.iter().any(|&x| x < 0.0) {
            continue; // gutter texel: shows the closest edge point, checked in the seam tests
        }
        let exact = interpolate(atlas, face, b);
        let stored = DVec3::from_array(atlas.buffers().position[t].map(f64::from));
        worst = worst.max(exact.distance(stored));
    }
    worst
}

#[test]
fn positions_are_the_exact_interpolation_at_texel_centres() {
    for (name, shape) in [("sphere", uv_sphere(1.0, 64, 32)), ("torus", torus(2.0, 0.5, 64, 32))] {
        let atlas = atlas(&shape, 512);
        let err = max_position_error(&atlas);
        assert!(err < 2e-6, "{name}: max |P - exact| = {err}");
    }
}

#[test]
fn every_texel_centre_inside_a_uv_triangle_is_covered_by_its_chart() {
    let shape = split_plane(24, true);
    let atlas = atlas(&shape, 512);
    let r = atlas.resolution();
    let mut inside = 0;
    for (face, uv) in atlas.topology.walk_faces.iter().map(|w| w.corners).enumerate() {
        for t in 0..r * r {
            let b = barycentric(uv, atlas.texel_centre(t));
            if b.iter().all(|&x| x > 1e-9) {
                inside += 1;
                assert_eq!(atlas.coverage().chart[t], atlas.topology.face_chart[face], "texel {t} of face {face}");
                assert!(atlas.coverage().face[t] >= 0);
            }
        }
    }
    assert!(inside > 1000);
    assert_eq!(atlas.coverage().diagnostics.overlapping_texels, 0);
}

/// Number of 4-connected texel regions of each chart.
fn regions_per_chart(atlas: &Atlas) -> Vec<usize> {
    let r = atlas.resolution();
    let chart = &atlas.coverage().chart;
    let mut seen = vec![false; r * r];
    let mut regions = vec![0usize; atlas.topology.n_charts];
    for start in 0..r * r {
        if seen[start] || chart[start] < 0 {
            continue;
        }
        regions[chart[start] as usize] += 1;
        let mut stack = vec![start];
        seen[start] = true;
        while let Some(t) = stack.pop() {
            let (i, j) = (t % r, t / r);
            let neighbours = [(i.wrapping_sub(1), j), (i + 1, j), (i, j.wrapping_sub(1)), (i, j + 1)];
            for (ni, nj) in neighbours {
                if ni < r && nj < r {
                    let n = nj * r + ni;
                    if !seen[n] && chart[n] == chart[t] {
                        seen[n] = true;
                        stack.push(n);
                    }
                }
            }
        }
    }
    regions
}

#[test]
fn each_chart_is_one_connected_texel_region() {
    for resolution in [512, 1024] {
        for shape in [uv_sphere(1.0, 48, 24), torus(2.0, 0.5, 48, 24), split_plane(16, true), split_plane(16, false)] {
            let atlas = atlas(&shape, resolution);
            let regions = regions_per_chart(&atlas);
            assert!(regions.iter().all(|&n| n == 1), "regions per chart at {resolution}: {regions:?}");
        }
    }
}

#[test]
fn thin_sliver_chart_stays_connected_through_boundary_rasterisation() {
    // A long triangle narrower than a texel covers few centres; its edges still join them.
    let shape = uvfeat_core::shapes::ShapeMesh {
        positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.01, 0.0]],
        faces: vec![[0, 1, 2]],
        uvs: vec![[0.1, 0.5], [0.9, 0.5005], [0.1, 0.5015]],
        uv_faces: vec![[0, 1, 2]],
    };
    let atlas = atlas(&shape, 512);
    assert_eq!(regions_per_chart(&atlas), vec![1]);
    assert!(atlas.coverage().diagnostics.border_texels > 400);
}

#[test]
fn every_texel_anchors_at_its_centre_or_at_the_closest_point_of_its_side() {
    for shape in [torus(2.0, 0.5, 48, 24), patchwork_sphere(6), cylinder(1.0, 2.0, 32, 8)] {
        let res = 128;
        let atlas = atlas(&shape, res);
        let (coverage, topology) = (atlas.coverage(), &atlas.topology);
        let (mut centres, mut gutters) = (0, 0);
        for t in 0..res * res {
            let Some((face, uv)) = coverage.anchor(topology, t) else {
                assert!(coverage.face[t] < 0, "texel {t} shows a face but has no anchor");
                continue;
            };
            let centre = atlas.texel_centre(t);
            if uv == centre {
                let b = barycentric(topology.corner_uvs(face as usize), uv);
                assert!(b.iter().all(|&x| x >= -1e-9), "texel {t}: its centre is not in face {face}: {b:?}");
                centres += 1;
            } else {
                // A gutter texel: the point is on its side, the closest one to the centre.
                let side = &topology.sides[coverage.border_side[t] as usize];
                let (_, [a, b]) = topology.side_endpoints(side);
                let along = (uv - a).dot(b - a) / (b - a).length_squared();
                assert!((a + (b - a) * along).distance(uv) < 1e-12 && (-1e-12..=1.0 + 1e-12).contains(&along));
                let best =
                    (0..=1000).map(|k| (a + (b - a) * (k as f64 / 1000.0)).distance(centre)).fold(f64::MAX, f64::min);
                assert!(uv.distance(centre) <= best + 1e-12, "texel {t}: not the closest point of its side");
                gutters += 1;
            }
        }
        assert!(centres > 1000 && gutters > 50, "{centres} covered and {gutters} gutter texels");
    }
}
