//! The sampler's fast path against its reference, the exact path, with the same seeds: the same
//! samples reach the same faces, so the maps agree up to f32 rounding (which can move a sample
//! lying on the sphere of radius r in or out of the ball: one sample in ~160 changes a texel's H
//! by up to ~2 %, so a few texels in 10^4 differ by that much).

use crate::support::{atlas, median, patchwork_sphere};
use uvfeat_core::features::Feature;
use uvfeat_core::output::FeatureMaps;
use uvfeat_core::sampling::SamplingPath;
use uvfeat_core::settings::ComputeSettings;
use uvfeat_core::shapes::{torus, uv_sphere};
use uvfeat_core::Atlas;

const FEATURES: [Feature; 4] =
    [Feature::MeanCurvature, Feature::GaussianCurvature, Feature::BendingEnergy, Feature::K1];

fn maps(atlas: &Atlas, radius: f64, path: SamplingPath) -> FeatureMaps {
    let mut settings = ComputeSettings::new(FEATURES.to_vec(), radius);
    settings.resolution = 128;
    settings.sampling = path;
    FeatureMaps::compute(atlas, &settings).expect("valid settings")
}

/// Fast and exact maps of every feature agree texel by texel up to the rim flips.
fn assert_paths_agree(name: &str, atlas: &Atlas, radius: f64) {
    let (fast, exact) = (maps(atlas, radius, SamplingPath::Fast), maps(atlas, radius, SamplingPath::Exact));
    assert_eq!(fast.chart, exact.chart);
    let texels: Vec<usize> = (0..fast.chart.len()).filter(|&t| exact.n_valid[t] > 0).collect();
    let valid = |m: &FeatureMaps| texels.iter().map(|&t| u64::from(m.n_valid[t])).sum::<u64>();
    let (v_fast, v_exact) = (valid(&fast), valid(&exact));
    assert!(v_fast.abs_diff(v_exact) * 10_000 <= v_exact, "{name}: {v_fast} vs {v_exact} samples");
    for (k, feature) in FEATURES.iter().enumerate() {
        let scale = median(texels.iter().map(|&t| f64::from(exact.values[k][t]).abs()).collect());
        let diffs: Vec<f64> =
            texels.iter().map(|&t| f64::from((fast.values[k][t] - exact.values[k][t]).abs()) / scale).collect();
        let close = diffs.iter().filter(|&&d| d <= 1e-4).count() as f64 / diffs.len() as f64;
        let worst = diffs.iter().cloned().fold(0.0, f64::max);
        assert!(close >= 0.99, "{name} {feature:?}: only {:.2} % of texels agree to 1e-4", 100.0 * close);
        assert!(worst < 0.1, "{name} {feature:?}: a texel differs by {worst} of the median");
    }
}

#[test]
fn the_fast_path_matches_the_exact_path_on_single_chart_shapes() {
    assert_paths_agree("sphere", &atlas(&uv_sphere(1.0, 96, 48), 512), 0.3);
    assert_paths_agree("torus", &atlas(&torus(2.0, 0.5, 96, 48), 512), 0.25);
}

#[test]
fn the_fast_path_matches_the_exact_path_across_many_charts() {
    let atlas = atlas(&patchwork_sphere(6), 512);
    assert!(atlas.topology.n_charts >= 36, "{} charts", atlas.topology.n_charts);
    assert_paths_agree("patchwork sphere", &atlas, 0.3);
    // And it is right: H = K = 1 on the unit sphere, across the charts' seams.
    let fast = maps(&atlas, 0.3, SamplingPath::Fast);
    let texels = (0..fast.chart.len()).filter(|&t| fast.n_valid[t] > 0);
    let h_error = median(texels.clone().map(|t| (f64::from(fast.values[0][t]) - 1.0).abs()).collect());
    let k_error = median(texels.map(|t| (f64::from(fast.values[1][t]) - 1.0).abs()).collect());
    assert!(h_error < 5e-3 && k_error < 2e-2, "median |H - 1| {h_error}, |K - 1| {k_error}");
}
