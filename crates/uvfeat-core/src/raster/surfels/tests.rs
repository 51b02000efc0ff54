use super::*;
use crate::mesh::{Topology, TriangleMesh};
use crate::shapes;

fn torus_surfels(width: usize) -> (f64, Surfels) {
    let torus = shapes::torus(2.0, 0.5, 64, 32);
    let mesh = TriangleMesh::new(&torus.positions, &torus.faces, &torus.uvs, &torus.uv_faces).unwrap();
    let topology = Topology::build(&mesh, 0.0).unwrap();
    let frame = Frame::new(&topology, &mesh.positions).unwrap();
    let area: f64 = mesh
        .faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| mesh.positions[v as usize]);
            (b - a).cross(c - a).length() / 2.0
        })
        .sum();
    (area, Surfels::build(&topology, &frame, width, Surface::Facets))
}

#[test]
fn surfels_partition_the_surface_at_every_level() {
    let (area, surfels) = torus_surfels(64);
    // The torus (area 4 pi^2, its facets' 0.2 % less) on [0.02, 0.98]^2: texels of 2 pi / (0.96 64).
    let side = std::f64::consts::TAU / (0.96 * 64.0);
    assert!((surfels.texel_side / side - 1.0).abs() < 0.005, "{} vs {side}", surfels.texel_side);
    // Up to the first cubes wider than the torus (5 across): 2^6 texels of 0.102.
    assert_eq!(surfels.levels.len(), 7);
    for (k, level) in surfels.levels.iter().enumerate() {
        let total: f64 = level.point.iter().map(|p| p.area).sum();
        assert!((total / area - 1.0).abs() < 1e-9, "level {k}: {total} vs {area}");
    }
    // Each level holds fewer surfels, down to a few per facing at the top.
    let counts: Vec<usize> = surfels.levels.iter().map(SurfelLevel::len).collect();
    assert!(counts.windows(2).all(|n| n[1] < n[0]), "{counts:?}");
    assert!(*counts.last().unwrap() <= 24, "{counts:?}");
}

#[test]
fn coarse_surfels_keep_their_pieces_spread() {
    let (_, surfels) = torus_surfels(64);
    for (fine, coarse) in surfels.levels.iter().zip(&surfels.levels[1..]) {
        let mut spread = vec![0.0; coarse.len()];
        for (s, p) in fine.point.iter().enumerate() {
            let parent = fine.parent[s] as usize;
            spread[parent] += p.spread + p.area * (p.position - coarse.point[parent].position).length_squared();
        }
        for (p, s) in coarse.point.iter().zip(spread) {
            assert!((s / p.spread - 1.0).abs() < 1e-9, "{s} vs {}", p.spread);
        }
    }
    // A disk has the least spread for its area, and the finest surfels (near rectangles of a
    // texel, up to 5:1 on this torus) hold at most a few times a disk's.
    for p in &surfels.levels[0].point {
        let disk = p.area * p.area / std::f64::consts::TAU;
        assert!(p.spread >= disk * (1.0 - 1e-9) && p.spread < 6.0 * disk, "{p:?}");
    }
}

#[test]
fn the_seam_of_a_torus_chart_links_both_sides() {
    // The lat-long torus is one chart whose u = 0 and u = 1 edges (and v = 0, v = 1) are seams:
    // surfels in the first column link to surfels in the last.
    let (_, surfels) = torus_surfels(64);
    let level = &surfels.levels[0];
    let row: Vec<i64> = (0..64).filter(|&i| level.at(20 * 64 + i as usize, 0).is_some()).collect();
    let (left, right) = (row[0], row[row.len() - 1]);
    assert!(right - left > 56, "{row:?}");
    let across: Vec<(i64, i64)> =
        level.neighbours(level.at(20 * 64 + left as usize, 0).unwrap()).iter().map(|&s| level.texel(s)).collect();
    assert!(across.iter().any(|&(i, j)| i == right && (j - 20).abs() <= 1), "{across:?}");
    assert!(level.on_border.iter().all(|&b| !b));
}

/// Level `k`'s key (cube along the 3D Z curve, facing) of every surfel of level `k - 1`.
fn keys_above(surfels: &Surfels, k: usize) -> Vec<(u64, u8)> {
    let origin = surfels.levels[0].point.iter().fold(DVec3::INFINITY, |lo, p| lo.min(p.position));
    let fine = &surfels.levels[k - 1];
    (0..fine.len())
        .map(|s| {
            let at = ((fine.point[s].position - origin) / surfels.cell(k)).max(DVec3::ZERO);
            (morton3(at.x as usize, at.y as usize, at.z as usize), facing(fine.normal[s]))
        })
        .collect()
}

#[test]
fn coarse_surfels_are_connected_pieces_of_a_cube_facing_one_way() {
    let (_, surfels) = torus_surfels(64);
    for k in 1..surfels.levels.len() {
        let (fine, coarse) = (&surfels.levels[k - 1], &surfels.levels[k]);
        let keys = keys_above(&surfels, k);
        let mut key_of_parent = vec![None; coarse.len()];
        for s in 0..fine.len() as u32 {
            let p = fine.parent[s as usize];
            // One cube and facing per coarse surfel.
            assert_eq!(*key_of_parent[p as usize].get_or_insert(keys[s as usize]), keys[s as usize], "level {k}");
            for &t in fine.neighbours(s) {
                let q = fine.parent[t as usize];
                assert!(p == q || coarse.neighbours(p).contains(&q), "level {k}");
                // Adjacent surfels of one cube and facing are one surfel above.
                assert!(keys[s as usize] != keys[t as usize] || p == q, "level {k}");
            }
        }
        // Numbered along the 3D Z curve of their cubes.
        let ordered: Vec<(u64, u8)> = key_of_parent.into_iter().map(Option::unwrap).collect();
        assert!(ordered.windows(2).all(|w| w[0] <= w[1]), "level {k} out of Z order");
    }
}

#[test]
fn the_finest_level_is_in_z_order_of_its_texels_and_finds_each_surfel_by_texel() {
    let (_, surfels) = torus_surfels(64);
    let finest = &surfels.levels[0];
    let key = |s: usize| {
        let (i, j) = finest.texel(s as u32);
        (morton(i as usize, j as usize), finest.chart[s])
    };
    assert!((1..finest.len()).all(|s| key(s - 1) <= key(s)), "finest level out of Z order");
    assert!((1..finest.len()).all(|s| finest.texel[s - 1] != finest.texel[s] || finest.chart[s - 1] < finest.chart[s]));
    for s in 0..finest.len() {
        let texel = finest.texel[s] as usize;
        assert_eq!(finest.at(texel, finest.chart[s]), Some(s as u32));
    }
    assert_eq!(finest.at(0, 99), None);
}
