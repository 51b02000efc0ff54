//! DESIGN.md §5.9 acceptance checks against analytic truth, on the single-chart parameterisations
//! (the multi-chart xatlas checks run in the Python suite).

use crate::support::{atlas, median};
use uvfeat_core::features::Feature;
use uvfeat_core::output::FeatureMaps;
use uvfeat_core::settings::ComputeSettings;
use uvfeat_core::shapes::{cylinder, plane, torus, uv_sphere, ShapeMesh};
use uvfeat_core::Atlas;

const ALL: [Feature; 9] = Feature::ALL;

fn maps(atlas: &Atlas, radius: f64, resolution: usize) -> FeatureMaps {
    let mut settings = ComputeSettings::new(ALL.to_vec(), radius);
    settings.resolution = resolution;
    FeatureMaps::compute(atlas, &settings).expect("valid settings")
}

/// Median of `f(value, texel centre)` over the texels of a map where `keep(texel)` holds.
fn median_where(maps: &FeatureMaps, feature: Feature, keep: impl Fn(usize) -> bool, f: impl Fn(f64) -> f64) -> f64 {
    let k = maps.features.iter().position(|&x| x == feature).unwrap();
    median(
        (0..maps.chart.len())
            .filter(|&t| maps.n_valid[t] > 0 && keep(t))
            .map(|t| f(f64::from(maps.values[k][t])))
            .collect(),
    )
}

fn sphere() -> ShapeMesh {
    uv_sphere(1.0, 160, 80) // 25,280 triangles
}

#[test]
fn unit_sphere_meets_the_acceptance_checks() {
    let atlas = atlas(&sphere(), 512);
    let m = maps(&atlas, 0.2, 128);
    let all = |_| true;
    let h = median_where(&m, Feature::MeanCurvature, all, |h| (h - 1.0).abs());
    let k = median_where(&m, Feature::GaussianCurvature, all, |k| (k - 1.0).abs());
    let lbe = median_where(&m, Feature::BendingEnergy, all, |e| e);
    let s = median_where(&m, Feature::ShapeIndex, all, |s| s);
    let c = median_where(&m, Feature::Curvedness, all, |c| c);
    let (k1, k2) = (median_where(&m, Feature::K1, all, |x| x), median_where(&m, Feature::K2, all, |x| x));
    let vr = median_where(&m, Feature::VolumeInvariant, all, |v| v);
    let exact_vr = 2.0 * std::f64::consts::PI * 0.2f64.powi(3) / 3.0 - std::f64::consts::PI * 0.2f64.powi(4) / 4.0;
    eprintln!("sphere: |H-1| {h:.4}, |K-1| {k:.4}, LBE {lbe:.4}, S {s:.4}, C {c:.4}, k1 {k1:.4}, k2 {k2:.4}, Vr {vr:.6} vs {exact_vr:.6}");
    eprintln!("summary {:?}", m.summary);
    assert!(h < 0.03, "median |H - 1| = {h}");
    assert!(k < 0.05, "median |K - 1| = {k}");
    assert!((lbe - 1.0).abs() < 0.03, "LBE {lbe}");
    assert!(s > 0.95, "shape index {s}");
    assert!((c - 1.0).abs() < 0.03 && (k1 - 1.0).abs() < 0.05 && (k2 - 1.0).abs() < 0.05);
    assert!((vr - exact_vr).abs() < 0.01 * exact_vr, "V_r {vr} vs {exact_vr}");
    // Away from the poles, where the lat-long chart degenerates into a fan of one-triangle wedges
    // separated by seams and a sample going over the pole needs more than max_jumps crossings.
    let w = m.resolution;
    let temperate = |t: usize| ((((t / w) as f64 + 0.5) / w as f64 - 0.5) / 0.48).abs() < 0.6;
    let (missing, drawn) = (0..w * w)
        .filter(|&t| m.n_valid[t] > 0 && temperate(t))
        .fold((0u64, 0u64), |(a, b), t| (a + u64::from(m.n_missing[t]), b + 256));
    assert!((missing as f64) < 1e-3 * drawn as f64, "missing {missing} of {drawn}");
}

#[test]
fn flipped_sphere_flips_h_k1_k2_and_shape_index_but_not_k() {
    let mut shape = sphere();
    for f in &mut shape.faces {
        f.swap(1, 2);
    }
    for f in &mut shape.uv_faces {
        f.swap(1, 2);
    }
    let m = maps(&atlas(&shape, 512), 0.2, 96);
    let all = |_| true;
    assert!((median_where(&m, Feature::MeanCurvature, all, |x| x) + 1.0).abs() < 0.03);
    assert!((median_where(&m, Feature::GaussianCurvature, all, |x| x) - 1.0).abs() < 0.05);
    assert!((median_where(&m, Feature::K1, all, |x| x) + 1.0).abs() < 0.05);
    assert!(median_where(&m, Feature::ShapeIndex, all, |x| x) < -0.95);
}

#[test]
fn plane_has_zero_curvature() {
    let m = maps(&atlas(&plane(1.0, 32), 512), 0.1, 96);
    // Away from the border (where neighbourhoods are truncated and flagged).
    let interior = |t: usize| m.n_border[t] == 0;
    for feature in [Feature::MeanCurvature, Feature::GaussianCurvature, Feature::BendingEnergy] {
        let worst = median_where(&m, feature, interior, f64::abs);
        assert!(worst < 1e-3, "{feature:?}: {worst}");
    }
    assert!(m.summary.truncated_texels > 0, "border texels must be flagged");
}

#[test]
fn cylinder_has_h_one_half_and_k_zero() {
    let m = maps(&atlas(&cylinder(1.0, 4.0, 160, 64), 512), 0.2, 128);
    let interior = |t: usize| m.n_border[t] == 0;
    let h = median_where(&m, Feature::MeanCurvature, interior, |x| x);
    let k = median_where(&m, Feature::GaussianCurvature, interior, |x| x);
    let s = median_where(&m, Feature::ShapeIndex, interior, |x| x);
    eprintln!("cylinder H {h}, K {k}, S {s}");
    assert!((h - 0.5).abs() < 0.015 && k.abs() < 0.02 && (s - 0.5).abs() < 0.03);
}

#[test]
fn torus_curvature_on_the_outer_and_inner_equator() {
    let (major, minor) = (2.0, 0.5);
    let atlas = atlas(&torus(major, minor, 384, 192), 1024);
    let m = maps(&atlas, 0.15, 256);
    let w = m.resolution as f64;
    // v of a texel: UV v = 0.02 + 0.96 t, t = angle / 2pi; outer equator t = 0 / 1, inner t = 1/2.
    let angle = |t: usize| std::f64::consts::TAU * ((((t / m.resolution) as f64 + 0.5) / w - 0.02) / 0.96);
    for (name, v) in [("outer", 0.0f64), ("inner", std::f64::consts::PI)] {
        let near = |t: usize| {
            let d = (angle(t) - v).rem_euclid(std::f64::consts::TAU);
            d.min(std::f64::consts::TAU - d) < 0.05
        };
        let h_true = (major + 2.0 * minor * v.cos()) / (2.0 * minor * (major + minor * v.cos()));
        let k_true = v.cos() / (minor * (major + minor * v.cos()));
        let h = median_where(&m, Feature::MeanCurvature, near, |x| x);
        let k = median_where(&m, Feature::GaussianCurvature, near, |x| x);
        eprintln!("torus {name}: H {h:.4} (true {h_true:.4}), K {k:.4} (true {k_true:.4})");
        assert!((h - h_true).abs() < 0.05 * h_true.abs(), "{name} H {h} vs {h_true}");
        assert!((k - k_true).abs() < 0.05 * k_true.abs(), "{name} K {k} vs {k_true}");
    }
}

#[test]
fn bad_settings_are_rejected_with_the_parameter_named() {
    let atlas = atlas(&plane(1.0, 4), 64);
    for (radius, samples, resolution, what) in [
        (0.0, 256, 64, "radius"),
        (f64::NAN, 256, 64, "radius"),
        (0.1, 3, 64, "samples"),
        (0.1, 256, 0, "compute_resolution"),
    ] {
        let mut s = ComputeSettings::new(vec![Feature::MeanCurvature], radius);
        s.samples = samples;
        s.resolution = resolution;
        let err = FeatureMaps::compute(&atlas, &s).unwrap_err().to_string();
        assert!(err.contains(what), "{err}");
    }
}

/// The geodesic distances (a chord sum of 16 lookups per sample in the paper's choices) are only
/// computed when a requested feature uses the geodesic-disk K, and leaving them out changes nothing
/// else: H alone equals the H of a run that also asks for K.
#[test]
fn geodesic_distances_are_computed_only_for_the_geodesic_disk_k() {
    use uvfeat_core::features::GaussianMethod;
    use uvfeat_core::lookup::Lookup;
    use uvfeat_core::relocation::Relocation;
    use uvfeat_core::sampling::Geodesic;
    let atlas = atlas(&torus(2.0, 0.5, 96, 48), 256);
    let paper_like = |features: Vec<Feature>| {
        let mut settings = ComputeSettings::new(features, 0.3);
        settings.resolution = 48;
        settings.gaussian_method = GaussianMethod::GeodesicArea;
        settings.geodesic = Geodesic::ChordSum;
        settings.lookup = Lookup::Bilinear;
        settings.relocation = Relocation::PerChart;
        settings
    };
    let alone = paper_like(vec![Feature::MeanCurvature]);
    let with_k = paper_like(vec![Feature::MeanCurvature, Feature::GaussianCurvature]);
    assert!(!alone.sampler().with_geodesic);
    assert!(with_k.sampler().with_geodesic);
    for uses_k in [Feature::K1, Feature::K2, Feature::ShapeIndex, Feature::Curvedness] {
        assert!(paper_like(vec![uses_k]).sampler().with_geodesic, "{uses_k:?}");
    }
    let h_alone = FeatureMaps::compute(&atlas, &alone).unwrap();
    let h_with_k = FeatureMaps::compute(&atlas, &with_k).unwrap();
    let k = h_with_k.features.iter().position(|&f| f == Feature::GaussianCurvature).unwrap();
    assert!(h_with_k.values[k].iter().filter(|v| v.is_finite()).count() > 1000, "K was computed");
    let same = h_alone.values[0].iter().zip(&h_with_k.values[0]).all(|(a, b)| a == b || (a.is_nan() && b.is_nan()));
    assert!(same, "H changed when the geodesic distances were left out");
}
