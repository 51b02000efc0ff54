//! DESIGN.md §1.3.3: per-texel distortion equals the first fundamental form of the parameterisation.

use crate::support::atlas;
use glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};
use uvfeat_core::shapes::{plane, torus, uv_sphere};
use uvfeat_core::Atlas;

/// Chart scale of the analytic shapes: UV = margin + scale * parameter.
const MARGIN: f64 = 0.02;
const SCALE: f64 = 1.0 - 2.0 * MARGIN;

#[test]
fn affine_plane_distortion_is_exact_including_the_angle() {
    let mut shape = plane(1.0, 8);
    // P(u, v) = A (u, v): a sheared, rotated, anisotropic map with known singular values.
    let a = [DVec3::new(3.0, 1.0, 0.5), DVec3::new(-0.5, 2.0, 1.0)];
    for (p, uv) in shape.positions.iter_mut().zip(&shape.uvs) {
        *p = (a[0] * uv[0] + a[1] * uv[1]).to_array();
    }
    let atlas = atlas(&shape, 256);
    let (e, f, g) = (a[0].dot(a[0]), a[0].dot(a[1]), a[1].dot(a[1]));
    let root = (((e - g) / 2.0).powi(2) + f * f).sqrt();
    let (s1, s2) = (((e + g) / 2.0 + root).sqrt(), ((e + g) / 2.0 - root).sqrt());
    let theta = 0.5 * (2.0 * f).atan2(e - g);
    let mut checked = 0;
    for t in 0..atlas.coverage().chart.len() {
        if atlas.coverage().chart[t] < 0 {
            continue;
        }
        let [x1, x2] = atlas.buffers().sigma[t].map(f64::from);
        assert!((x1 - s1).abs() < 1e-6 * s1 && (x2 - s2).abs() < 1e-6 * s1, "sigma {x1} {x2} vs {s1} {s2}");
        assert!((f64::from(atlas.buffers().theta[t]) - theta).abs() < 1e-6);
        // The eigenvector of sigma_1 is the direction of largest stretch.
        let axis = DVec2::from_angle(theta);
        assert!(((a[0] * axis.x + a[1] * axis.y).length() - s1).abs() < 1e-9);
        checked += 1;
    }
    assert!(checked > 10_000);
}

/// Relative errors of `E + G` and `sqrt(EG - F^2)` against `analytic(u, v) -> (E, G)` (F = 0), per
/// face. The piecewise-linear metric is second-order accurate on the edges of the grid, so the
/// analytic form is taken at the centroid's u and at the v of the face's u-parallel edge.
fn worst_metric_errors(atlas: &Atlas, analytic: impl Fn(f64, f64) -> (f64, f64)) -> (f64, f64) {
    let mut worst = (0.0f64, 0.0f64);
    for (face, uv) in atlas.topology.walk_faces.iter().map(|w| w.corners).enumerate() {
        let Some(jac) = atlas.frame.face_map(&atlas.topology, face as u32).map(|m| m.jacobian) else {
            continue;
        };
        let Some(k) = (0..3).find(|&k| uv[k].y == uv[(k + 1) % 3].y) else {
            continue;
        };
        let u = (uv[0].x + uv[1].x + uv[2].x) / 3.0;
        let (e, g) = analytic((u - MARGIN) / SCALE, (uv[k].y - MARGIN) / SCALE);
        let [te, tf, tg] = jac.metric();
        let d = atlas.frame.distortion[face];
        assert!((d.sigma1.powi(2) + d.sigma2.powi(2) - (te + tg)).abs() < 1e-9 * (te + tg));
        let trace = ((te + tg) - (e + g)).abs() / (e + g);
        let area = ((te * tg - tf * tf).sqrt() - (e * g).sqrt()).abs() / (e * g).sqrt();
        worst = (worst.0.max(trace), worst.1.max(area));
    }
    worst
}

#[test]
fn lat_long_sphere_metric_matches_the_analytic_form() {
    let radius = 1.5;
    let atlas = atlas(&uv_sphere(radius, 256, 128), 512);
    let (trace, area) = worst_metric_errors(&atlas, |_, v| {
        let lat = PI * (v - 0.5);
        ((TAU * radius * lat.cos() / SCALE).powi(2), (PI * radius / SCALE).powi(2))
    });
    assert!(trace < 1e-3 && area < 1e-3, "relative errors: E+G {trace:.2e}, sqrt(EG-F^2) {area:.2e}");
}

#[test]
fn torus_metric_matches_the_analytic_form() {
    let (major, minor) = (2.0, 0.5);
    let atlas = atlas(&torus(major, minor, 256, 128), 512);
    let (trace, area) = worst_metric_errors(&atlas, |_, v| {
        let ring = major + minor * (TAU * v).cos();
        ((TAU * ring / SCALE).powi(2), (TAU * minor / SCALE).powi(2))
    });
    assert!(trace < 1e-3 && area < 1e-3, "relative errors: E+G {trace:.2e}, sqrt(EG-F^2) {area:.2e}");
}

#[test]
fn sphere_stretch_axis_follows_the_parallels_below_sixty_degrees() {
    // E > G (theta = 0) where cos(lat) > 1/2, E < G (theta = pi/2) nearer the poles.
    let atlas = atlas(&uv_sphere(1.0, 256, 128), 512);
    for (t, &chart) in atlas.coverage().chart.iter().enumerate() {
        if chart < 0 || atlas.coverage().border_side[t] >= 0 {
            continue;
        }
        let lat = PI * ((atlas.texel_centre(t).y - MARGIN) / SCALE - 0.5);
        let theta = f64::from(atlas.buffers().theta[t]).abs();
        if lat.cos() > 0.6 {
            assert!(theta < 0.05, "lat {lat}: theta {theta}");
        } else if lat.cos() < 0.4 {
            assert!((theta - PI / 2.0).abs() < 0.05, "lat {lat}: theta {theta}");
        }
    }
}
