use super::super::{lattice_statistics, LatticeNeighbourhood, StatsSettings, WeightedSums};
use super::SumsKernel;
use crate::sampling::{LatticeTexel, TileLattice};
use glam::{Vec2, Vec3};

/// A paraboloid patch `z = (k1 x^2 + k2 y^2) / 2` sampled on a jittered grid of the plane `w`
/// (pattern units, `q = scale w`), with its normals and uneven areas: curvature, elevation and
/// bending are all non-zero.
fn paraboloid_lattice(side: usize, scale: f32) -> TileLattice {
    let (k1, k2, spacing) = (3.0f32, -1.5f32, 3.0 / side as f32);
    let points: Vec<_> = (0..side * side)
        .map(|k| {
            let jitter = ((k * 7919) % 101) as f32 / 101.0 - 0.5;
            let w = Vec2::new((k % side) as f32, (k / side) as f32) * spacing - Vec2::splat(1.5)
                + Vec2::new(0.1, -0.2) * jitter * spacing;
            let (x, y) = (scale * w.x, scale * w.y);
            let q = Vec3::new(x, y, 0.5 * (k1 * x * x + k2 * y * y));
            let normal = Vec3::new(-k1 * x, -k2 * y, 1.0).normalize();
            (w, q, normal, scale * scale * spacing * spacing * (1.0 + 0.3 * jitter))
        })
        .collect();
    TileLattice::from_points(&points, 1.25, spacing, true)
}

/// The texels of a 5 x 5 block around the patch's middle and of a column near its end along the
/// sorted axis (their runs reach the padding), on the surface.
fn texels(scale: f32) -> Vec<LatticeTexel> {
    let middle = (0..25).map(|k| Vec2::new((k % 5) as f32 - 2.0, (k / 5) as f32 - 2.0) * 0.07);
    let end = (0..5).map(|k| Vec2::new(1.2, 0.3 * k as f32 - 0.6));
    middle
        .chain(end)
        .map(|place| {
            let (x, y) = (scale * place.x, scale * place.y);
            let position = Vec3::new(x, y, 0.5 * (3.0 * x * x - 1.5 * y * y));
            LatticeTexel { place, position, normal: Vec3::new(-3.0 * x, 1.5 * y, 1.0).normalize() }
        })
        .collect()
}

/// Relative agreement of two sums, against the larger of their magnitudes and `floor`.
fn close(a: f64, b: f64, tolerance: f64, floor: f64) -> bool {
    (a - b).abs() <= tolerance * a.abs().max(b.abs()).max(floor)
}

fn assert_same(a: &LatticeNeighbourhood, b: &LatticeNeighbourhood, what: &str) {
    let pairs = |s: &LatticeNeighbourhood| -> [WeightedSums; 5] {
        [s.stats.elevation, s.stats.radial, s.stats.bending, s.stats.normal_curvature, s.stats.geodesic_disk]
    };
    for (k, (x, y)) in pairs(a).iter().zip(pairs(b)).enumerate() {
        for (u, v) in [(x.w, y.w), (x.wg, y.wg), (x.wg2, y.wg2)] {
            assert!(close(u, v, 2e-5, 1e-9), "{what}, sums {k}: {u} against {v}");
        }
    }
    assert_eq!((a.counts, a.rim), (b.counts, b.rim), "{what}");
}

/// Every copy of the pass this CPU runs gives the sums of the formulas, evaluated here in f64
/// point by point (`lattice_statistics`' doc: `w = dA rho`, `k = -2 n.(q - p) / rho^2` with
/// weights `dA rho^2 / r^2` beyond `rho_min`, the ball's edge a ramp two cells wide).
#[test]
fn every_kernel_gives_the_sums_of_the_formulas() {
    let scale = 0.1;
    let lattice = paraboloid_lattice(40, scale);
    let settings = StatsSettings { radius: f64::from(scale), rho_min: 0.01, volume_weighting: Default::default() };
    let kernels = [SumsKernel::Portable, SumsKernel::Avx2, SumsKernel::Avx512];
    let mut checked = 0;
    for texel in texels(scale) {
        for with_normals in [false, true] {
            let shift = 0.7;
            let (reference, farthest) = formulas(&lattice, &texel, &settings, with_normals);
            for kernel in kernels.into_iter().filter(|kernel| kernel.available()) {
                let what = format!("{kernel:?} at {}", texel.place);
                let sums = lattice_statistics(kernel, &lattice, &texel, &settings, 0.8, with_normals, shift);
                assert_same(&sums, &reference, &what);
                // The rim test reads the farthest point of the ball exactly: just inside it, and
                // just beyond.
                let rim_at = |fraction: f64| {
                    let fraction = (fraction * farthest).sqrt() as f32 / lattice.margin;
                    lattice_statistics(kernel, &lattice, &texel, &settings, fraction, with_normals, shift).rim
                };
                assert!(farthest > 0.0 && rim_at(1.0 - 1e-5) && !rim_at(1.0 + 1e-5), "{what}: {farthest}");
                checked += 1;
            }
        }
    }
    assert!(checked >= 50, "{checked}");
    assert!(SumsKernel::detected().available());
}

/// The neighbourhood from the formulas, in f64 over every point of the lattice (the shift of the
/// curvature sums only guards their f32 rounding: these are the unshifted sums), and the largest
/// `|w - place|^2` of a point in the ball.
fn formulas(
    lattice: &TileLattice,
    texel: &LatticeTexel,
    settings: &StatsSettings,
    with_normals: bool,
) -> (LatticeNeighbourhood, f64) {
    let r = settings.radius;
    let ramp_width = r * 2.0 * f64::from(lattice.spacing);
    let ramp_end = r * (crate::sampling::ramp_centre(ramp_width / r) + 0.5 * ramp_width / r);
    let (p, n) = (texel.position.as_dvec3(), texel.normal.as_dvec3());
    let mut out = LatticeNeighbourhood::default();
    let mut farthest = 0.0f64;
    for k in 0..lattice.len() {
        let w = glam::DVec2::new(f64::from(lattice.w[0][k]), f64::from(lattice.w[1][k]));
        let d =
            glam::DVec3::new(f64::from(lattice.q[0][k]), f64::from(lattice.q[1][k]), f64::from(lattice.q[2][k])) - p;
        let (dw2, rho) = ((w - texel.place.as_dvec2()).length_squared(), d.length());
        if dw2 >= f64::from(lattice.margin).powi(2) || rho <= 1e-6 * r {
            continue;
        }
        if rho < r {
            out.counts.valid += 1;
            farthest = farthest.max(dw2);
        }
        let a = f64::from(lattice.area[k]) * ((ramp_end - rho) / ramp_width).clamp(0.0, 1.0);
        let curved = if rho >= settings.rho_min { a } else { 0.0 };
        let elevation = n.dot(d);
        let s = &mut out.stats;
        s.geodesic_disk.w += a;
        s.elevation.w += a * rho;
        s.elevation.wg += a * elevation;
        s.radial.wg += a * rho * rho / r;
        let (weight, curvature) = (curved * rho * rho / (r * r), -2.0 * elevation / (rho * rho));
        s.normal_curvature.w += weight;
        s.normal_curvature.wg += weight * curvature;
        s.normal_curvature.wg2 += weight * curvature * curvature;
        if with_normals {
            let normal = glam::DVec3::new(
                f64::from(lattice.normal[0][k]),
                f64::from(lattice.normal[1][k]),
                f64::from(lattice.normal[2][k]),
            );
            s.bending.w += curved;
            s.bending.wg += curved * (n - normal).length_squared() / (rho * rho);
        }
    }
    out.stats.radial.w = out.stats.elevation.w;
    out.rim = farthest >= (0.8 * f64::from(lattice.margin)).powi(2);
    (out, farthest)
}

/// The farthest point of the ball decides the rim even when its lane later reads the padding (the
/// inert points lie at infinity): 17 points on a line, the farthest in the ball the second.
#[test]
fn the_farthest_point_decides_the_rim_beside_the_padding() {
    let xs = [-1.2f32, -0.97].into_iter().chain((0..15).map(|k| -0.8 + 0.1 * k as f32));
    let points: Vec<_> = xs.map(|x| (Vec2::new(x, 0.0), Vec3::new(0.1 * x, 0.0, 0.0), Vec3::Z, 1e-4)).collect();
    let lattice = TileLattice::from_points(&points, 1.25, 0.1, false);
    let settings = StatsSettings { radius: 0.1, rho_min: 0.01, volume_weighting: Default::default() };
    let texel = LatticeTexel { place: Vec2::ZERO, position: Vec3::ZERO, normal: Vec3::Z };
    for kernel in [SumsKernel::Portable, SumsKernel::Avx2, SumsKernel::Avx512].into_iter().filter(|k| k.available()) {
        let rim_at =
            |distance: f32| lattice_statistics(kernel, &lattice, &texel, &settings, distance / 1.25, false, 0.0).rim;
        assert!(rim_at(0.969) && !rim_at(0.971), "{kernel:?}");
    }
}
