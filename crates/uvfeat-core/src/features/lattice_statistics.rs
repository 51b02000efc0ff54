//! The statistics of one texel over its tile's shared lattice (`sampling/lattice.rs`): the same
//! weighted sums as [`NeighbourhoodStats::accumulate`] over the lattice points of the texel's
//! sampling domain that lie in its ball, in one branch-free pass over f32 columns, eight points at
//! a time, without building a sample per point.
//!
//! Only the sums the estimators read are formed (`w`, `wg`, and `wg2` of the curvature moments):
//! the sums of squared weights serve the standard errors and adaptive sampling, which the shared
//! path does not run, and stay 0, so that a standard error read from them is NaN, never a wrong
//! number. The distance weighting `w = dA rho` lets every integrand be written without a
//! division by `rho` (`w sin(alpha) = dA n.(q - p)`, `w rho / r = dA rho^2 / r`), and the curvature
//! moments need one `1 / rho^2`.

use super::statistics::{NeighbourhoodStats, StatsSettings, WeightedSums};
use crate::sampling::{ramp_centre, LatticeDomain, LatticeTexel, SampleCounts, TileLattice};

/// Width of the ball's edge ramp, in lattice cells (see `lattice_statistics`).
const RAMP: f32 = 2.0;

/// Points summed at once (one AVX2 register of f32).
const LANES: usize = TileLattice::PADDING;

/// The neighbourhood of one texel on its tile's lattice.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LatticeNeighbourhood {
    /// The weighted sums.
    pub stats: NeighbourhoodStats,
    /// Points in the ball (valid), and lost points of the domain (border, missing).
    pub counts: SampleCounts,
    /// A point in the ball lies at the rim of the domain: the ball may reach past it.
    pub rim: bool,
}

/// Lane sums of one pass; `[f32; LANES]` columns, so the loop compiles to vector instructions.
#[derive(Default)]
struct Lanes {
    valid: [f32; LANES],
    rim: [f32; LANES],
    area: [f32; LANES],
    elevation_w: [f32; LANES],
    elevation_wg: [f32; LANES],
    radial_wg: [f32; LANES],
    curvature_w: [f32; LANES],
    curvature_wg: [f32; LANES],
    curvature_wg2: [f32; LANES],
    bending_w: [f32; LANES],
    bending_wg: [f32; LANES],
}

/// Thresholds of one pass.
struct Thresholds {
    margin2: f32,
    rim2: f32,
    inner2: f32,
    outer2: f32,
    rho_min2: f32,
    inverse_radius: f32,
    inverse_radius2: f32,
    /// The ball's edge as a ramp: `clamp((ramp_end - rho) / ramp_width, 0, 1)`.
    ramp_end: f32,
    inverse_ramp_width: f32,
    /// The normal curvatures are summed less this value (see `lattice_statistics`).
    shift: f32,
}

/// The statistics of `texel` over `lattice`, where a point at `rim_fraction` of the margin or more
/// marks the rim. `with_normals` adds the bending integrand (the lattice then carries normals).
///
/// The normal curvatures `k_i` are summed as `k_i - curvature_shift` and the sums shifted back in
/// f64: the principal curvatures read `sqrt(Var(k))`, which near an umbilic is the small
/// difference `<k^2> - <k>^2` of two numbers near `H^2`, and f32 sums of `k^2` lose it (k1 of a
/// sphere moved by 4e-4 when the mesh's normals did by 1e-16). A shift near the neighbourhood's
/// `<k>` (the group centre's own) keeps the f32 terms small.
pub fn lattice_statistics(
    lattice: &TileLattice,
    texel: &LatticeTexel,
    settings: &StatsSettings,
    rim_fraction: f32,
    with_normals: bool,
    curvature_shift: f64,
) -> LatticeNeighbourhood {
    let r = settings.radius as f32;
    let rho_min = settings.rho_min as f32;
    let margin = lattice.margin;
    // A grown domain is shared by every texel and final (the coverage check gathers twice at most).
    let grown = matches!(lattice.domain, LatticeDomain::Grown(_));
    let thresholds = Thresholds {
        margin2: if grown { f32::INFINITY } else { margin * margin },
        rim2: if grown { f32::INFINITY } else { (rim_fraction * margin).powi(2) },
        inner2: (1e-6 * r) * (1e-6 * r),
        outer2: r * r,
        rho_min2: rho_min * rho_min,
        inverse_radius: 1.0 / r,
        inverse_radius2: 1.0 / (r * r),
        ramp_end: r * (ramp_centre(f64::from(RAMP * lattice.spacing)) as f32 + 0.5 * RAMP * lattice.spacing),
        inverse_ramp_width: 1.0 / (r * RAMP * lattice.spacing),
        shift: curvature_shift as f32,
    };
    // No point beyond the ramp's end weighs anything.
    let run = lattice.run(texel, thresholds.ramp_end);
    let lanes = if with_normals {
        dispatch::<true>(lattice, texel, &thresholds, run)
    } else {
        dispatch::<false>(lattice, texel, &thresholds, run)
    };
    let total = |column: &[f32; LANES]| column.iter().map(|&x| f64::from(x)).sum::<f64>();
    let sums = |w: &[f32; LANES], wg: &[f32; LANES], wg2: Option<&[f32; LANES]>| WeightedSums {
        w: total(w),
        w2: 0.0,
        wg: total(wg),
        wg2: wg2.map_or(0.0, total),
    };
    let stats = NeighbourhoodStats {
        elevation: sums(&lanes.elevation_w, &lanes.elevation_wg, None),
        radial: sums(&lanes.elevation_w, &lanes.radial_wg, None),
        bending: sums(&lanes.bending_w, &lanes.bending_wg, None),
        // Shifted back by the value the lanes subtracted (the f32 one).
        normal_curvature: unshifted(
            sums(&lanes.curvature_w, &lanes.curvature_wg, Some(&lanes.curvature_wg2)),
            f64::from(thresholds.shift),
        ),
        geodesic_disk: WeightedSums { w: total(&lanes.area), w2: 0.0, wg: 0.0, wg2: 0.0 },
    };
    // Counted over a window of the sorted lost points, or once for a grown domain: a texel went
    // through all its lattice's (the clean 200K lat-long sphere at r = 4 %: 10 a texel on the
    // disks, 80 on the pole groups' grown domains).
    let (border, missing) = lattice.lost_in_domain(texel.place);
    let counts = SampleCounts { valid: total(&lanes.valid) as u32, border, missing };
    LatticeNeighbourhood { stats, counts, rim: lanes.rim.iter().any(|&x| x > 0.0) }
}

/// The sums of `k` from the sums of `k - shift` (`sum w k^2 = sum w (k - s)^2 + 2 s sum w (k - s) + s^2 sum w`).
fn unshifted(sums: WeightedSums, shift: f64) -> WeightedSums {
    WeightedSums {
        wg: sums.wg + shift * sums.w,
        wg2: sums.wg2 + 2.0 * shift * sums.wg + shift * shift * sums.w,
        ..sums
    }
}

/// [`sums`] in the copy compiled for AVX2 and FMA where the CPU has them.
fn dispatch<const NORMALS: bool>(
    lattice: &TileLattice,
    texel: &LatticeTexel,
    thresholds: &Thresholds,
    run: std::ops::Range<usize>,
) -> Lanes {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU has the features `sums_avx2` is compiled for (checked just above).
        return unsafe { sums_avx2::<NORMALS>(lattice, texel, thresholds, run) };
    }
    sums::<NORMALS>(lattice, texel, thresholds, run)
}

/// [`sums`] compiled for AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn sums_avx2<const NORMALS: bool>(
    lattice: &TileLattice,
    texel: &LatticeTexel,
    thresholds: &Thresholds,
    run: std::ops::Range<usize>,
) -> Lanes {
    sums::<NORMALS>(lattice, texel, thresholds, run)
}

/// The lane sums over the points of `run`, `LANES` at a time. The lattice's columns are padded
/// with inert points (see `TileLattice::PADDING`, equal to `LANES`), so a chunk may read past the run: points
/// outside the run lie outside the texel's domain and the domain test drops them.
#[inline(always)]
fn sums<const NORMALS: bool>(
    lattice: &TileLattice,
    texel: &LatticeTexel,
    t: &Thresholds,
    run: std::ops::Range<usize>,
) -> Lanes {
    let mut lanes = Lanes::default();
    let (place, p, n) = (texel.place, texel.position, texel.normal);
    let chunk = |column: &[f32], k: usize| -> [f32; LANES] { column[k..k + LANES].try_into().unwrap() };
    for k in run.step_by(LANES) {
        let (wx, wy) = (chunk(&lattice.w[0], k), chunk(&lattice.w[1], k));
        let (qx, qy, qz) = (chunk(&lattice.q[0], k), chunk(&lattice.q[1], k), chunk(&lattice.q[2], k));
        let area = chunk(&lattice.area, k);
        let mut bend = [0.0f32; LANES];
        if NORMALS {
            let (nx, ny, nz) =
                (chunk(&lattice.normal[0], k), chunk(&lattice.normal[1], k), chunk(&lattice.normal[2], k));
            for l in 0..LANES {
                let (ex, ey, ez) = (n.x - nx[l], n.y - ny[l], n.z - nz[l]);
                bend[l] = ex * ex + ey * ey + ez * ez;
            }
        }
        for l in 0..LANES {
            let (dwx, dwy) = (wx[l] - place.x, wy[l] - place.y);
            let dw2 = dwx * dwx + dwy * dwy;
            let (dx, dy, dz) = (qx[l] - p.x, qy[l] - p.y, qz[l] - p.z);
            let d2 = dx * dx + dy * dy + dz * dz;
            let in_domain = dw2 < t.margin2 && d2 > t.inner2;
            let accepted = in_domain && d2 < t.outer2;
            let distance = d2.sqrt();
            let inside = ((t.ramp_end - distance) * t.inverse_ramp_width).clamp(0.0, 1.0);
            let a = if in_domain { area[l] * inside } else { 0.0 };
            let curved = if d2 >= t.rho_min2 { a } else { 0.0 };
            let inverse_d2 = 1.0 / d2.max(t.inner2);
            let elevation = n.x * dx + n.y * dy + n.z * dz;
            lanes.valid[l] += if accepted { 1.0 } else { 0.0 };
            lanes.rim[l] += if accepted && dw2 >= t.rim2 { 1.0 } else { 0.0 };
            lanes.area[l] += a;
            lanes.elevation_w[l] += a * distance;
            lanes.elevation_wg[l] += a * elevation;
            lanes.radial_wg[l] += a * d2 * t.inverse_radius;
            let weight = curved * d2 * t.inverse_radius2;
            let shifted = -2.0 * elevation * inverse_d2 - t.shift;
            lanes.curvature_w[l] += weight;
            lanes.curvature_wg[l] += weight * shifted;
            lanes.curvature_wg2[l] += weight * shifted * shifted;
            if NORMALS {
                lanes.bending_w[l] += curved;
                lanes.bending_wg[l] += curved * bend[l] * inverse_d2;
            }
        }
    }
    lanes
}
