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

/// Every level of `surfels`, finest first (each built on its first use).
fn every_level(surfels: &Surfels) -> impl Iterator<Item = &SurfelLevel> {
    (0..surfels.n_levels()).map(|k| surfels.level(k))
}

#[test]
fn coarser_levels_are_built_on_first_use_and_the_coarsest_from_all_below() {
    let (_, surfels) = torus_surfels(64);
    assert!(surfels.levels[0].get().is_some() && surfels.levels[1..].iter().all(|level| level.get().is_none()));
    assert_eq!(surfels.ancestor(0, 0), 0);
    let top = surfels.ancestor(0, 4);
    assert!(surfels.levels.iter().all(|level| level.get().is_some()));
    assert_eq!(surfels.level(4).chart[top as usize], surfels.level(0).chart[0]);
}

#[test]
fn surfels_partition_the_surface_at_every_level() {
    let (area, surfels) = torus_surfels(64);
    assert_eq!(surfels.n_levels(), 5); // 64, 32, 16, 8, 4
    for level in every_level(&surfels) {
        let total: f64 = level.point.iter().map(|p| p.area).sum();
        assert!((total / area - 1.0).abs() < 1e-9, "level {}: {total} vs {area}", level.width);
    }
}

#[test]
fn coarse_surfels_keep_their_pieces_spread() {
    let (_, surfels) = torus_surfels(64);
    for (fine, coarse) in every_level(&surfels).zip(every_level(&surfels).skip(1)) {
        let mut spread = vec![0.0; coarse.len()];
        for (s, p) in fine.point.iter().enumerate() {
            let parent = coarse.finer_parent[s] as usize;
            spread[parent] += p.spread + p.area * (p.position - coarse.point[parent].position).length_squared();
        }
        for (p, s) in coarse.point.iter().zip(spread) {
            assert!((s / p.spread - 1.0).abs() < 1e-9, "{s} vs {}", p.spread);
        }
    }
    // A disk has the least spread for its area, and the finest surfels (near rectangles of a
    // texel, up to 5:1 on this torus) hold at most a few times a disk's.
    for p in &surfels.level(0).point {
        let disk = p.area * p.area / std::f64::consts::TAU;
        assert!(p.spread >= disk * (1.0 - 1e-9) && p.spread < 6.0 * disk, "{p:?}");
    }
}

#[test]
fn the_seam_of_a_torus_chart_links_both_sides() {
    // The lat-long torus is one chart whose u = 0 and u = 1 edges (and v = 0, v = 1) are seams:
    // surfels in the first column link to surfels in the last.
    let (_, surfels) = torus_surfels(64);
    let level = surfels.level(0);
    let row: Vec<i64> = (0..64).filter(|&i| level.at(20 * 64 + i as usize, 0).is_some()).collect();
    let (left, right) = (row[0], row[row.len() - 1]);
    assert!(right - left > 56, "{row:?}");
    let across: Vec<(i64, i64)> =
        level.neighbours(level.at(20 * 64 + left as usize, 0).unwrap()).iter().map(|&s| level.texel(s)).collect();
    assert!(across.iter().any(|&(i, j)| i == right && (j - 20).abs() <= 1), "{across:?}");
    assert!(level.on_border.iter().all(|&b| !b));
}

#[test]
fn coarse_surfels_are_connected_pieces_with_their_parents_neighbours() {
    let (_, surfels) = torus_surfels(64);
    for (fine, coarse) in every_level(&surfels).zip(every_level(&surfels).skip(1)) {
        for s in 0..fine.len() as u32 {
            let p = coarse.finer_parent[s as usize];
            assert_eq!(coarse.chart[p as usize], fine.chart[s as usize]);
            for &t in fine.neighbours(s) {
                let q = coarse.finer_parent[t as usize];
                assert!(p == q || coarse.neighbours(p).contains(&q));
            }
        }
    }
    // One chart, no slit: one surfel per covered coarse texel.
    let top = surfels.level(surfels.n_levels() - 1);
    let mut texels = top.texel.clone();
    texels.dedup();
    assert_eq!(texels.len(), top.len());
}

#[test]
fn every_level_is_in_z_order_and_the_finest_finds_each_surfel_by_texel() {
    let (_, surfels) = torus_surfels(64);
    for level in every_level(&surfels) {
        let key = |s: usize| {
            let (i, j) = level.texel(s as u32);
            (morton(i as usize, j as usize), level.chart[s])
        };
        // Two pieces of one chart in one coarse texel share a key (they stay apart when not adjacent).
        assert!((1..level.len()).all(|s| key(s - 1) <= key(s)), "level {} out of Z order", level.width);
    }
    let finest = surfels.level(0);
    assert!((1..finest.len()).all(|s| finest.texel[s - 1] != finest.texel[s] || finest.chart[s - 1] < finest.chart[s]));
    for s in 0..finest.len() {
        let texel = finest.texel[s] as usize;
        assert_eq!(finest.at(texel, finest.chart[s]), Some(s as u32));
    }
    assert_eq!(finest.at(0, 99), None);
}

#[test]
fn texels_are_joined_through_a_face_not_across_a_notch_of_the_chart() {
    // A flat U in UV (and in space): two arms 0.002 apart, the texel side u = 0.25 of a 16² grid
    // between them, joined by a band at the bottom. The arms' surfels beside that side are not
    // adjacent; the band's, which one face spans, are.
    let (us, vs) = ([0.1, 0.249, 0.251, 0.4], [0.1, 0.2, 0.9]);
    let points: Vec<[f64; 3]> = vs.iter().flat_map(|&v| us.iter().map(move |&u| [u, v, 0.0])).collect();
    let uvs: Vec<[f64; 2]> = points.iter().map(|p| [p[0], p[1]]).collect();
    let quads = [(0, 0), (1, 0), (2, 0), (0, 1), (2, 1)];
    let faces: Vec<[i64; 3]> = quads
        .iter()
        .flat_map(|&(a, b)| {
            let at = |a: i64, b: i64| b * 4 + a;
            [[at(a, b), at(a + 1, b), at(a + 1, b + 1)], [at(a, b), at(a + 1, b + 1), at(a, b + 1)]]
        })
        .collect();
    let mesh = TriangleMesh::new(&points, &faces, &uvs, &faces).unwrap();
    let topology = Topology::build(&mesh, 0.0).unwrap();
    assert_eq!(topology.n_charts, 1);
    let frame = Frame::new(&topology, &mesh.positions).unwrap();
    let surfels = Surfels::build(&topology, &frame, 16, Surface::Facets);
    let level = surfels.level(0);
    let at = |i: usize, j: usize| level.at(j * 16 + i, 0).unwrap();
    assert!(!level.neighbours(at(3, 8)).contains(&at(4, 8)), "the arms are joined across the notch");
    assert!(level.neighbours(at(3, 2)).contains(&at(4, 2)), "the band's faces join its texels");
    assert!(level.neighbours(at(3, 8)).contains(&at(3, 7)) && level.neighbours(at(2, 8)).contains(&at(3, 8)));
}
