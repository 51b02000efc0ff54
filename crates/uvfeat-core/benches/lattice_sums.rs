//! The lattice sums (`features/lattice_sums.rs`) by each copy of the pass this CPU runs:
//! one tile's lattice on a sphere cap (about 1,800 points, the disks of a 16 x 16 tile at the
//! default 256 samples) and the 256 texels of the tile, one thread.
//!
//!     cargo bench -p uvfeat-core --bench lattice_sums

use glam::{Vec2, Vec3};
use std::time::Instant;
use uvfeat_core::features::{lattice_statistics, StatsSettings, SumsKernel};
use uvfeat_core::sampling::{LatticeTexel, TileLattice};

/// A point of the unit sphere's cap around the north pole at `w` (pattern units, `q = scale w`
/// on the tangent plane, lifted to the sphere).
fn on_cap(w: Vec2, scale: f32) -> (Vec3, Vec3) {
    let (x, y) = (scale * w.x, scale * w.y);
    let normal = Vec3::new(x, y, (1.0 - x * x - y * y).sqrt());
    (normal, normal)
}

fn main() {
    let (scale, spacing, side) = (0.05f32, 0.11f32, 48usize);
    let points: Vec<_> = (0..side * side)
        .map(|k| {
            let w = (Vec2::new((k % side) as f32, (k / side) as f32) - Vec2::splat(side as f32 / 2.0)) * spacing;
            let (q, normal) = on_cap(w, scale);
            (w, q, normal, (scale * spacing).powi(2))
        })
        .filter(|(w, ..)| w.x.abs().max(w.y.abs()) < 2.3)
        .collect();
    let lattice = TileLattice::from_points(&points, 1.25, spacing, false);
    let settings = StatsSettings {
        radius: f64::from(scale),
        rho_min: 0.1 * f64::from(scale),
        volume_weighting: Default::default(),
    };
    let texels: Vec<LatticeTexel> = (0..256)
        .map(|k| {
            let place = (Vec2::new((k % 16) as f32, (k / 16) as f32) - Vec2::splat(7.5)) * 0.06;
            let (position, normal) = on_cap(place, scale);
            LatticeTexel { place, position, normal }
        })
        .collect();
    let read: usize = texels.iter().map(|texel| lattice.run(texel, 1.05 * scale).len()).sum();
    println!(
        "{} lattice points, {:.0} read a texel (256 texels), detected: {:?}",
        lattice.len(),
        read as f64 / 256.0,
        SumsKernel::detected()
    );
    let mut portable = None;
    for kernel in [SumsKernel::Portable, SumsKernel::Avx2, SumsKernel::Avx512] {
        if !kernel.available() {
            println!("{kernel:?}: not available on this CPU");
            continue;
        }
        let mut best = f64::INFINITY;
        for _ in 0..30 {
            let started = Instant::now();
            for _ in 0..20 {
                for texel in &texels {
                    std::hint::black_box(lattice_statistics(kernel, &lattice, texel, &settings, 0.8, false, 1.0));
                }
            }
            best = best.min(started.elapsed().as_secs_f64() / (20.0 * 256.0));
        }
        let ratio = portable.map_or(String::new(), |p: f64| format!(", {:.2}x the portable copy's time", best / p));
        println!(
            "{kernel:?}: {:.0} ns a texel, {:.2} ns a point read{ratio}",
            1e9 * best,
            1e9 * best * 256.0 / read as f64
        );
        portable.get_or_insert(best);
    }
}
