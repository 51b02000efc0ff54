//! `quadrature = "surfels"` (DESIGN.md §1.4.8) against the analytic truth across rotated seams.

use crate::support::{atlas, errors, median, patchwork_sphere, unit_sphere};
use uvfeat_core::evaluation::{evaluate_point, Patterns};
use uvfeat_core::features::Feature;
use uvfeat_core::output::{per_vertex, vertex_values, vertex_values_at_radii, FeatureMaps, VertexValues};
use uvfeat_core::raster::Surface;
use uvfeat_core::sampling::Placement;
use uvfeat_core::sampling::Quadrature;
use uvfeat_core::settings::{ComputeSettings, VertexQuery};

fn settings(radius: f64) -> ComputeSettings {
    let features = vec![Feature::MeanCurvature, Feature::GaussianCurvature, Feature::BendingEnergy];
    let mut settings = ComputeSettings::new(features, radius);
    settings.resolution = 96;
    settings.quadrature = Quadrature::Surfels;
    settings
}

#[test]
fn surfels_across_rotated_seams_meet_the_analytic_sphere() {
    let atlas = atlas(&patchwork_sphere(4), 512);
    let maps = FeatureMaps::compute(&atlas, &settings(0.5)).unwrap();
    let [h, k] = errors(&atlas, &maps, unit_sphere);
    // The pattern's shared lattice: about 0.3 % / 1 % here; a wrong factor would be tens of percent.
    assert!(h < 0.01 && k < 0.02, "H {h}, K {k}");
}

/// Median relative errors of per-vertex H and K against the unit sphere's 1 and 1.
fn vertex_errors(values: &[Vec<f32>]) -> [f64; 2] {
    [0, 1].map(|k| median(values[k].iter().map(|&v| (f64::from(v) - 1.0).abs()).collect()))
}

#[test]
fn values_at_the_vertices_meet_the_analytic_sphere_across_rotated_seams() {
    let atlas = atlas(&patchwork_sphere(4), 512);
    // Measured: smooth 0.01 % / 0.6 %; facets, whose chords sit inside the sphere, 0.9 % / 2.4 %.
    for (surface, [h_bound, k_bound]) in [(Surface::Smooth, [0.002, 0.012]), (Surface::Facets, [0.015, 0.035])] {
        let mut s = settings(0.5);
        s.surface = surface;
        let VertexValues { values, counts } = vertex_values(&atlas, &s).unwrap();
        let [h, k] = vertex_errors(&values);
        // A wrong factor or sign would be far outside.
        assert!(h < h_bound && k < k_bound, "{surface:?}: H {h}, K {k}");
        // A closed sphere: every ball holds its surfels, and none is cut by a border.
        assert!(counts.iter().all(|c| c.valid > 100 && c.border == 0), "{:?}", counts.iter().min_by_key(|c| c.valid));
    }
}

#[test]
fn values_at_the_vertices_agree_with_the_flat_surfels_and_need_them() {
    let atlas = atlas(&patchwork_sphere(4), 512);
    let mut s = settings(0.3);
    s.surface = Surface::Facets;
    let at_vertices = vertex_values(&atlas, &s).unwrap().values;
    // The flat quadrature at one corner UV of each vertex, through the general evaluation.
    let topology = &atlas.topology;
    let mut corner_uv = vec![None; topology.n_geometric()];
    for (face, corners) in topology.faces.iter().enumerate() {
        for (k, &vertex) in corners.iter().enumerate() {
            corner_uv[vertex as usize].get_or_insert(topology.walk_faces[face].corners[k]);
        }
    }
    let patterns = Patterns::new(&s);
    let mut scratch = Vec::new();
    let flat: Vec<[f32; 9]> = corner_uv
        .iter()
        .enumerate()
        .map(|(g, uv)| {
            evaluate_point(&atlas, uv.unwrap(), Placement::of_vertex(g as u32, 0), &s, &patterns, &mut scratch).values
        })
        .collect();
    let ids = &topology.vertex_ids;
    for (f, values) in [Feature::MeanCurvature, Feature::GaussianCurvature].iter().zip(&at_vertices) {
        let gap =
            median(ids.iter().zip(values).map(|(&g, &v)| f64::from((v - flat[g as usize][f.index()]).abs())).collect());
        assert!(gap < 0.01, "{f:?}: median gap {gap}");
    }
    // The direct query of surfel maps is these values.
    let maps = FeatureMaps::compute(&atlas, &s).unwrap();
    assert_eq!(per_vertex(&atlas, &maps, &s, VertexQuery::Direct).unwrap(), at_vertices);
    s.quadrature = Quadrature::Pattern;
    let err = vertex_values(&atlas, &s).unwrap_err().to_string();
    assert!(err.contains("surfels"), "{err}");
}

#[test]
fn each_vertex_takes_its_own_radius() {
    let atlas = atlas(&patchwork_sphere(4), 512);
    let n = atlas.topology.vertex_ids.len();
    let radii: Vec<f64> = (0..n).map(|v| if v % 2 == 0 { 0.3 } else { 0.6 }).collect();
    let own = vertex_values_at_radii(&atlas, &settings(0.6), &radii).unwrap().values;
    // Exactly the single radius's values at its vertices, whatever `settings.radius` says.
    for r in [0.3, 0.6] {
        let single = vertex_values(&atlas, &settings(r)).unwrap().values;
        for (own, single) in own.iter().zip(&single) {
            for v in (0..n).filter(|&v| radii[v] == r) {
                assert_eq!(own[v].to_bits(), single[v].to_bits(), "vertex {v} at r = {r}");
            }
        }
    }
    let err = vertex_values_at_radii(&atlas, &settings(0.6), &radii[1..]).unwrap_err().to_string();
    assert!(err.contains("radii for"), "{err}");
    let mut bad = radii.clone();
    bad[3] = 0.0;
    let err = vertex_values_at_radii(&atlas, &settings(0.6), &bad).unwrap_err().to_string();
    assert!(err.contains("vertex 3"), "{err}");
}
