//! The statistics of one texel over its tile's shared lattice (`sampling/lattice.rs`): the same
//! weighted sums as [`NeighbourhoodStats::accumulate`] over the lattice points of the texel's
//! sampling domain that lie in its ball, in one branch-free pass over f32 columns, eight or sixteen
//! points at a time (`features/lattice_sums.rs`), without building a sample per point.
//!
//! Only the sums the estimators read are formed (`w`, `wg`, and `wg2` of the curvature moments):
//! the sums of squared weights serve the standard errors and adaptive sampling, which the shared
//! path does not run, and stay 0, so that a standard error read from them is NaN, never a wrong
//! number. The distance weighting `w = dA rho` lets every integrand be written without a
//! division by `rho` (`w sin(alpha) = dA n.(q - p)`, `w rho / r = dA rho^2 / r`), and the curvature
//! moments need one `1 / rho^2`.

use super::lattice_sums::{sums, SumsKernel, Thresholds};
use super::statistics::{NeighbourhoodStats, StatsSettings, WeightedSums};
use crate::sampling::{ramp_centre, LatticeDomain, LatticeTexel, SampleCounts, TileLattice};

/// Width of the ball's edge ramp, in lattice cells (see `lattice_statistics`).
const RAMP: f32 = 2.0;

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

/// The statistics of `texel` over `lattice`, where a point at `rim_fraction` of the margin or more
/// marks the rim. `with_normals` adds the bending integrand (the lattice then carries normals).
///
/// The normal curvatures `k_i` are summed as `k_i - curvature_shift` and the sums shifted back in
/// f64: the principal curvatures read `sqrt(Var(k))`, which near an umbilic is the small
/// difference `<k^2> - <k>^2` of two numbers near `H^2`, and f32 sums of `k^2` lose it (k1 of a
/// sphere moved by 4e-4 when the mesh's normals did by 1e-16). A shift near the neighbourhood's
/// `<k>` (the group centre's own) keeps the f32 terms small.
///
/// `kernel` is the copy of the pass that forms the sums ([`SumsKernel::detected`] but in tests and
/// benchmarks, which compare them).
pub fn lattice_statistics(
    kernel: SumsKernel,
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
    let ramp_end = r * (ramp_centre(f64::from(RAMP * lattice.spacing)) as f32 + 0.5 * RAMP * lattice.spacing);
    let inverse_ramp_width = 1.0 / (r * RAMP * lattice.spacing);
    // The value the pass subtracts, in f32 (the sums are shifted back by this one).
    let shift = curvature_shift as f32;
    let thresholds = Thresholds {
        margin2: if grown { f32::INFINITY } else { margin * margin },
        // Floored so that `1 / rho^2` stays finite at radii whose square underflows.
        inner2: ((1e-6 * r) * (1e-6 * r)).max(f32::MIN_POSITIVE),
        outer2: r * r,
        rho_min2: rho_min * rho_min,
        ramp_end_in_widths: ramp_end * inverse_ramp_width,
        inverse_ramp_width,
        half_shift: 0.5 * shift,
    };
    // No point beyond the ramp's end weighs anything.
    let run = lattice.run(texel, ramp_end);
    let totals = sums(kernel, lattice, texel, &thresholds, run, with_normals);
    let radius = f64::from(r);
    let elevation = WeightedSums { w: totals.elevation_w, w2: 0.0, wg: totals.elevation_wg, wg2: 0.0 };
    // The pass summed `-k / 2` (its weights without `1 / r^2`).
    let curvature_scale = 1.0 / (radius * radius);
    let stats = NeighbourhoodStats {
        elevation,
        radial: WeightedSums { wg: totals.radial_wg / radius, ..elevation },
        bending: WeightedSums { w: totals.bending_w, w2: 0.0, wg: totals.bending_wg, wg2: 0.0 },
        normal_curvature: unshifted(
            WeightedSums {
                w: curvature_scale * totals.curvature_w,
                w2: 0.0,
                wg: -2.0 * curvature_scale * totals.curvature_wg,
                wg2: 4.0 * curvature_scale * totals.curvature_wg2,
            },
            f64::from(shift),
        ),
        geodesic_disk: WeightedSums { w: totals.area, w2: 0.0, wg: 0.0, wg2: 0.0 },
    };
    let rim = !grown && totals.farthest >= (rim_fraction * margin).powi(2);
    // Counted over a window of the sorted lost points, or once for a grown domain: a texel went
    // through all its lattice's (the clean 200K lat-long sphere at r = 4 %: 10 a texel on the
    // disks, 80 on the pole groups' grown domains).
    let (border, missing) = lattice.lost_in_domain(texel.place);
    let counts = SampleCounts { valid: totals.valid as u32, border, missing };
    LatticeNeighbourhood { stats, counts, rim }
}

/// The sums of `k` from the sums of `k - shift` (`sum w k^2 = sum w (k - s)^2 + 2 s sum w (k - s) + s^2 sum w`).
fn unshifted(sums: WeightedSums, shift: f64) -> WeightedSums {
    WeightedSums {
        wg: sums.wg + shift * sums.w,
        wg2: sums.wg2 + 2.0 * shift * sums.wg + shift * shift * sums.w,
        ..sums
    }
}
