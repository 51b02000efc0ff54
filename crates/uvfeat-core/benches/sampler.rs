//! Sampler benchmark (issue 12): feature maps of the default configuration on the 102,400-face
//! lat-long torus, fast path against the exact path, with CPU time per sample.
//!
//!     cargo bench -p uvfeat-core --bench sampler [-- --radius 4 --samples 256]

use std::sync::Arc;
use std::time::Instant;
use uvfeat_core::features::Feature;
use uvfeat_core::mesh::{Topology, TriangleMesh};
use uvfeat_core::output::{ComputeSettings, FeatureMaps};
use uvfeat_core::sampling::SamplingPath;
use uvfeat_core::{Atlas, AtlasOptions};

/// CPU seconds of this process (user + system) from /proc, or NaN where it is not available.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else { return f64::NAN };
    let fields: Vec<&str> = stat.rsplit(')').next().unwrap_or("").split_whitespace().collect();
    let ticks = |k: usize| fields.get(k).and_then(|x| x.parse::<f64>().ok()).unwrap_or(f64::NAN);
    (ticks(11) + ticks(12)) / 100.0
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str, default: f64| {
        args.iter()
            .position(|a| a == name)
            .and_then(|k| args.get(k + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let radius_percent = value("--radius", 4.0);
    let samples = value("--samples", 256.0) as usize;
    let exact = !args.iter().any(|a| a == "--fast-only");
    let torus = uvfeat_core::shapes::torus(2.0, 0.5, 320, 160);
    let mesh = TriangleMesh::new(&torus.positions, &torus.faces, &torus.uvs, &torus.uv_faces).unwrap();
    let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
    let atlas = Atlas::new(topology, &mesh.positions, &AtlasOptions::default()).unwrap();
    let (low, high) = mesh
        .positions
        .iter()
        .fold((glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
    let radius = radius_percent / 100.0 * (high - low).length();
    let mut settings = ComputeSettings::new(vec![Feature::MeanCurvature, Feature::GaussianCurvature], radius);
    settings.samples = samples;
    settings.grow_margin = !args.iter().any(|a| a == "--no-grow");
    let threads = rayon::current_num_threads();
    println!("lat-long torus, {} faces, 1024² buffers, 512² texels x {samples} samples, r = {radius_percent} %, {threads} threads", mesh.faces.len());
    let mut results = Vec::new();
    for path in [SamplingPath::Fast, SamplingPath::Exact].into_iter().filter(|p| exact || *p == SamplingPath::Fast) {
        settings.sampling = path;
        let (wall, cpu) = (Instant::now(), cpu_seconds());
        let maps = FeatureMaps::compute(&atlas, &settings).unwrap();
        let (wall, cpu) = (wall.elapsed().as_secs_f64(), cpu_seconds() - cpu);
        let drawn = maps.summary.texels as f64 * samples as f64;
        println!(
            "{path:?}: wall {:.0} ms, cpu {:.0} ms, {:.1} ns cpu per sample, {} texels, {:.1} valid/texel",
            1e3 * wall,
            1e3 * cpu,
            1e9 * cpu / drawn,
            maps.summary.texels,
            maps.summary.mean_valid
        );
        results.push(maps);
    }
    if results.len() == 2 {
        let (a, b) = (&results[0].values[0], &results[1].values[0]);
        let diffs: Vec<f64> = a
            .iter()
            .zip(b)
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .map(|(x, y)| f64::from((x - y).abs()))
            .collect();
        let max = diffs.iter().cloned().fold(0.0, f64::max);
        println!("H fast vs exact: max |diff| {max:.3e}, mean {:.3e}", diffs.iter().sum::<f64>() / diffs.len() as f64);
        let worst = (0..a.len())
            .filter(|&t| a[t].is_finite() && b[t].is_finite())
            .max_by(|&s, &t| (a[s] - b[s]).abs().total_cmp(&(a[t] - b[t]).abs()))
            .unwrap();
        let over = (0..a.len()).filter(|&t| (a[t] - b[t]).abs() > 1e-4).count();
        println!(
            "worst texel {} ({}, {}): {} vs {}, valid {} vs {}; {over} texels over 1e-4",
            worst,
            worst % 512,
            worst / 512,
            a[worst],
            b[worst],
            results[0].n_valid[worst],
            results[1].n_valid[worst]
        );
    }
}
