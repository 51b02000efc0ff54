//! The shared lattice (`sampling = "shared"`) against its reference, the exact path, with the same
//! seeds. The two sample different points (one lattice per tile against one turned pattern per
//! texel), so they are compared as estimators: both against the analytic truth, where the shared
//! lattice must be as accurate as the exact path or better, and against each other within the
//! exact path's own noise.

use crate::support::{atlas, errors, median, patchwork_sphere, unit_sphere, Truth};
use glam::{DVec2, DVec3, Vec2};
use uvfeat_core::features::Feature;
use uvfeat_core::lookup::Lookup;
use uvfeat_core::output::FeatureMaps;
use uvfeat_core::sampling::{
    centre_at, texel_point, LatticeDomain, LatticeTexel, Reach, SamplingPath, TileLattice, TilePlane,
};
use uvfeat_core::settings::ComputeSettings;
use uvfeat_core::shapes::{ellipsoid, torus, uv_sphere};
use uvfeat_core::Atlas;

const FEATURES: [Feature; 3] = [Feature::MeanCurvature, Feature::GaussianCurvature, Feature::BendingEnergy];

fn settings(radius: f64, path: SamplingPath) -> ComputeSettings {
    let mut settings = ComputeSettings::new(FEATURES.to_vec(), radius);
    settings.resolution = 128;
    settings.sampling = path;
    settings
}

fn maps(atlas: &Atlas, radius: f64, path: SamplingPath) -> FeatureMaps {
    FeatureMaps::compute(atlas, &settings(radius, path)).expect("valid settings")
}

fn torus_2_05(p: DVec3) -> (f64, f64) {
    let (major, minor) = (2.0, 0.5);
    let cos_v = ((p.x.hypot(p.y) - major) / minor).clamp(-1.0, 1.0);
    let ring = major + minor * cos_v;
    ((major + 2.0 * minor * cos_v) / (2.0 * minor * ring), cos_v / (minor * ring))
}

const AXES: [f64; 3] = [1.0, 0.8, 0.6];

fn ellipsoid_axes(p: DVec3) -> (f64, f64) {
    let [a, b, c] = AXES;
    let g = p.x * p.x / a.powi(4) + p.y * p.y / b.powi(4) + p.z * p.z / c.powi(4);
    let abc2 = (a * b * c).powi(2);
    let mean = (a * a + b * b + c * c - p.length_squared()) / (2.0 * abc2 * g.powf(1.5));
    (mean, 1.0 / (abc2 * g * g))
}

fn assert_as_accurate(name: &str, atlas: &Atlas, radius: f64, truth: Truth) -> [f64; 2] {
    let (shared, exact) = (maps(atlas, radius, SamplingPath::Shared), maps(atlas, radius, SamplingPath::Exact));
    assert_eq!(shared.chart, exact.chart);
    let texels: Vec<usize> = (0..shared.chart.len()).filter(|&t| exact.n_valid[t] > 0).collect();
    let empty = texels.iter().filter(|&&t| shared.n_valid[t] == 0).count();
    assert!(empty == 0, "{name}: {empty} texels without samples");
    // Both paths draw N points per disk of the margin, the lattice in the metric of its tile's
    // centre: about the same number lands in the balls (3 % fewer near the poles of a lat-long
    // sphere). Where the coverage check grows a domain, the pattern spreads its N points over it
    // while the lattice keeps its density, so it has more there (17 % more over the sphere).
    let valid = |m: &FeatureMaps| texels.iter().map(|&t| u64::from(m.n_valid[t])).sum::<u64>() as f64;
    let ratio = valid(&shared) / valid(&exact);
    assert!((0.95..1.25).contains(&ratio), "{name}: {ratio} as many samples in the balls");
    let (e_shared, e_exact) = (errors(atlas, &shared, truth), errors(atlas, &exact, truth));
    for (k, feature) in ["H", "K"].iter().enumerate() {
        assert!(
            e_shared[k] <= 1.1 * e_exact[k] + 2e-3,
            "{name} {feature}: shared {:.4} against exact {:.4} (median relative error)",
            e_shared[k],
            e_exact[k]
        );
    }
    // Bending energy has no closed form here: the two estimates agree within the exact one's noise.
    let scale = median(texels.iter().map(|&t| f64::from(exact.values[2][t]).abs()).collect());
    let difference =
        median(texels.iter().map(|&t| f64::from((shared.values[2][t] - exact.values[2][t]).abs())).collect());
    assert!(difference < 0.03 * scale, "{name} bending energy: median difference {difference} of {scale}");
    e_shared
}

#[test]
fn the_shared_lattice_is_as_accurate_as_the_exact_path_on_analytic_shapes() {
    let sphere = assert_as_accurate("sphere", &atlas(&uv_sphere(1.0, 96, 48), 512), 0.3, unit_sphere);
    assert!(sphere[0] < 5e-3 && sphere[1] < 2e-2, "sphere: median |H - 1| {}, |K - 1| {}", sphere[0], sphere[1]);
    assert_as_accurate("torus", &atlas(&torus(2.0, 0.5, 96, 48), 512), 0.25, torus_2_05);
    assert_as_accurate("ellipsoid", &atlas(&ellipsoid(AXES, 96, 48), 512), 0.2, ellipsoid_axes);
}

#[test]
fn the_shared_lattice_is_as_accurate_as_the_exact_path_across_many_charts() {
    let atlas = atlas(&patchwork_sphere(6), 512);
    assert!(atlas.topology.n_charts >= 36, "{} charts", atlas.topology.n_charts);
    let [h, k] = assert_as_accurate("patchwork sphere", &atlas, 0.3, unit_sphere);
    assert!(h < 5e-3 && k < 2e-2, "patchwork sphere: median |H - 1| {h}, |K - 1| {k}");
    // Balls past their disks at their groups' centres (the groups after them probe first), and
    // texels at the poles, where half the walks from the centre go round the fan of slits until
    // they run out of seam jumps.
    let [h, k] = assert_as_accurate("patchwork sphere, large balls", &atlas, 0.8, unit_sphere);
    assert!(h < 1e-3 && k < 1e-3, "patchwork sphere at r = 0.8: median |H - 1| {h}, |K - 1| {k}");
}

#[test]
fn the_shared_lattice_gives_the_same_maps_on_any_number_of_threads() {
    let atlas = atlas(&torus(2.0, 0.5, 96, 48), 512);
    // At r = 1 the balls wrap round the tube: a group after one whose centre's ball reached past
    // its disk probes first (`evaluation/tile.rs`), in its tile's order, whichever thread runs it.
    for radius in [0.25, 1.0] {
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool");
            pool.install(|| maps(&atlas, radius, SamplingPath::Shared))
        };
        let (one, three) = (on(1), on(3));
        for (feature, (a, b)) in FEATURES.iter().zip(one.values.iter().zip(&three.values)) {
            let same = a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
            assert!(same, "{feature:?} differs between 1 and 3 threads at r = {radius}");
        }
        assert_eq!(one.n_valid, three.n_valid);
    }
}

#[test]
fn the_seed_shifts_the_lattice() {
    let atlas = atlas(&uv_sphere(1.0, 96, 48), 512);
    let first = maps(&atlas, 0.3, SamplingPath::Shared);
    let mut other = settings(0.3, SamplingPath::Shared);
    other.seed = 7;
    let second = FeatureMaps::compute(&atlas, &other).expect("valid settings");
    let changed = first.values[0].iter().zip(&second.values[0]).filter(|(a, b)| a.is_finite() && a != b).count();
    assert!(changed > first.summary.texels / 2, "only {changed} texels changed with the seed");
    assert!(errors(&atlas, &second, unit_sphere)[0] < 5e-3);
}

#[test]
fn settings_the_lattice_does_not_serve_take_the_per_texel_fast_path() {
    let atlas = atlas(&torus(2.0, 0.5, 64, 32), 256);
    for change in [|s: &mut ComputeSettings| s.adaptive = true, |s: &mut ComputeSettings| s.standard_errors = true] {
        let (mut shared, mut fast) = (settings(0.25, SamplingPath::Shared), settings(0.25, SamplingPath::Fast));
        shared.resolution = 48;
        fast.resolution = 48;
        change(&mut shared);
        change(&mut fast);
        let (a, b) = (FeatureMaps::compute(&atlas, &shared).unwrap(), FeatureMaps::compute(&atlas, &fast).unwrap());
        assert!(a.values[0].iter().zip(&b.values[0]).all(|(x, y)| x.to_bits() == y.to_bits()));
    }
}

#[test]
fn a_lattice_holds_n_points_per_domain_and_a_texel_reads_one_run_of_them() {
    let atlas = atlas(&uvfeat_core::shapes::plane(1.0, 64), 512);
    let centre = centre_at(&atlas, DVec2::new(0.5, 0.5), Lookup::Triangle).expect("a centre");
    let build = |radius: f64| {
        let sampler = settings(radius, SamplingPath::Shared).sampler();
        let plane = TilePlane::new(centre, &sampler);
        let places: Vec<Vec2> = [DVec2::ZERO, DVec2::new(0.03, 0.01)].map(|uv| plane.place(centre.uv + uv)).to_vec();
        (TileLattice::build(&atlas, &plane, &places, LatticeDomain::Disks(1.25), 256, 0, &sampler), places)
    };
    // Texels 30 balls apart: one lattice over both would hold far more points than their patterns.
    assert!(build(0.001).0.is_none());
    let (lattice, places) = build(0.05);
    let lattice = lattice.expect("a lattice");
    assert!(lattice.lost.is_empty());
    let columns = lattice.w.clone();
    let point = |k: usize| Vec2::new(columns[0][k], columns[1][k]);
    for place in places {
        let inside = (0..lattice.len()).filter(|&k| point(k).distance(place) < 1.25).count();
        assert!((246..=266).contains(&inside), "{inside} points in a domain of 256");
        // The run holds every point of the domain, and the padding after the last point is inert.
        let texel = LatticeTexel { place, position: glam::Vec3::ZERO, normal: glam::Vec3::Z };
        let run = lattice.run(&texel, 0.0);
        assert!((0..lattice.len()).filter(|&k| point(k).distance(place) < 1.25).all(|k| run.contains(&k)));
        assert!(run.end <= lattice.len() + TileLattice::PADDING);
    }
    let padding = lattice.len()..lattice.len() + TileLattice::PADDING;
    assert!(padding.clone().all(|k| lattice.area[k] == 0.0 && !point(k).is_finite()));
    // Each point stands for its cell of the plane: the areas add up to the lattice's extent.
    let area: f64 = lattice.area.iter().map(|&a| f64::from(a)).sum();
    let cell = f64::from(lattice.spacing).powi(2) * (0.05f64).powi(2);
    assert!((area / (lattice.len() as f64 * cell) - 1.0).abs() < 1e-3, "{area} for {} cells", lattice.len());
}

#[test]
fn a_texel_of_a_grown_domain_reads_a_run_holding_every_point_of_its_ball() {
    let atlas = atlas(&uvfeat_core::shapes::plane(1.0, 64), 512);
    let sampler = settings(0.05, SamplingPath::Shared).sampler();
    let centre = centre_at(&atlas, DVec2::new(0.5, 0.5), Lookup::Triangle).expect("a centre");
    let plane = TilePlane::new(centre, &sampler);
    let texels: Vec<LatticeTexel> = [DVec2::ZERO, DVec2::new(0.03, 0.01), DVec2::new(-0.02, 0.04)]
        .map(|offset| {
            let point = texel_point(&atlas, centre.uv + offset).expect("a texel point");
            LatticeTexel { place: plane.place(point.uv), position: point.position, normal: point.normal }
        })
        .to_vec();
    let places: Vec<Vec2> = texels.iter().map(|t| t.place).collect();
    let domain = LatticeDomain::Grown(Reach::uniform(1.5));
    let lattice = TileLattice::build(&atlas, &plane, &places, domain, 256, 0, &sampler).expect("a lattice");
    let ball = 0.05f32;
    for texel in &texels {
        let q = |k: usize| glam::Vec3::new(lattice.q[0][k], lattice.q[1][k], lattice.q[2][k]);
        let in_ball: Vec<usize> = (0..lattice.len()).filter(|&k| q(k).distance(texel.position) < ball).collect();
        let run = lattice.run(texel, ball);
        assert!(in_ball.len() > 100 && in_ball.iter().all(|k| run.contains(k)), "{} points in the ball", in_ball.len());
        assert!(run.len() < lattice.len(), "the run is a slab of the domain, not all {} points", lattice.len());
    }
}

#[test]
fn neighbourhoods_cut_by_a_mesh_border_are_flagged_as_on_the_exact_path() {
    // An open cylinder: rings of texels near its two border loops lose part of their balls.
    let atlas = atlas(&uvfeat_core::shapes::cylinder(0.5, 2.0, 96, 48), 512);
    let (shared, exact) = (maps(&atlas, 0.3, SamplingPath::Shared), maps(&atlas, 0.3, SamplingPath::Exact));
    let truncated = |m: &FeatureMaps| -> Vec<bool> { m.n_border.iter().map(|&n| n > 0).collect() };
    let (a, b) = (truncated(&shared), truncated(&exact));
    let both = a.iter().zip(&b).filter(|(x, y)| **x && **y).count();
    let either = a.iter().zip(&b).filter(|(x, y)| **x || **y).count();
    assert!(either > 500 && both as f64 >= 0.9 * either as f64, "{both} of {either} truncated texels agree");
    // Away from the borders H = 1 / (2 * 0.5) = 1 and K = 0: the shared lattice errs no more than
    // the exact path (both carry the estimators' bias at r = 0.6 times the cylinder's radius).
    let inner: Vec<usize> = (0..a.len()).filter(|&t| !a[t] && !b[t] && exact.n_valid[t] > 0).collect();
    let error = |m: &FeatureMaps, k: usize, truth: f64| {
        median(inner.iter().map(|&t| (f64::from(m.values[k][t]) - truth).abs()).collect())
    };
    for (k, truth) in [(0, 1.0), (1, 0.0)] {
        let (e_shared, e_exact) = (error(&shared, k, truth), error(&exact, k, truth));
        assert!(e_shared <= 1.1 * e_exact + 1e-3 && e_shared < 0.05, "{:?}: {e_shared} against {e_exact}", FEATURES[k]);
    }
}

#[test]
fn balls_smaller_than_the_texel_spacing_take_the_per_texel_path() {
    // 128² texels over a torus 12.6 long: texels 0.1 apart, balls of radius 0.004.
    let atlas = atlas(&torus(2.0, 0.5, 96, 48), 512);
    let (shared, fast) = (maps(&atlas, 0.004, SamplingPath::Shared), maps(&atlas, 0.004, SamplingPath::Fast));
    assert!(shared.summary.texels > 10_000);
    assert!(shared.values[0].iter().zip(&fast.values[0]).all(|(a, b)| a.to_bits() == b.to_bits()));
}
