//! The pass behind [`lattice_statistics`](super::lattice_statistics): the weighted sums of one
//! texel over a run of its tile's lattice points, several points at a time, in the widest copy
//! the CPU runs ([`SumsKernel`]).
//!
//! The pass is bound by the vector units: on the 200K-face surfaces of docs/PEERS.md it was 45 %
//! of a tile's time with eight points at a time (25 % with sixteen), and each point costs a ball test, a square root, a reciprocal and ten
//! products and sums. The vector copies take `1 / rho` from the hardware estimate and one Newton
//! step (`sqrtps` and `divps` share one unit that takes 10-15 cycles for eight values each); the
//! AVX-512 copy sums sixteen points at a time, with masks for the ball tests and a register for
//! every sum, where the AVX2 copy spills them. Constant factors (`1 / r`, `1 / r^2`, `-2`) are
//! applied to the totals, not to every point. The products are not fused: with `mul_add` LLVM
//! left the AVX2 copy scalar, and the AVX-512 copy gained nothing from them.

use crate::sampling::{LatticeTexel, TileLattice};
use std::sync::OnceLock;

/// Which copy of the pass runs, narrowest first (a CPU that runs one runs those before it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum SumsKernel {
    /// Any CPU: eight points at a time, `1 / rho` from `sqrt` and a division.
    Portable,
    /// x86-64 with AVX2 and FMA: eight points in one register.
    Avx2,
    /// x86-64 with AVX-512 (F and VL) and FMA: sixteen points in one register.
    Avx512,
}

impl SumsKernel {
    /// The widest copy this CPU runs (its features are read once per process).
    pub fn detected() -> Self {
        static KERNEL: OnceLock<SumsKernel> = OnceLock::new();
        *KERNEL.get_or_init(|| {
            #[cfg(target_arch = "x86_64")]
            if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
                let avx512 = std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512vl");
                return if avx512 { Self::Avx512 } else { Self::Avx2 };
            }
            Self::Portable
        })
    }

    /// `true` when this CPU runs this copy.
    pub fn available(self) -> bool {
        self <= Self::detected()
    }
}

/// Thresholds of one pass (squared distances in the units of `q` and of `w`).
pub(super) struct Thresholds {
    pub margin2: f32,
    pub inner2: f32,
    pub outer2: f32,
    pub rho_min2: f32,
    /// The ball's edge as a ramp: `clamp(ramp_end / ramp_width - rho / ramp_width, 0, 1)`.
    pub ramp_end_in_widths: f32,
    pub inverse_ramp_width: f32,
    /// The normal curvatures are summed less this value (see `lattice_statistics`), halved: the
    /// pass sums `-k / 2`.
    pub half_shift: f32,
}

/// The totals of one pass, in f64. The curvature sums leave out the constant factor `1 / r^2` of
/// their weights and the `-2` of the normal curvature (the pass sums `-k / 2`), the radial sum the
/// `1 / r` of its integrand: the caller applies them.
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub(super) struct Totals {
    /// Points in the ball.
    pub valid: f64,
    /// The largest `|w - place|^2` of a point in the ball (0 without one).
    pub farthest: f32,
    pub area: f64,
    pub elevation_w: f64,
    pub elevation_wg: f64,
    pub radial_wg: f64,
    pub curvature_w: f64,
    pub curvature_wg: f64,
    pub curvature_wg2: f64,
    pub bending_w: f64,
    pub bending_wg: f64,
}

/// The widest pass's lanes: the lattice's columns are padded with this many inert points.
pub(crate) const WIDEST: usize = 16;
const _: () = assert!(WIDEST <= TileLattice::PADDING);

/// The sums of `texel` over the points of `run` of `lattice`, by `kernel` (which must be
/// [`available`](SumsKernel::available); the portable pass runs otherwise).
pub(super) fn sums(
    kernel: SumsKernel,
    lattice: &TileLattice,
    texel: &LatticeTexel,
    thresholds: &Thresholds,
    run: std::ops::Range<usize>,
    with_normals: bool,
) -> Totals {
    macro_rules! pass {
        ($f:ident) => {
            if with_normals {
                $f::<true>(lattice, texel, thresholds, run)
            } else {
                $f::<false>(lattice, texel, thresholds, run)
            }
        };
    }
    #[cfg(target_arch = "x86_64")]
    if kernel != SumsKernel::Portable && kernel.available() {
        // SAFETY: the CPU has the features each copy is compiled for (checked just above).
        return unsafe {
            match kernel {
                SumsKernel::Avx512 => pass!(pass_avx512),
                _ => pass!(pass_avx2),
            }
        };
    }
    pass!(pass_portable)
}

fn pass_portable<const NORMALS: bool>(
    lattice: &TileLattice,
    texel: &LatticeTexel,
    t: &Thresholds,
    run: std::ops::Range<usize>,
) -> Totals {
    pass::<NORMALS, false, 8>(lattice, texel, t, run)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn pass_avx2<const NORMALS: bool>(
    lattice: &TileLattice,
    texel: &LatticeTexel,
    t: &Thresholds,
    run: std::ops::Range<usize>,
) -> Totals {
    pass::<NORMALS, true, 8>(lattice, texel, t, run)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
unsafe fn pass_avx512<const NORMALS: bool>(
    lattice: &TileLattice,
    texel: &LatticeTexel,
    t: &Thresholds,
    run: std::ops::Range<usize>,
) -> Totals {
    pass::<NORMALS, true, WIDEST>(lattice, texel, t, run)
}

/// Lane sums of one pass; `[f32; L]` columns, so the loop compiles to vector instructions.
struct Lanes<const L: usize> {
    valid: [f32; L],
    farthest: [f32; L],
    area: [f32; L],
    elevation_w: [f32; L],
    elevation_wg: [f32; L],
    radial_wg: [f32; L],
    curvature_w: [f32; L],
    curvature_wg: [f32; L],
    curvature_wg2: [f32; L],
    bending_w: [f32; L],
    bending_wg: [f32; L],
}

impl<const L: usize> Lanes<L> {
    fn zero() -> Self {
        let zero = [0.0; L];
        Self {
            valid: zero,
            farthest: zero,
            area: zero,
            elevation_w: zero,
            elevation_wg: zero,
            radial_wg: zero,
            curvature_w: zero,
            curvature_wg: zero,
            curvature_wg2: zero,
            bending_w: zero,
            bending_wg: zero,
        }
    }

    /// Not inlined into the pass: with this inlined, the pass's loop took 1.5x its time.
    fn totals(&self) -> Totals {
        let total = |column: &[f32; L]| pairwise_total(column.map(f64::from));
        Totals {
            valid: total(&self.valid),
            farthest: self.farthest.iter().copied().fold(0.0, greater),
            area: total(&self.area),
            elevation_w: total(&self.elevation_w),
            elevation_wg: total(&self.elevation_wg),
            radial_wg: total(&self.radial_wg),
            curvature_w: total(&self.curvature_w),
            curvature_wg: total(&self.curvature_wg),
            curvature_wg2: total(&self.curvature_wg2),
            bending_w: total(&self.bending_w),
            bending_wg: total(&self.bending_wg),
        }
    }
}

/// The sum of `L` (a power of two) values, pairwise: the upper half added to the lower one lane by
/// lane, down to one, where a running sum is `L` dependent additions per column, eleven columns
/// per texel (with the farthest lane's fold, `totals` went from 3.1 to 2.5 % of the features' CPU
/// on the 200K lat-long sphere at r = 4 %).
#[inline(always)]
fn pairwise_total<const L: usize>(mut values: [f64; L]) -> f64 {
    let mut half = L / 2;
    while half > 0 {
        for l in 0..half {
            values[l] += values[l + half];
        }
        half /= 2;
    }
    values[0]
}

/// `a` if it is greater than `b`, else `b`: one `maxps` (`f32::max` adds a NaN test, and no
/// operand here is NaN).
#[inline(always)]
fn greater(a: f32, b: f32) -> f32 {
    if a > b {
        a
    } else {
        b
    }
}

/// `a` if it is less than `b`, else `b` (one `minps`).
#[inline(always)]
fn lesser(a: f32, b: f32) -> f32 {
    if a < b {
        a
    } else {
        b
    }
}

/// `1 / sqrt(x)` of `L` positive values. In the vector copies, the hardware estimate (12 bits
/// with AVX2, 14 with AVX-512) and one Newton step, a relative error under 1e-6: the f32 sums
/// round at 6e-8 a term, and their Monte Carlo noise is 1e-3.
#[inline(always)]
fn inverse_sqrt<const ESTIMATE: bool, const L: usize>(x: [f32; L]) -> [f32; L] {
    #[cfg(target_arch = "x86_64")]
    if ESTIMATE {
        use std::arch::x86_64::*;
        let mut inverse = [0.0; L];
        // SAFETY: `ESTIMATE` is set only in `pass_avx2` (L = 8) and `pass_avx512` (L = 16), compiled
        // for the instructions used here, into which this function is inlined; the loads and
        // stores are of `L` f32.
        unsafe {
            if L == 8 {
                let x = _mm256_loadu_ps(x.as_ptr());
                let estimate = _mm256_rsqrt_ps(x);
                let half_x = _mm256_mul_ps(x, _mm256_set1_ps(0.5));
                // y (3/2 - x y^2 / 2)
                let step = _mm256_fnmadd_ps(_mm256_mul_ps(half_x, estimate), estimate, _mm256_set1_ps(1.5));
                _mm256_storeu_ps(inverse.as_mut_ptr(), _mm256_mul_ps(estimate, step));
                return inverse;
            }
            if L == 16 {
                let x = _mm512_loadu_ps(x.as_ptr());
                let estimate = _mm512_rsqrt14_ps(x);
                let half_x = _mm512_mul_ps(x, _mm512_set1_ps(0.5));
                let step = _mm512_fnmadd_ps(_mm512_mul_ps(half_x, estimate), estimate, _mm512_set1_ps(1.5));
                _mm512_storeu_ps(inverse.as_mut_ptr(), _mm512_mul_ps(estimate, step));
                return inverse;
            }
        }
    }
    x.map(|v| 1.0 / v.sqrt())
}

/// The columns' `chunks` chunks of `L` points from `start`: the padding (at least [`WIDEST`]
/// inert points) keeps the last chunk inside the column.
fn chunked<const L: usize>(column: &[f32], start: usize, chunks: usize) -> &[[f32; L]] {
    &column[start..].as_chunks::<L>().0[..chunks]
}

/// The lane sums over the points of `run`, `L` at a time. A chunk may read past the run into the
/// next points or the padding: those lie outside the texel's domain (the run holds every point
/// of it), and the domain test drops them.
#[inline(always)]
fn pass<const NORMALS: bool, const ESTIMATE: bool, const L: usize>(
    lattice: &TileLattice,
    texel: &LatticeTexel,
    t: &Thresholds,
    run: std::ops::Range<usize>,
) -> Totals {
    let mut lanes = Lanes::<L>::zero();
    let (place, p, n) = (texel.place, texel.position, texel.normal);
    let chunks = run.len().div_ceil(L);
    let columns = |column| chunked::<L>(column, run.start, chunks);
    let (wx, wy) = (columns(&lattice.w[0]), columns(&lattice.w[1]));
    let (qx, qy, qz) = (columns(&lattice.q[0]), columns(&lattice.q[1]), columns(&lattice.q[2]));
    let area = columns(&lattice.area);
    let normals = if NORMALS {
        [columns(&lattice.normal[0]), columns(&lattice.normal[1]), columns(&lattice.normal[2])]
    } else {
        [area; 3] // not read
    };
    for k in 0..chunks {
        let (wx, wy, qx, qy, qz, area) = (wx[k], wy[k], qx[k], qy[k], qz[k], area[k]);
        // Stage by stage through arrays of `L`: one expression per point from the columns to the
        // sums is too deep a tree for LLVM's vectorizer, which then left the AVX2 copy scalar.
        let (mut dx, mut dy, mut dz, mut d2, mut dw2) = ([0.0; L], [0.0; L], [0.0; L], [0.0; L], [0.0; L]);
        for l in 0..L {
            (dx[l], dy[l], dz[l]) = (qx[l] - p.x, qy[l] - p.y, qz[l] - p.z);
            d2[l] = dx[l] * dx[l] + dy[l] * dy[l] + dz[l] * dz[l];
            let (dwx, dwy) = (wx[l] - place.x, wy[l] - place.y);
            dw2[l] = dwx * dwx + dwy * dwy;
        }
        // Points nearer than `inner` are dropped: the floor only keeps their terms finite.
        let inverse_distance = inverse_sqrt::<ESTIMATE, L>(d2.map(|x| greater(x, t.inner2)));
        let (mut a, mut curved, mut elevation, mut valid) = ([0.0; L], [0.0; L], [0.0; L], [0.0; L]);
        let distance: [f32; L] = std::array::from_fn(|l| d2[l] * inverse_distance[l]);
        for l in 0..L {
            // `&`, not `&&`: a branch per point keeps the lanes from being vectorized.
            let in_domain = (dw2[l] < t.margin2) & (d2[l] > t.inner2);
            let ramp = t.ramp_end_in_widths - distance[l] * t.inverse_ramp_width;
            a[l] = if in_domain { area[l] * lesser(greater(ramp, 0.0), 1.0) } else { 0.0 };
            curved[l] = if d2[l] >= t.rho_min2 { a[l] } else { 0.0 };
            elevation[l] = n.x * dx[l] + n.y * dy[l] + n.z * dz[l];
            valid[l] = if in_domain & (d2[l] < t.outer2) { 1.0 } else { 0.0 };
        }
        for l in 0..L {
            let inverse_d2 = inverse_distance[l] * inverse_distance[l];
            lanes.valid[l] += valid[l];
            // A select, not `valid * dw2`: the padding's `dw2` is infinite, and `0 * inf` is NaN.
            lanes.farthest[l] = greater(lanes.farthest[l], if valid[l] > 0.0 { dw2[l] } else { 0.0 });
            lanes.area[l] += a[l];
            lanes.elevation_w[l] += a[l] * distance[l];
            lanes.elevation_wg[l] += a[l] * elevation[l];
            lanes.radial_wg[l] += a[l] * d2[l];
            // The normal curvature `-2 elevation / rho^2`, summed as `elevation / rho^2 + shift / 2`
            // (the caller scales by -2): weights `curved rho^2` (times `1 / r^2`, also the caller's).
            let weight = curved[l] * d2[l];
            let shifted = elevation[l] * inverse_d2 + t.half_shift;
            let weighted = weight * shifted;
            lanes.curvature_w[l] += weight;
            lanes.curvature_wg[l] += weighted;
            lanes.curvature_wg2[l] += weighted * shifted;
            if NORMALS {
                let (ex, ey, ez) = (n.x - normals[0][k][l], n.y - normals[1][k][l], n.z - normals[2][k][l]);
                let bend = ex * ex + ey * ey + ez * ez;
                lanes.bending_w[l] += curved[l];
                lanes.bending_wg[l] += curved[l] * bend * inverse_d2;
            }
        }
    }
    lanes.totals()
}

#[cfg(test)]
mod tests;
