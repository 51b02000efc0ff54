//! The sample pattern shared by all pixels (DESIGN.md §1.4.2–§1.4.3): a stratified jittered grid
//! mapped to the unit disk by the Shirley–Chiu concentric map, rotated per pixel by a hashed angle.

use glam::{DMat2, DVec2};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

/// PCG-style integer hash (O'Neill's PCG output permutation applied to an LCG step); good
/// avalanche, no state, so results do not depend on the order or number of threads.
#[inline]
pub fn pcg_hash(input: u32) -> u32 {
    let state = input.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// Uniform number in `[0, 1)` from a hash of several keys.
fn unit(keys: &[u32]) -> f64 {
    let h = keys.iter().fold(0x9e37_79b9u32, |h, &k| pcg_hash(h ^ k));
    f64::from(h) / 4_294_967_296.0
}

/// Per-pixel rotation `psi = 2 pi hash(i, j, seed) / 2^32` (DESIGN.md §1.4.3).
#[inline]
pub fn pixel_angle(i: u32, j: u32, seed: u64) -> f64 {
    TAU * unit(&[i, j, seed as u32, (seed >> 32) as u32])
}

/// Where the shared pattern lies at one pixel: turned by the pixel's angle (DESIGN.md §1.4.3) and
/// shifted in area radius, `rho^2 -> frac(rho^2 + shift)` (a Cranley–Patterson rotation of the
/// radial strata). The turn alone leaves the radii of the pattern the same at every pixel, so the
/// number of samples inside any circle is the same everywhere: on a plane at r = 0.1 the
/// geodesic-disk area then read 2.3 % low at every pixel (K = 28 instead of 0). With the shift the
/// strata move per pixel and that count is right on average, while each pixel keeps one sample
/// per stratum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    turn: DMat2,
    shift: f64,
}

impl Placement {
    /// A placement turned by `angle` (radians) and shifted by `shift` in `[0, 1)`.
    pub fn new(angle: f64, shift: f64) -> Self {
        Self { turn: DMat2::from_angle(angle), shift }
    }

    /// The placement of computation texel `(i, j)`.
    pub fn of_pixel(i: u32, j: u32, seed: u64) -> Self {
        Self::new(pixel_angle(i, j, seed), unit(&[i, j, seed as u32, (seed >> 32) as u32, 5]))
    }

    /// The placement of a direct evaluation at an input vertex.
    pub fn of_vertex(vertex: u32, seed: u64) -> Self {
        Self::new(TAU * unit(&[vertex, seed as u32, (seed >> 32) as u32, 6]), unit(&[vertex, seed as u32, 7]))
    }

    /// The turn of the placement.
    pub fn turn(&self) -> DMat2 {
        self.turn
    }

    /// The shift of the area radius, in `[0, 1)`.
    pub fn shift(&self) -> f64 {
        self.shift
    }

    /// The pattern point `disk` placed at this pixel.
    #[inline]
    pub fn place(&self, disk: DVec2) -> DVec2 {
        let area_radius = disk.length_squared();
        let shifted = self.shifted(area_radius);
        let scale = if area_radius > 0.0 { (shifted / area_radius).sqrt() } else { 0.0 };
        self.turn * (disk * scale)
    }

    /// `|place(disk)|^2`, the shifted area radius, without the square root and the turn.
    #[inline]
    pub fn placed_area_radius(&self, disk: DVec2) -> f64 {
        self.shifted(disk.length_squared())
    }

    /// `frac(area_radius + shift)` for a unit-disk point (the sum is in `[0, 2)`), without the
    /// library call `fract` compiles to on plain x86-64; the same value.
    #[inline]
    fn shifted(&self, area_radius: f64) -> f64 {
        let x = area_radius + self.shift;
        if x >= 1.0 {
            x - 1.0
        } else {
            x
        }
    }
}

/// Shirley–Chiu concentric map of `xi` in `[0, 1]^2` to the unit disk (area-preserving).
pub fn concentric_disk(xi: DVec2) -> DVec2 {
    let (a, b) = (2.0 * xi.x - 1.0, 2.0 * xi.y - 1.0);
    if a == 0.0 && b == 0.0 {
        return DVec2::ZERO;
    }
    let (radius, phi) = if a.abs() > b.abs() { (a, FRAC_PI_4 * (b / a)) } else { (b, FRAC_PI_2 - FRAC_PI_4 * (a / b)) };
    DVec2::new(radius * phi.cos(), radius * phi.sin())
}

/// Grid of `n_x x n_y = n` cells with `n_x` the largest divisor of `n` not above `sqrt(n)`.
pub fn grid_shape(n: usize) -> (usize, usize) {
    let nx = (1..=n.max(1)).take_while(|d| d * d <= n).filter(|d| n.is_multiple_of(*d)).last().unwrap_or(1);
    (nx, n / nx)
}

/// Rotational copies of the stratified base pattern in [`disk_pattern`].
pub const TURNS: usize = 8;

/// `n` points of the unit disk: `n / 8` base points, stratified in area (`rho^2`) and spread in
/// angle over one 45-degree sector, each turned by every multiple of 45 degrees (the `n mod 8`
/// remaining points are turned copies too, see [`leftover_points`]). `stage` selects independent jitters
/// (the two halves of adaptive sampling, DESIGN.md §1.8, use stages 1 and 2; full sampling stage 0).
///
/// Why turns: the ellipse maps the disk onto the tangent plane isometrically (up to scale), and
/// the normal curvature `kappa_n(phi) = H + (k1 - k2)/2 cos 2(phi - phi_1)` carries the
/// anisotropy in `cos 2 phi` (and `kappa_n^2` in `cos 4 phi`). Eight equally turned copies cancel
/// every harmonic below the 8th exactly, the dominant Monte Carlo noise of H and K on anisotropic
/// surfaces. The per-pixel rotation cannot average the radial distribution (it is shared by every
/// pixel), so the base radii are stratified explicitly: one per equal-area ring.
pub fn disk_pattern(n: usize, seed: u64, stage: u32) -> Vec<DVec2> {
    let m = n / TURNS;
    let (s0, s1) = (seed as u32, (seed >> 32) as u32);
    let sector = TAU / TURNS as f64;
    let mut points = Vec::with_capacity(n);
    for k in 0..m {
        let cell = k as u32;
        let radius = ((k as f64 + unit(&[s0, s1, stage, cell, 3])) / m as f64).sqrt();
        let spread = (k as f64 * 0.618_033_988_749_895 + unit(&[s0, s1, stage, cell, 4]) / m as f64).fract();
        let base = DVec2::from_angle(sector * spread) * radius;
        points.extend((0..TURNS).map(|t| DVec2::from_angle(sector * t as f64).rotate(base)));
    }
    points.extend(leftover_points(n % TURNS, seed, stage + 1000));
    points
}

/// The `count < 8` points of a pattern that the eight turns leave over, as copies of stratified
/// base points turned a quarter turn apart (four copies: the `cos 2 phi` anisotropy cancels), half
/// a turn apart (two copies), and one single point for an odd count. As independent points they
/// carried the whole anisotropy: at N = 100 (4 left over) the per-vertex noise of H on a torus was
/// 1.8x that of N = 64.
fn leftover_points(count: usize, seed: u64, stage: u32) -> Vec<DVec2> {
    let mut groups = Vec::new();
    let mut left = count;
    for turns in [4, 2, 1] {
        while left >= turns {
            groups.push(turns);
            left -= turns;
        }
    }
    let bases = stratified_disk(groups.len(), seed, stage);
    bases
        .into_iter()
        .zip(groups)
        .flat_map(|(base, turns)| {
            (0..turns).map(move |t| DVec2::from_angle(TAU * t as f64 / turns as f64).rotate(base))
        })
        .collect()
}

/// `n` stratified, jittered points of the unit disk (DESIGN.md §1.4.2).
pub fn stratified_disk(n: usize, seed: u64, stage: u32) -> Vec<DVec2> {
    let (nx, ny) = grid_shape(n);
    let (s0, s1) = (seed as u32, (seed >> 32) as u32);
    (0..ny)
        .flat_map(|l| (0..nx).map(move |k| (k, l)))
        .map(|(k, l)| {
            let cell = (l * nx + k) as u32;
            let jitter = DVec2::new(unit(&[s0, s1, stage, cell, 1]), unit(&[s0, s1, stage, cell, 2]));
            concentric_disk(DVec2::new((k as f64 + jitter.x) / nx as f64, (l as f64 + jitter.y) / ny as f64))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_shapes_follow_the_spec() {
        assert_eq!(grid_shape(64), (8, 8));
        assert_eq!(grid_shape(32), (4, 8));
        assert_eq!(grid_shape(100), (10, 10));
        assert_eq!(grid_shape(50), (5, 10));
        assert_eq!(grid_shape(7), (1, 7));
    }

    #[test]
    fn pattern_is_inside_the_disk_and_area_uniform() {
        let points = disk_pattern(4096, 7, 0);
        assert_eq!(points.len(), 4096);
        assert_eq!(disk_pattern(7, 1, 0).len(), 7);
        assert!((points[4] + points[0]).length() < 1e-12);
        assert!(points.iter().all(|p| p.length() <= 1.0));
        // Area-uniform: a quarter of the points within radius 1/2, and centred.
        let inner = points.iter().filter(|p| p.length() < 0.5).count() as f64 / 4096.0;
        assert!((inner - 0.25).abs() < 0.01, "{inner}");
        let mean = points.iter().copied().sum::<DVec2>() / 4096.0;
        assert!(mean.length() < 0.01);
    }

    #[test]
    fn shifted_placements_count_the_samples_inside_a_circle_right_on_average() {
        // The turned pattern alone has the same count inside radius 0.8 at every pixel.
        let points = disk_pattern(256, 0, 0);
        let inside = |placement: Placement| points.iter().filter(|&&p| placement.place(p).length() < 0.8).count();
        assert_eq!(inside(Placement::new(0.3, 0.0)), inside(Placement::new(2.0, 0.0)));
        let pixels = 4000;
        let mean = (0..pixels).map(|i| inside(Placement::of_pixel(i, 3, 0)) as f64).sum::<f64>() / f64::from(pixels);
        assert!((mean / (256.0 * 0.64) - 1.0).abs() < 2e-3, "{mean}");
        let placed = Placement::new(1.0, 0.5).place(DVec2::new(0.6, 0.0));
        assert!((placed.length_squared() - 0.86).abs() < 1e-12);
    }

    #[test]
    fn leftover_points_are_turned_copies_that_cancel_the_second_harmonic() {
        for n in [100, 52, 14, 7] {
            let points = disk_pattern(n, 3, 0);
            assert_eq!(points.len(), n);
            assert!(points.iter().all(|p| p.length() <= 1.0));
            let leftover = &points[n / TURNS * TURNS..];
            // sum of cos 2 phi and sin 2 phi weighted by rho^2: zero for groups of four.
            let harmonic: DVec2 = leftover
                .iter()
                .take(leftover.len() / 4 * 4)
                .map(|p| DVec2::new(p.x * p.x - p.y * p.y, 2.0 * p.x * p.y))
                .sum();
            assert!(harmonic.length() < 1e-12, "{n}: {harmonic}");
        }
        assert!((disk_pattern(100, 0, 0)[96] + disk_pattern(100, 0, 0)[98]).length() < 1e-12);
    }

    #[test]
    fn stages_and_seeds_give_independent_jitter_and_angles_are_spread() {
        assert_ne!(disk_pattern(16, 0, 1), disk_pattern(16, 0, 2));
        assert_ne!(disk_pattern(16, 0, 0), disk_pattern(16, 1, 0));
        assert_eq!(disk_pattern(16, 3, 0), disk_pattern(16, 3, 0));
        let angles: Vec<f64> = (0..1000).map(|i| pixel_angle(i, 7, 0)).collect();
        let mean = angles.iter().sum::<f64>() / 1000.0;
        assert!((mean - std::f64::consts::PI).abs() < 0.2);
    }
}
