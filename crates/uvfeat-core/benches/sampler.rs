//! Sampler benchmark: feature maps of the default configuration on the 102,400-face
//! lat-long torus on each sampling path (shared lattice, fast, exact), with CPU time per sample and
//! the error against the analytic torus, beside the floor of
//! any parametric sampler: a bare bilinear gather of the position buffer over the same ellipses
//! (same texels, samples and footprint; no relocation, no estimator).
//!
//!     cargo bench -p uvfeat-core --bench sampler [-- --radius 4 --samples 256 --paths shared,fast,exact --no-floors]

use rayon::prelude::*;
use std::sync::Arc;
use std::time::Instant;
use uvfeat_core::features::Feature;
use uvfeat_core::lookup::Lookup;
use uvfeat_core::mesh::{Topology, TriangleMesh};
use uvfeat_core::output::FeatureMaps;
use uvfeat_core::sampling::{centre_at, disk_pattern, pixel_angle, SamplingPath};
use uvfeat_core::settings::{Choice, ComputeSettings};
use uvfeat_core::{Atlas, AtlasOptions};

/// CPU seconds of this process (user + system) from /proc, or NaN where it is not available.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else { return f64::NAN };
    let fields: Vec<&str> = stat.rsplit(')').next().unwrap_or("").split_whitespace().collect();
    let ticks = |k: usize| fields.get(k).and_then(|x| x.parse::<f64>().ok()).unwrap_or(f64::NAN);
    (ticks(11) + ticks(12)) / 100.0
}

/// The position buffer as three planes of f32 (SoA), NaN off the charts, and as it is (AoS).
struct Planes {
    side: usize,
    xyz: [Vec<f32>; 3],
    points: Vec<[f32; 3]>,
}

impl Planes {
    fn new(atlas: &Atlas) -> Self {
        let position = &atlas.buffers().position;
        Self {
            side: atlas.resolution(),
            xyz: [0, 1, 2].map(|c| position.iter().map(|p| p[c]).collect()),
            points: position.clone(),
        }
    }

    /// Bilinear filtering of the three planes at texel coordinates `(x, y)` (texel centres at +0.5).
    #[inline(always)]
    fn bilinear(&self, x: f32, y: f32) -> [f32; 3] {
        let (x, y) = ((x - 0.5).clamp(0.0, (self.side - 2) as f32), (y - 0.5).clamp(0.0, (self.side - 2) as f32));
        let (i, j) = (x as usize, y as usize);
        let (fx, fy) = (x - i as f32, y - j as f32);
        let t = j * self.side + i;
        let weights = [(1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy];
        let texels = [t, t + 1, t + self.side, t + self.side + 1];
        self.xyz.each_ref().map(|plane| texels.iter().zip(weights).map(|(&t, w)| plane[t] * w).sum())
    }

    /// The position of the texel containing texel coordinates `(x, y)`: one load.
    #[inline(always)]
    fn nearest(&self, x: f32, y: f32) -> [f32; 3] {
        let last = (self.side - 1) as f32;
        self.points[y.clamp(0.0, last) as usize * self.side + x.clamp(0.0, last) as usize]
    }
}

/// Pattern points `d` at texel coordinates `centre + ellipse d` inside the ball around `p`,
/// compiled for AVX2 and FMA (the loads are the cost: 12 per sample bilinear, 1 nearest).
#[target_feature(enable = "avx2,fma")]
unsafe fn count_inside(
    planes: &Planes,
    bilinear: bool,
    pattern: &[[f32; 2]],
    centre: [f32; 2],
    e: [f32; 4],
    p: [f32; 3],
    r2: f32,
) -> u64 {
    let mut count = 0;
    for &[dx, dy] in pattern {
        let (x, y) = (centre[0] + e[0] * dx + e[2] * dy, centre[1] + e[1] * dx + e[3] * dy);
        let q = if bilinear { planes.bilinear(x, y) } else { planes.nearest(x, y) };
        let d2 = (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2);
        count += u64::from(d2 < r2);
    }
    count
}

/// The gather floor: every computation texel reads `samples` bilinear positions on its metric
/// ellipse (margin 1.25, turned per pixel, as the sampler places them) and counts those in the
/// ball, by bilinear filtering or from the nearest texel. Returns CPU seconds and the mean count
/// per texel.
fn gather_floor(
    atlas: &Atlas,
    planes: &Planes,
    bilinear: bool,
    radius: f64,
    samples: usize,
    compute_side: usize,
) -> (f64, f64) {
    let pattern: Vec<[f32; 2]> = disk_pattern(samples, 0, 0).iter().map(|d| [d.x as f32, d.y as f32]).collect();
    let side = atlas.resolution();
    let (r2, reach) = ((radius * radius) as f32, (1.25 * radius) as f32);
    let cpu = cpu_seconds();
    // Tile after tile of 16 x 16 texels, as the sampler evaluates them.
    let tiles = compute_side.div_ceil(16);
    let (texels, inside) = (0..tiles * tiles * 256)
        .into_par_iter()
        .with_min_len(256)
        .map(|t| {
            let (tile, within) = (t / 256, t % 256);
            let (i, j) = (tile % tiles * 16 + within % 16, tile / tiles * 16 + within / 16);
            if i >= compute_side || j >= compute_side {
                return (0u64, 0u64);
            }
            let (x, y) = (
                (i as f32 + 0.5) / compute_side as f32 * side as f32,
                (j as f32 + 0.5) / compute_side as f32 * side as f32,
            );
            let texel = y as usize * side + x as usize;
            let [s1, s2] = atlas.buffers().sigma[texel];
            if s2.is_nan() || s2 <= 0.0 {
                return (0u64, 0u64);
            }
            let p = planes.bilinear(x, y);
            let theta = atlas.buffers().theta[texel];
            let psi = pixel_angle(i as u32, j as u32, 0) as f32;
            let (a, b) = (reach / s1 * side as f32, reach / s2 * side as f32);
            let (ct, st, cp, sp) = (theta.cos(), theta.sin(), psi.cos(), psi.sin());
            assert!(std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma"));
            let ellipse = [
                a * cp * ct - b * sp * st,
                a * cp * st + b * sp * ct,
                -a * sp * ct - b * cp * st,
                -a * sp * st + b * cp * ct,
            ];
            // SAFETY: AVX2 and FMA were detected on this CPU (the benchmark needs them).
            let count = unsafe { count_inside(planes, bilinear, &pattern, [x, y], ellipse, p, r2) };
            (1, count)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    (cpu_seconds() - cpu, inside as f64 / texels.max(1) as f64)
}

/// The analytic H and K of the torus at the centre of every computation texel.
struct TorusTruth {
    mean: Vec<f64>,
    gaussian: Vec<f64>,
}

impl TorusTruth {
    fn new(atlas: &Atlas, major: f64, minor: f64, side: usize) -> Self {
        let (mut mean, mut gaussian) = (vec![f64::NAN; side * side], vec![f64::NAN; side * side]);
        for t in 0..side * side {
            let uv = glam::DVec2::new(((t % side) as f64 + 0.5) / side as f64, ((t / side) as f64 + 0.5) / side as f64);
            if let Some(centre) = centre_at(atlas, uv, Lookup::Triangle) {
                let p = centre.position;
                let cos_v = ((p.x.hypot(p.y) - major) / minor).clamp(-1.0, 1.0);
                mean[t] = (major + 2.0 * minor * cos_v) / (2.0 * minor * (major + minor * cos_v));
                gaussian[t] = cos_v / (minor * (major + minor * cos_v));
            }
        }
        Self { mean, gaussian }
    }

    /// Mean absolute error of H and K over the map, in % of the mean |truth|, and the mean
    /// signed error of H in the same unit (the bias).
    fn errors(&self, maps: &FeatureMaps) -> String {
        let error = |values: &[f32], truth: &[f64]| {
            let pairs: Vec<(f64, f64)> = values
                .iter()
                .zip(truth)
                .filter(|(v, t)| v.is_finite() && t.is_finite())
                .map(|(&v, &t)| (f64::from(v) - t, t.abs()))
                .collect();
            let scale = pairs.iter().map(|p| p.1).sum::<f64>();
            let absolute = pairs.iter().map(|p| p.0.abs()).sum::<f64>() / scale;
            let signed = pairs.iter().map(|p| p.0).sum::<f64>() / scale;
            (100.0 * absolute, 100.0 * signed)
        };
        let (h, h_bias) = error(&maps.values[0], &self.mean);
        let (k, k_bias) = error(&maps.values[1], &self.gaussian);
        format!("against the analytic torus: H {h:.2} % (bias {h_bias:+.2} %), K {k:.2} % (bias {k_bias:+.2} %)")
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |name: &str, default: &str| -> String {
        args.iter().position(|a| a == name).and_then(|k| args.get(k + 1)).cloned().unwrap_or_else(|| default.into())
    };
    let radius_percent: f64 = value("--radius", "4").parse().expect("--radius: a percentage");
    let samples: usize = value("--samples", "256").parse().expect("--samples: a count");
    let paths: Vec<SamplingPath> = value("--paths", "shared,fast,exact")
        .split(',')
        .map(|name| SamplingPath::named(name).expect("--paths: shared, fast or exact"))
        .collect();
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
    let truth = TorusTruth::new(&atlas, 2.0, 0.5, 512);
    let mut results = Vec::new();
    for &path in &paths {
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
        println!("    {}", truth.errors(&maps));
        results.push((path, maps, cpu));
    }
    let drawn = results[0].1.summary.texels as f64 * samples as f64;
    let planes = Planes::new(&atlas);
    let floors: &[(bool, &str)] = if args.iter().any(|a| a == "--no-floors") {
        &[]
    } else {
        &[(true, "bilinear SoA, 12 loads"), (false, "nearest texel AoS, 1 load")]
    };
    for &(bilinear, name) in floors {
        let (floor_cpu, floor_inside) = gather_floor(&atlas, &planes, bilinear, radius, samples, 512);
        let ratios: Vec<String> =
            results.iter().map(|(path, _, cpu)| format!("{path:?} / floor {:.2}x", cpu / floor_cpu)).collect();
        println!(
            "gather floor ({name}): cpu {:.0} ms, {:.1} ns cpu per sample, {floor_inside:.1} inside/texel; {}",
            1e3 * floor_cpu,
            1e9 * floor_cpu / drawn,
            ratios.join(", ")
        );
    }
    let find = |wanted: SamplingPath| results.iter().find(|(path, _, _)| *path == wanted).map(|(_, maps, _)| maps);
    if let (Some(fast), Some(exact)) = (find(SamplingPath::Fast), find(SamplingPath::Exact)) {
        let (a, b) = (&fast.values[0], &exact.values[0]);
        let diffs: Vec<f64> = a
            .iter()
            .zip(b)
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .map(|(x, y)| f64::from((x - y).abs()))
            .collect();
        let max = diffs.iter().cloned().fold(0.0, f64::max);
        let over = diffs.iter().filter(|&&d| d > 1e-4).count();
        println!(
            "H fast vs exact: max |diff| {max:.3e}, mean {:.3e}; {over} texels over 1e-4",
            diffs.iter().sum::<f64>() / diffs.len() as f64
        );
    }
}
