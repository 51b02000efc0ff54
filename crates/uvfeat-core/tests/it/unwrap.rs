//! The automatic atlas (stage 0): charts that are injective, within their cone and packed apart,
//! and features on them as accurate as on the analytic shapes' own atlases.

use crate::support::{atlas, errors, unit_sphere};
use glam::{DVec2, DVec3};
use uvfeat_core::features::Feature;
use uvfeat_core::output::FeatureMaps;
use uvfeat_core::settings::ComputeSettings;
use uvfeat_core::shapes::{torus, uv_sphere, ShapeMesh};
use uvfeat_core::unwrap::{unwrap, UnwrapOptions};
use uvfeat_core::UvfeatError;

fn unwrapped(shape: &ShapeMesh, options: &UnwrapOptions) -> (ShapeMesh, usize) {
    let result = unwrap(&shape.positions, &shape.faces, options).expect("unwrap");
    let mesh = ShapeMesh {
        positions: shape.positions.clone(),
        faces: shape.faces.clone(),
        uvs: result.uv_rows(),
        uv_faces: result.uv_face_rows(),
    };
    (mesh, result.n_charts)
}

/// A helicoid strip of `turns` turns around z, rising `pitch` per radian: its normals stay within
/// a few degrees of z, so one cone holds it all, but its projection covers itself once per turn.
fn spiral_ramp(turns: f64, pitch: f64) -> ShapeMesh {
    let (n_t, n_s) = ((turns * 64.0) as usize, 8);
    let mut shape = ShapeMesh::default();
    for i in 0..=n_t {
        let t = turns * std::f64::consts::TAU * i as f64 / n_t as f64;
        for j in 0..=n_s {
            let s = 1.0 + j as f64 / n_s as f64;
            shape.positions.push([s * t.cos(), s * t.sin(), pitch * t]);
        }
    }
    let at = |i: usize, j: usize| (i * (n_s + 1) + j) as i64;
    for i in 0..n_t {
        for j in 0..n_s {
            shape.faces.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
            shape.faces.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
        }
    }
    shape
}

fn corners(shape: &ShapeMesh, f: usize) -> ([DVec3; 3], [DVec2; 3]) {
    (
        shape.faces[f].map(|v| DVec3::from_array(shape.positions[v as usize])),
        shape.uv_faces[f].map(|k| DVec2::from_array(shape.uvs[k as usize])),
    )
}

#[test]
fn charts_are_injective_within_their_cone_and_share_one_scale() {
    let options = UnwrapOptions::default();
    let (mesh, n_charts) = unwrapped(&torus(2.0, 0.5, 96, 48), &options);
    assert!((4..=64).contains(&n_charts), "{n_charts} charts on a torus");
    let atlas = atlas(&mesh, 1024);
    assert_eq!(atlas.topology.n_charts, n_charts, "a chart the unwrap made is not one connected UV chart");
    let diagnostics = &atlas.topology.diagnostics;
    assert_eq!((diagnostics.mirrored_uv_faces, diagnostics.degenerate_uv_faces), (0, 0));
    assert_eq!(atlas.coverage().diagnostics.overlapping_texels, 0);
    // Orthographic projection: UV area / surface area is the shared scale squared times the cosine
    // between the face and its chart's axis. The cone test reads smoothed normals (45°, 75° for a
    // notch), so a face's own normal may lean a little further, but never past 85°.
    let ratios: Vec<f64> = (0..mesh.faces.len())
        .map(|f| {
            let (p, uv) = corners(&mesh, f);
            (uv[1] - uv[0]).perp_dot(uv[2] - uv[0]) / (p[1] - p[0]).cross(p[2] - p[0]).length()
        })
        .collect();
    let largest = ratios.iter().cloned().fold(0.0, f64::max);
    let share_over = |angle: f64| {
        ratios.iter().filter(|&&r| r >= largest * angle.to_radians().cos() - 1e-12).count() as f64 / ratios.len() as f64
    };
    assert_eq!(share_over(85.0), 1.0, "a face tilts more than any face may");
    assert!(share_over(75.0) > 0.99, "{:.3} of the faces within the notches' cone", share_over(75.0));
    assert!(share_over(45.0) > 0.9, "{:.3} of the faces within the cone", share_over(45.0));
    assert!(share_over(20.0) < 0.9, "every face lies flat in its chart: the cone test is not at work");
    let again = unwrap(&mesh.positions, &mesh.faces, &options).expect("unwrap");
    assert_eq!(again.uv_rows(), mesh.uvs, "the unwrap is not deterministic");
}

#[test]
fn a_spiral_ramp_is_cut_where_it_would_cover_itself() {
    let ramp = spiral_ramp(3.0, 0.05);
    let (mesh, n_charts) = unwrapped(&ramp, &UnwrapOptions::default());
    assert!(n_charts >= 3, "three turns in {n_charts} charts");
    let atlas = atlas(&mesh, 512);
    assert_eq!(atlas.coverage().diagnostics.overlapping_texels, 0);
    assert_eq!(atlas.topology.diagnostics.mirrored_uv_faces, 0);
}

#[test]
fn features_on_the_automatic_atlas_match_the_truth() {
    let (mesh, _) = unwrapped(&uv_sphere(1.0, 96, 48), &UnwrapOptions::default());
    let atlas = atlas(&mesh, 512);
    let mut settings = ComputeSettings::new(vec![Feature::MeanCurvature, Feature::GaussianCurvature], 0.3);
    settings.resolution = 128;
    let maps = FeatureMaps::compute(&atlas, &settings).expect("valid settings");
    let [h, k] = errors(&atlas, &maps, unit_sphere);
    // The lat-long sphere's own atlas gives about 1e-3 and 1e-2 (tests/it/shared_lattice.rs).
    assert!(h < 5e-3 && k < 2e-2, "median |H - 1| {h}, |K - 1| {k}");
}

#[test]
fn split_vertices_are_welded_before_charting() {
    let sphere = uv_sphere(1.0, 32, 16);
    let mut split = ShapeMesh::default();
    for face in &sphere.faces {
        let base = split.positions.len() as i64;
        split.positions.extend(face.map(|v| sphere.positions[v as usize]));
        split.faces.push([base, base + 1, base + 2]);
    }
    let options = UnwrapOptions::default();
    let (welded, split_charts) = (
        unwrap(&sphere.positions, &sphere.faces, &options).unwrap(),
        unwrap(&split.positions, &split.faces, &options).unwrap(),
    );
    assert_eq!(split_charts.n_charts, welded.n_charts);
    assert!(welded.n_charts < 20, "{} charts on a sphere", welded.n_charts);
}

#[test]
fn bad_options_and_meshes_name_the_problem() {
    let sphere = uv_sphere(1.0, 16, 8);
    let with = |change: fn(&mut UnwrapOptions)| {
        let mut options = UnwrapOptions::default();
        change(&mut options);
        unwrap(&sphere.positions, &sphere.faces, &options).unwrap_err()
    };
    for angle in [0.0, 90.0, f64::NAN] {
        let options = UnwrapOptions { max_angle_degrees: angle, ..UnwrapOptions::default() };
        let error = unwrap(&sphere.positions, &sphere.faces, &options).unwrap_err();
        assert!(matches!(error, UvfeatError::InvalidParameter { name: "max_angle", .. }), "{angle}: {error}");
    }
    assert!(matches!(with(|o| o.padding = -1.0), UvfeatError::InvalidParameter { name: "padding", .. }));
    assert!(matches!(with(|o| o.resolution = 0), UvfeatError::InvalidResolution { .. }));
    let crowded = with(|o| {
        o.resolution = 8;
        o.max_angle_degrees = 1.0;
    });
    assert!(matches!(&crowded, UvfeatError::InvalidParameter { name: "resolution", .. }), "{crowded}");
    assert!(crowded.to_string().contains("do not fit"), "{crowded}");

    let mut broken = sphere.clone();
    broken.positions[3][1] = f64::NAN;
    let options = UnwrapOptions::default();
    assert!(matches!(
        unwrap(&broken.positions, &broken.faces, &options),
        Err(UvfeatError::NonFinitePosition { index: 3, .. })
    ));
    broken = sphere.clone();
    broken.faces[5][2] = 10_000;
    assert!(matches!(
        unwrap(&broken.positions, &broken.faces, &options),
        Err(UvfeatError::IndexOutOfRange { face: 5, .. })
    ));
    assert!(matches!(unwrap(&[], &[], &options), Err(UvfeatError::EmptyMesh { .. })));
}

#[test]
fn huge_coordinates_and_faces_without_area_still_unwrap() {
    let sphere = uv_sphere(1.0, 16, 8);
    let huge: Vec<[f64; 3]> = sphere.positions.iter().map(|p| p.map(|c| c * 1e300)).collect();
    let options = UnwrapOptions::default();
    let (small, large) =
        (unwrap(&sphere.positions, &sphere.faces, &options).unwrap(), unwrap(&huge, &sphere.faces, &options).unwrap());
    assert_eq!(small.n_charts, large.n_charts);
    assert!(large.uvs.iter().all(|uv| uv.is_finite() && uv.min_element() >= 0.0 && uv.max_element() <= 1.0));
    // Every face collapsed to a point or a segment: nothing to chart but nothing to fail on either.
    let flat: Vec<[f64; 3]> = sphere.positions.iter().map(|p| [p[0], 0.0, 0.0]).collect();
    let collapsed = unwrap(&flat, &sphere.faces, &options).unwrap();
    assert!(collapsed.uvs.iter().all(|uv| uv.is_finite()));
}

#[test]
fn a_large_face_among_small_ones_and_collapsed_faces_stay_cheap() {
    // A fine grid with a large plate beside it, touching nothing: the plate spans about 10^8 cells
    // of the overlap guard's grid (mean edge length), which it must not fill.
    let mut shape = torus(2.0, 0.5, 96, 48);
    let base = shape.positions.len() as i64;
    shape.positions.extend([[10.0, 10.0, 0.0], [1010.0, 10.0, 0.0], [10.0, 1010.0, 0.0]]);
    shape.faces.push([base, base + 1, base + 2]);
    // Faces whose corners weld together: one inside the torus's grid, one on its own.
    shape.faces.push([0, 0, 1]);
    shape.positions.push([0.0, 0.0, 9.0]);
    let lonely = shape.positions.len() as i64 - 1;
    shape.faces.push([lonely, lonely, lonely]);
    let started = std::time::Instant::now();
    let plain =
        unwrap(&torus(2.0, 0.5, 96, 48).positions, &torus(2.0, 0.5, 96, 48).faces, &UnwrapOptions::default()).unwrap();
    let result = unwrap(&shape.positions, &shape.faces, &UnwrapOptions::default()).unwrap();
    assert!(started.elapsed().as_secs_f64() < 5.0, "took {:?}", started.elapsed());
    // The plate is one chart more; the collapsed faces take their vertices' UVs (the lonely one a
    // point of its own), and do not cut the torus's charts.
    assert_eq!(result.n_charts, plain.n_charts + 2);
    let f = shape.faces.len() - 2;
    assert_eq!(result.uv_faces[f][0], result.uv_faces[f][1]);
}

#[test]
fn thousands_of_slivers_still_pack() {
    // Separate sliver triangles (aspect 1000): each is a chart that the packing enlarges, which
    // must not stop the atlas's scale from shrinking until they fit.
    let mut shape = ShapeMesh::default();
    for k in 0..3000 {
        let (x, y) = ((k % 60) as f64, (k / 60) as f64);
        let base = shape.positions.len() as i64;
        shape.positions.extend([[x, y, 0.0], [x + 1.0, y, 0.0], [x + 0.5, y + 0.001, 0.0]]);
        shape.faces.push([base, base + 1, base + 2]);
    }
    let result = unwrap(&shape.positions, &shape.faces, &UnwrapOptions::default()).expect("the slivers pack");
    assert_eq!(result.n_charts, 3000);
    assert!(result.uvs.iter().all(|uv| uv.min_element() >= 0.0 && uv.max_element() <= 1.0));
}

#[test]
fn noise_at_the_scale_of_the_faces_does_not_cut_a_chart_at_every_face() {
    const AMPLITUDE: f64 = 0.05;
    // A torus whose vertices move along their normals by up to one edge length of the tube,
    // pseudo-randomly (as a scan's noise): the face normals scatter by tens of degrees and the
    // projections of the faces fold; the smoothed normals the cone test reads, and the smoothed
    // surface the rough parts are projected from, do not.
    let mut shape = torus(2.0, 0.5, 128, 64);
    for (k, p) in shape.positions.iter_mut().enumerate() {
        let hash = (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40;
        let offset = AMPLITUDE * (2.0 * hash as f64 / (1u64 << 24) as f64 - 1.0);
        let point = DVec3::from_array(*p);
        let ring = DVec3::new(point.x, point.y, 0.0).normalize() * 2.0;
        *p = (point + (point - ring).normalize() * offset).to_array();
    }
    let (mesh, n_charts) = unwrapped(&shape, &UnwrapOptions::default());
    // Measured: 43 charts; 213 when every face was projected from the surface itself.
    assert!(n_charts < 80, "{n_charts} charts for {} faces", mesh.faces.len());
    let atlas = atlas(&mesh, 1024);
    assert_eq!(atlas.coverage().diagnostics.overlapping_texels, 0);
    assert_eq!(atlas.topology.diagnostics.mirrored_uv_faces, 0);
}
