//! The fitting estimator against analytic truth: curvatures as accurate as the integral
//! estimators, principal directions of a torus and an ellipsoid within 2 degrees, consistent at
//! the seams and invariant under a rigid motion.

use crate::support::{atlas, median};
use glam::{DMat3, DQuat, DVec2, DVec3};
use uvfeat_core::features::{CurvatureMethod, Feature};
use uvfeat_core::lookup::Lookup;
use uvfeat_core::output::{per_vertex_directions, FeatureMaps};
use uvfeat_core::sampling::centre_at;
use uvfeat_core::settings::ComputeSettings;
use uvfeat_core::shapes::{cylinder, ellipsoid, torus, uv_sphere, ShapeMesh};
use uvfeat_core::Atlas;

const CURVATURES: [Feature; 4] = [Feature::MeanCurvature, Feature::GaussianCurvature, Feature::K1, Feature::K2];

fn maps(atlas: &Atlas, radius: f64, resolution: usize, method: CurvatureMethod) -> FeatureMaps {
    let mut settings = ComputeSettings::new(CURVATURES.to_vec(), radius);
    settings.resolution = resolution;
    settings.method = method;
    FeatureMaps::compute(atlas, &settings).expect("valid settings")
}

/// Median over evaluated texels of `|value - truth|` for `feature`.
fn median_error(maps: &FeatureMaps, feature: Feature, truth: f64, keep: impl Fn(usize) -> bool) -> f64 {
    let k = maps.features.iter().position(|&x| x == feature).unwrap();
    median(
        (0..maps.chart.len())
            .filter(|&t| maps.n_valid[t] > 0 && maps.n_border[t] == 0 && keep(t))
            .map(|t| (f64::from(maps.values[k][t]) - truth).abs())
            .collect(),
    )
}

fn texel_uv(maps: &FeatureMaps, t: usize) -> DVec2 {
    let w = maps.resolution;
    DVec2::new(((t % w) as f64 + 0.5) / w as f64, ((t / w) as f64 + 0.5) / w as f64)
}

/// Angle in degrees between two line fields (sign-free).
fn line_angle(a: DVec3, b: DVec3) -> f64 {
    a.normalize().dot(b.normalize()).abs().min(1.0).acos().to_degrees()
}

fn direction(maps: &FeatureMaps, t: usize, which: usize) -> DVec3 {
    let d = maps.directions.as_ref().expect("fit directions")[t][which];
    DVec3::new(f64::from(d[0]), f64::from(d[1]), f64::from(d[2]))
}

/// Median angles of the fitted `d1, d2` to the analytic ones over the texels where `truth`
/// (texel centre position -> `(d1, d2, k1, k2)`) has `|k1 - k2| > 0.2 |k1|` and `keep` holds.
fn direction_errors(
    atlas: &Atlas,
    maps: &FeatureMaps,
    truth: impl Fn(DVec3) -> (DVec3, DVec3, f64, f64),
    keep: impl Fn(usize) -> bool,
) -> (f64, f64, usize) {
    let mut errors = (Vec::new(), Vec::new());
    for t in (0..maps.chart.len()).filter(|&t| maps.n_valid[t] > 0 && keep(t)) {
        let Some(centre) = centre_at(atlas, texel_uv(maps, t), Lookup::Triangle) else {
            continue;
        };
        let (d1, d2, k1, k2) = truth(centre.position);
        if (k1 - k2).abs() > 0.2 * k1.abs() {
            errors.0.push(line_angle(direction(maps, t, 0), d1));
            errors.1.push(line_angle(direction(maps, t, 1), d2));
        }
    }
    let n = errors.0.len();
    (median(errors.0), median(errors.1), n)
}

/// Torus of tube centre radius `major` and tube radius `minor` around z: `k1 = 1/minor` along the
/// meridian, `k2 = cos v / (major + minor cos v)` along the parallel (outward normals).
fn torus_truth(major: f64, minor: f64) -> impl Fn(DVec3) -> (DVec3, DVec3, f64, f64) {
    move |p: DVec3| {
        let radial = DVec3::new(p.x, p.y, 0.0).normalize();
        let normal = (p - major * radial).normalize();
        let parallel = DVec3::Z.cross(radial);
        let cos_v = normal.dot(radial);
        (normal.cross(parallel), parallel, 1.0 / minor, cos_v / (major + minor * cos_v))
    }
}

/// Ellipsoid `sum (x_i / a_i)^2 = 1`: the shape operator is the tangential part of
/// `Hess F / |grad F|` with `F = sum (x_i / a_i)^2`; its eigenvectors are the principal directions.
fn ellipsoid_truth(axes: [f64; 3]) -> impl Fn(DVec3) -> (DVec3, DVec3, f64, f64) {
    move |p: DVec3| {
        let hess = DMat3::from_diagonal(DVec3::from(axes.map(|a| 2.0 / (a * a))));
        let grad = hess * p;
        let normal = grad.normalize();
        let (t1, t2) = normal.any_orthonormal_pair();
        let s = |a: DVec3, b: DVec3| a.dot(hess * b) / grad.length();
        let (e, f, g) = (s(t1, t1), s(t1, t2), s(t2, t2));
        let (mean, root) = ((e + g) / 2.0, (((e - g) / 2.0).powi(2) + f * f).sqrt());
        let k1 = mean + root;
        // Eigenvector of [[e, f], [f, g]] for k1.
        let v = if (k1 - e).abs() > (k1 - g).abs() { DVec2::new(f, k1 - e) } else { DVec2::new(k1 - g, f) };
        let d1 = (v.x * t1 + v.y * t2).normalize();
        (d1, normal.cross(d1), k1, mean - root)
    }
}

fn sphere() -> ShapeMesh {
    uv_sphere(1.0, 160, 80)
}

#[test]
fn fit_curvatures_of_the_sphere_and_cylinder_are_as_accurate_as_the_integral_ones() {
    let sphere = atlas(&sphere(), 512);
    let cylinder = atlas(&cylinder(1.0, 4.0, 160, 64), 512);
    for (name, atlas, truth) in
        [("sphere", &sphere, [1.0, 1.0, 1.0, 1.0]), ("cylinder", &cylinder, [0.5, 0.0, 1.0, 0.0])]
    {
        let fit = maps(atlas, 0.2, 96, CurvatureMethod::Fit);
        let integral = maps(atlas, 0.2, 96, CurvatureMethod::Integral);
        for (feature, truth) in CURVATURES.into_iter().zip(truth) {
            let e_fit = median_error(&fit, feature, truth, |_| true);
            let e_int = median_error(&integral, feature, truth, |_| true);
            eprintln!("{name} {feature:?}: fit {e_fit:.4}, integral {e_int:.4}");
            assert!(e_fit < 2e-3, "{name} {feature:?}: fit error {e_fit}");
            assert!(e_fit <= e_int + 1e-3, "{name} {feature:?}: fit {e_fit} vs integral {e_int}");
        }
        let residual = median(fit.fit_residual.as_ref().unwrap().iter().map(|&x| f64::from(x)).collect());
        assert!(residual < 1e-2, "{name} residual {residual}");
    }
}

#[test]
fn fit_directions_of_the_torus_follow_meridians_and_parallels_also_at_the_seams() {
    let (major, minor) = (2.0, 0.5);
    let atlas = atlas(&torus(major, minor, 384, 192), 1024);
    let m = maps(&atlas, 0.15, 192, CurvatureMethod::Fit);
    let truth = torus_truth(major, minor);
    let (e1, e2, n) = direction_errors(&atlas, &m, &truth, |_| true);
    eprintln!("torus: median angle d1 {e1:.3} deg, d2 {e2:.3} deg over {n} texels");
    assert!(n > 1000 && e1 < 2.0 && e2 < 2.0, "d1 {e1}, d2 {e2}");
    // Texels within 3 texels of the chart border: their neighbourhoods cross a seam.
    let w = m.resolution;
    let near_seam = |t: usize| {
        let (i, j) = (t % w, t / w);
        let interior = |k: usize| (3..w - 3).contains(&k) && m.chart[t] >= 0;
        let off = |di: i64, dj: i64| {
            let (a, b) = (i as i64 + di, j as i64 + dj);
            a < 0 || b < 0 || a >= w as i64 || b >= w as i64 || m.chart[b as usize * w + a as usize] < 0
        };
        interior(i) && interior(j) && (off(3, 0) || off(-3, 0) || off(0, 3) || off(0, -3))
    };
    let (s1, s2, ns) = direction_errors(&atlas, &m, &truth, near_seam);
    eprintln!("torus at the seams: d1 {s1:.3} deg, d2 {s2:.3} deg over {ns} texels");
    assert!(ns > 100 && s1 < 2.0 && s2 < 2.0, "seams: d1 {s1}, d2 {s2}");
}

#[test]
fn fit_directions_of_an_ellipsoid_match_the_analytic_ones() {
    let axes = [1.0, 0.7, 0.5];
    let atlas = atlas(&ellipsoid(axes, 192, 96), 1024);
    let m = maps(&atlas, 0.08, 160, CurvatureMethod::Fit);
    let (e1, e2, n) = direction_errors(&atlas, &m, ellipsoid_truth(axes), |_| true);
    eprintln!("ellipsoid: median angle d1 {e1:.3} deg, d2 {e2:.3} deg over {n} texels");
    assert!(n > 1000 && e1 < 2.0 && e2 < 2.0, "d1 {e1}, d2 {e2}");
}

#[test]
fn fit_directions_turn_with_a_rigid_motion() {
    let shape = torus(2.0, 0.5, 192, 96);
    let motion = DQuat::from_euler(glam::EulerRot::ZXY, 0.8, -0.4, 1.9);
    let shift = DVec3::new(3.0, -1.0, 0.5);
    let mut moved = shape.clone();
    for p in &mut moved.positions {
        *p = (motion * DVec3::from(*p) + shift).to_array();
    }
    let (a, b) = (atlas(&shape, 512), atlas(&moved, 512));
    let (ma, mb) = (maps(&a, 0.15, 64, CurvatureMethod::Fit), maps(&b, 0.15, 64, CurvatureMethod::Fit));
    let mut angles = Vec::new();
    for t in (0..ma.chart.len()).filter(|&t| ma.n_valid[t] > 0 && mb.n_valid[t] > 0) {
        for which in 0..2 {
            angles.push(line_angle(motion * direction(&ma, t, which), direction(&mb, t, which)));
        }
    }
    let worst = angles.iter().copied().fold(0.0, f64::max);
    eprintln!("rigid motion: worst direction change {worst:.2e} deg over {} texels", angles.len() / 2);
    assert!(angles.len() > 1000 && median(angles) < 0.01, "worst {worst}");
}

#[test]
fn per_vertex_directions_of_the_torus_match_the_analytic_ones() {
    let (major, minor) = (2.0, 0.5);
    let shape = torus(major, minor, 192, 96);
    let atlas = atlas(&shape, 512);
    let settings = ComputeSettings::new(vec![Feature::MeanCurvature], 0.15);
    let directions = per_vertex_directions(&atlas, &settings).unwrap();
    assert_eq!(directions.len(), shape.positions.len());
    let truth = torus_truth(major, minor);
    let (mut e1, mut e2) = (Vec::new(), Vec::new());
    for (p, d) in shape.positions.iter().zip(&directions) {
        let (d1, d2, _, _) = truth(DVec3::from(*p));
        e1.push(line_angle(DVec3::from(d[0].map(f64::from)), d1));
        e2.push(line_angle(DVec3::from(d[1].map(f64::from)), d2));
    }
    let (e1, e2) = (median(e1), median(e2));
    eprintln!("torus per vertex: d1 {e1:.3} deg, d2 {e2:.3} deg");
    assert!(e1 < 2.0 && e2 < 2.0, "d1 {e1}, d2 {e2}");
}
