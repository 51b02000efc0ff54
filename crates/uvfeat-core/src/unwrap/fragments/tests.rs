//! The merges of `unwrap/fragments.rs` on a flat grid whose charts are its projection.

use super::super::face_neighbours;
use super::super::segment::ChartFrame;
use super::*;
use crate::shapes::plane;
use glam::DVec3;
use std::collections::HashMap;

/// A flat 8x8-cell grid charted by its projection (chart 0, and chart 2 right of `split`),
/// except the faces around the vertex at `(column, row)`, which form chart 1 (UVs far away).
fn charted_grid(column: usize, row: usize, split: Option<f64>) -> (Vec<DVec3>, Vec<[u32; 3]>, Charts) {
    let shape = plane(1.0, 8);
    let positions: Vec<DVec3> = shape.positions.iter().map(|&p| DVec3::from_array(p)).collect();
    let faces: Vec<[u32; 3]> = shape.faces.iter().map(|t| t.map(|v| v as u32)).collect();
    let centre = (row * 9 + column) as u32;
    let chart_of = |t: &[u32; 3]| {
        let x = t.iter().map(|&v| positions[v as usize].x).sum::<f64>() / 3.0;
        if t.contains(&centre) {
            1
        } else {
            u32::from(split.is_some_and(|s| x > s)) * 2
        }
    };
    let flat = ChartFrame { origin: DVec3::ZERO, t1: DVec3::X, t2: DVec3::Y };
    let away = ChartFrame { origin: DVec3::new(-10.0, -10.0, 0.0), ..flat };
    let mut charts = Charts {
        uv_faces: vec![[0; 3]; faces.len()],
        uvs: Vec::new(),
        uv_chart: Vec::new(),
        n_charts: if split.is_some() { 3 } else { 2 },
        frames: vec![flat, away, flat],
    };
    let mut uv_of: HashMap<(u32, u32), u32> = HashMap::new();
    for (f, t) in faces.iter().enumerate() {
        let chart = chart_of(t);
        charts.uv_faces[f] = t.map(|v| {
            *uv_of.entry((chart, v)).or_insert_with(|| {
                charts.uvs.push(charts.frames[chart as usize].project(positions[v as usize]));
                charts.uv_chart.push(chart);
                charts.uvs.len() as u32 - 1
            })
        });
    }
    (positions, faces, charts)
}

/// Runs `body` on the face graph of a flat mesh.
fn on_graph<T>(positions: &[DVec3], faces: &[[u32; 3]], body: impl FnOnce(&FaceGraph) -> T) -> T {
    let neighbours = face_neighbours(faces);
    let flat = vec![DVec3::Z; faces.len()];
    let graph = FaceGraph {
        positions,
        faces,
        neighbours: &neighbours,
        normals: &flat,
        smoothed_normals: &flat,
        centroids: &flat,
        cell: 1.0,
    };
    body(&graph)
}

fn merged(positions: &[DVec3], faces: &[[u32; 3]], charts: &mut Charts) {
    on_graph(positions, faces, |graph| merge_fragments(graph, charts));
}

/// Every face's UVs are its corners' projection, and its chart the one `chart_of` expects.
fn assert_projected(positions: &[DVec3], faces: &[[u32; 3]], charts: &Charts, chart_of: impl Fn(usize) -> u32) {
    for (f, t) in faces.iter().enumerate() {
        let uv = charts.uv_faces[f].map(|k| charts.uvs[k as usize]);
        for (k, &v) in t.iter().enumerate() {
            assert!(uv[k].distance(positions[v as usize].truncate()) < 1e-9, "face {f}: {uv:?}");
        }
        assert_eq!(charts.uv_chart[charts.uv_faces[f][0] as usize], chart_of(f), "face {f}");
    }
}

#[test]
fn a_fragment_inside_a_chart_is_filled_with_it() {
    let (positions, faces, mut charts) = charted_grid(3, 4, None);
    let before = charts.uvs.len();
    merged(&positions, &faces, &mut charts);
    assert_eq!((charts.n_charts, charts.frames.len()), (1, 1));
    // The fragment's seven UV vertices gave way to one: its centre's, at the mean of its ring,
    // which on this grid is where it projects.
    assert_eq!(charts.uvs.len(), before - 7 + 1);
    assert_projected(&positions, &faces, &charts, |_| 0);
}

#[test]
fn a_fragment_between_two_charts_joins_the_one_it_shares_most_edges_with() {
    // The fan around (3, 4) at x = 0.375 borders chart 2 (x > 0.4) on two of its edges.
    let (positions, faces, mut charts) = charted_grid(3, 4, Some(0.4));
    let right: Vec<bool> =
        faces.iter().map(|t| t.iter().map(|&v| positions[v as usize].x).sum::<f64>() / 3.0 > 0.4).collect();
    let fan: Vec<bool> = faces.iter().map(|t| t.contains(&(4 * 9 + 3))).collect();
    merged(&positions, &faces, &mut charts);
    assert_eq!(charts.n_charts, 2);
    assert_projected(&positions, &faces, &charts, |f| u32::from(right[f] && !fan[f]));
}

#[test]
fn a_fragment_on_the_border_stays_a_chart() {
    let (positions, faces, mut charts) = charted_grid(0, 4, None);
    let (uvs, uv_faces, n_charts) = (charts.uvs.clone(), charts.uv_faces.clone(), charts.n_charts);
    merged(&positions, &faces, &mut charts);
    assert_eq!((charts.uvs, charts.uv_faces, charts.n_charts), (uvs, uv_faces, n_charts));
}

#[test]
fn a_fragment_that_would_overlap_its_first_choice_joins_the_other_chart() {
    // Chart 0's plane moved: the fragment's vertices it does not hold would land on its faces.
    let (positions, faces, mut charts) = charted_grid(3, 4, Some(0.4));
    charts.frames[0].origin = DVec3::new(0.3, 0.0, 0.0);
    let right: Vec<bool> =
        faces.iter().map(|t| t.iter().map(|&v| positions[v as usize].x).sum::<f64>() / 3.0 > 0.4).collect();
    let fan: Vec<bool> = faces.iter().map(|t| t.contains(&(4 * 9 + 3))).collect();
    merged(&positions, &faces, &mut charts);
    assert_eq!(charts.n_charts, 2);
    assert_projected(&positions, &faces, &charts, |f| u32::from(right[f] || fan[f]));
}

#[test]
fn placed_faces_overlap_the_charts_faces_only_where_they_cover_them() {
    let (positions, faces, charts) = charted_grid(3, 4, Some(0.4));
    on_graph(&positions, &faces, |graph| {
        let layout = Layout::new(graph, &charts);
        let fragment: Vec<u32> = (0..faces.len() as u32).filter(|&f| layout.face_chart[f as usize] == 1).collect();
        let of_chart = |g: u32| layout.face_chart[g as usize] == 0;
        let shifted = |f: u32, shift: DVec2| faces[f as usize].map(|v| positions[v as usize].truncate() + shift);
        assert!(!overlaps(&charts, &layout, &fragment, 0, &|f| shifted(f, DVec2::ZERO), &of_chart));
        assert!(overlaps(&charts, &layout, &fragment, 0, &|f| shifted(f, DVec2::new(-0.125, 0.0)), &of_chart));
        // The fragment's faces over one another.
        let folded = |f: u32| shifted(if f == fragment[0] { fragment[1] } else { f }, DVec2::ZERO);
        assert!(overlaps(&charts, &layout, &fragment, 0, &folded, &|_| false));
    });
}

#[test]
fn a_hole_the_mean_placement_would_fold_is_widened_until_it_fills() {
    let (positions, faces, mut charts) = charted_grid(3, 4, None);
    // The hole's border vertex right of its centre moves, in the chart around it, to the
    // centre's left: the faces of the fan next to it would turn the other way.
    let right = (4 * 9 + 4) as usize;
    let k = (0..charts.uvs.len())
        .find(|&k| charts.uv_chart[k] == 0 && charts.uvs[k] == positions[right].truncate())
        .expect("the chart's UV of the vertex");
    charts.uvs[k].x -= 0.2;
    on_graph(&positions, &faces, |graph| {
        let layout = Layout::new(graph, &charts);
        let fragment: Vec<u32> = (0..faces.len() as u32).filter(|&f| layout.face_chart[f as usize] == 1).collect();
        let (uvs, uv_faces) = (charts.uvs.clone(), charts.uv_faces.clone());
        assert!(!merge(graph, &mut charts, &layout, &fragment, 0));
        assert_eq!((&charts.uvs, &charts.uv_faces), (&uvs, &uv_faces), "a refused merge changed the charts");
        merge_fragments(graph, &mut charts);
        assert_eq!(charts.n_charts, 1);
        let area = |f: usize| {
            let uv = charts.uv_faces[f].map(|k| charts.uvs[k as usize]);
            (uv[1] - uv[0]).perp_dot(uv[2] - uv[0])
        };
        assert!((0..faces.len()).all(|f| area(f) > 0.0), "a face turns the wrong way");
    });
}
