//! Exact polyhedral geodesics of the reference against analytic distances and invariants.

use glam::DVec3;
use std::f64::consts::PI;
use uvfeat_core::reference::{EdgePaths, ExactGeodesic, Geometry, ReferenceMesh};
use uvfeat_core::shapes::{cylinder, plane, torus, uv_sphere, ShapeMesh};

struct Prepared {
    mesh: ReferenceMesh,
    geometry: Geometry,
}

fn prepare(shape: &ShapeMesh) -> Prepared {
    let mesh = ReferenceMesh::new(&shape.positions, &shape.faces).expect("valid analytic mesh");
    let positions: Vec<DVec3> = shape.positions.iter().map(|p| DVec3::from_array(*p)).collect();
    let geometry = Geometry::new(mesh.connectivity(), &positions);
    Prepared { mesh, geometry }
}

impl Prepared {
    /// Exact distances from input vertex `source` to every welded vertex (`inf` beyond `bound`).
    fn exact(&self, source: usize, bound: f64) -> Vec<f64> {
        let c = self.mesh.connectivity();
        let mut search = ExactGeodesic::new(c.n_vertices());
        search.run(c.vertex_ids[source], bound, c, &self.geometry);
        (0..c.n_vertices() as u32).map(|v| search.distances.get(v)).collect()
    }

    fn edge_paths(&self, source: usize, bound: f64) -> Vec<f64> {
        let c = self.mesh.connectivity();
        let mut search = EdgePaths::new(c.n_vertices());
        search.run(c.vertex_ids[source], bound, c, &self.geometry.positions);
        (0..c.n_vertices() as u32).map(|v| search.distances.get(v)).collect()
    }

    fn welded(&self, input: usize) -> usize {
        self.mesh.connectivity().vertex_ids[input] as usize
    }
}

#[test]
fn distances_on_a_plane_are_euclidean() {
    let shape = plane(2.0, 40);
    let m = prepare(&shape);
    let source = 20 * 41 + 20; // (1, 1), the middle of the grid
    let d = m.exact(source, 0.7);
    let p = &m.geometry.positions;
    let centre = p[m.welded(source)];
    let mut checked = 0;
    for (v, &dv) in d.iter().enumerate() {
        let euclid = p[v].distance(centre);
        if euclid <= 0.7 {
            assert!((dv - euclid).abs() < 1e-9, "vertex {v}: {dv} vs {euclid}");
            checked += 1;
        }
    }
    assert!(checked > 500, "{checked}");
}

#[test]
fn distances_on_a_developable_cylinder_are_those_of_the_unrolled_strip() {
    // Each quad of the polyhedral cylinder is a flat w x dz rectangle, so it unrolls isometrically
    // into a strip whose columns have the chord width w = 2 sin(pi / n).
    let (n, rows) = (64usize, 32usize);
    let shape = cylinder(1.0, 2.0, n, rows);
    let m = prepare(&shape);
    let (i0, j0) = (5usize, 16usize);
    let d = m.exact(j0 * n + i0, 1.0);
    let w = 2.0 * (PI / n as f64).sin();
    let mut checked = 0;
    for j in 0..=rows {
        for i in 0..n {
            let di = i.abs_diff(i0).min(n - i.abs_diff(i0)) as f64;
            let dz = 2.0 * (j as f64 - j0 as f64) / rows as f64;
            let unrolled = (di * w).hypot(dz);
            if unrolled <= 1.0 {
                let got = d[m.welded(j * n + i)];
                assert!((got - unrolled).abs() < 1e-9, "({i}, {j}): {got} vs {unrolled}");
                checked += 1;
            }
        }
    }
    assert!(checked > 500, "{checked}");
}

/// Euclidean <= exact <= edge paths wherever both are known, and the exact distance is symmetric
/// (any missed or wrongly pruned window breaks symmetry).
fn check_invariants(m: &Prepared, source: usize, bound: f64, partners: usize) -> f64 {
    let exact = m.exact(source, bound);
    let edges = m.edge_paths(source, 2.0 * bound);
    let p = &m.geometry.positions;
    let centre = m.welded(source);
    let mut within: Vec<usize> = (0..exact.len()).filter(|&v| exact[v] <= bound).collect();
    assert!(within.len() > 100, "{} vertices within the bound", within.len());
    for &v in &within {
        let chord = p[v].distance(p[centre]);
        assert!(exact[v] >= chord - 1e-12, "vertex {v}: geodesic {} < chord {chord}", exact[v]);
        assert!(exact[v] <= edges[v] + 1e-12, "vertex {v}: geodesic {} > edge path {}", exact[v], edges[v]);
    }
    let mut worst: f64 = 0.0;
    within.retain(|&v| exact[v] < bound / 2.0 && v != centre);
    let welded_to_input: Vec<usize> = {
        let ids = &m.mesh.connectivity().vertex_ids;
        let mut back = vec![0; exact.len()];
        for (input, &g) in ids.iter().enumerate().rev() {
            back[g as usize] = input;
        }
        back
    };
    for &v in within.iter().step_by((within.len() / partners).max(1)) {
        let back = m.exact(welded_to_input[v], bound)[centre];
        worst = worst.max((back - exact[v]).abs() / exact[v]);
    }
    assert!(worst < 1e-9, "asymmetric distances: relative difference {worst}");
    worst
}

#[test]
fn sphere_distances_follow_great_circles_and_are_symmetric() {
    let shape = uv_sphere(1.0, 96, 48);
    let m = prepare(&shape);
    let source = 20 * 96 + 7; // latitude -15 degrees
    check_invariants(&m, source, 0.8, 12);
    // The polyhedral geodesic is close to the great-circle arc (chords are shorter than arcs).
    let d = m.exact(source, 0.8);
    let p = &m.geometry.positions;
    let a = p[m.welded(source)];
    let mut worst: f64 = 0.0;
    for (v, &dv) in d.iter().enumerate() {
        let arc = a.dot(p[v]).clamp(-1.0, 1.0).acos();
        if dv <= 0.8 && arc > 0.2 {
            worst = worst.max((dv - arc).abs() / arc);
        }
    }
    eprintln!("sphere 96x48: worst relative difference to the great circle {worst:.2e}");
    assert!(worst < 2e-3, "{worst}");
}

#[test]
fn torus_distances_through_saddles_are_symmetric_and_bounded() {
    // The inner equator is made of saddle vertices: shortest paths bend around them.
    let shape = torus(2.0, 0.5, 96, 48);
    let m = prepare(&shape);
    let inner = 24 * 96 + 10;
    check_invariants(&m, inner, 0.9, 12);
    let outer = 10;
    check_invariants(&m, outer, 0.9, 12);
}
