//! The star-shaped sampling domain around a centre: the unit pattern disk, scaled in each
//! direction by its own margin before it is mapped onto the centre's metric ellipse. Where the
//! metric varies over the neighbourhood (near the poles of a latitude-longitude chart, across a
//! distorted chart) the ball reaches further in some directions than in others; a margin per
//! direction covers it without spreading every sample over the largest reach.
//!
//! A disk point `w` at angle `phi` goes to `m(phi) w`. In polar coordinates the map is
//! `(rho, phi) -> (m(phi) rho, phi)`, whose Jacobian is `m(phi)^2` (the `m'` term is tangential
//! and drops out of the determinant), so a sample stands for `m(phi)^2` times the area of its
//! pattern cell: the Monte Carlo sum stays unbiased for any continuous `m`.

use std::f64::consts::TAU;

/// Directions at which the margin is set; the margin is linear in angle between them.
pub const DIRECTIONS: usize = 16;

/// Per-direction margins of the sampling domain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    margins: [f64; DIRECTIONS],
}

impl Reach {
    /// The same margin in every direction (the plain ellipse of DESIGN.md §1.4.3).
    pub fn uniform(margin: f64) -> Self {
        Self { margins: [margin; DIRECTIONS] }
    }

    /// Angle of direction `k`.
    pub fn direction_angle(k: usize) -> f64 {
        TAU * k as f64 / DIRECTIONS as f64
    }

    /// Margin of direction `k`.
    pub fn margin(&self, k: usize) -> f64 {
        self.margins[k]
    }

    /// Sets the margin of direction `k`.
    pub fn set_margin(&mut self, k: usize, margin: f64) {
        self.margins[k] = margin;
    }

    /// The two directions on either side of `angle`, and the weight of the second.
    pub fn bracket(angle: f64) -> (usize, usize, f64) {
        let t = (angle / TAU * DIRECTIONS as f64).rem_euclid(DIRECTIONS as f64);
        let below = (t.floor() as usize).min(DIRECTIONS - 1);
        (below, (below + 1) % DIRECTIONS, t - below as f64)
    }

    /// Margin at `angle` (radians, any turn).
    pub fn at(&self, angle: f64) -> f64 {
        let (below, above, weight) = Self::bracket(angle);
        self.margins[below] * (1.0 - weight) + self.margins[above] * weight
    }

    /// `true` when every direction has the same margin.
    pub fn is_uniform(&self) -> bool {
        self.margins.iter().all(|&m| m == self.margins[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_margin_interpolates_between_directions_and_wraps_around() {
        let mut reach = Reach::uniform(1.0);
        reach.set_margin(0, 3.0);
        assert_eq!(reach.at(0.0), 3.0);
        assert_eq!(reach.at(TAU), 3.0);
        let half_step = Reach::direction_angle(1) / 2.0;
        assert!((reach.at(half_step) - 2.0).abs() < 1e-12);
        assert!((reach.at(-half_step) - 2.0).abs() < 1e-12);
        assert_eq!(reach.at(Reach::direction_angle(2)), 1.0);
        assert!(!reach.is_uniform() && Reach::uniform(1.5).is_uniform());
    }

    /// The Jacobian `m(phi)^2` of the star map: pattern cells weighted by it add up to the area of
    /// the star-shaped domain, counted here on a grid.
    #[test]
    fn weights_by_the_square_margin_measure_the_star_shaped_area() {
        let mut reach = Reach::uniform(1.25);
        reach.set_margin(3, 4.0);
        reach.set_margin(4, 2.0);
        let pattern = crate::sampling::disk_pattern(4096, 7, 0);
        let cell = std::f64::consts::PI / pattern.len() as f64;
        let weighted: f64 = pattern.iter().map(|w| cell * reach.at(w.y.atan2(w.x)).powi(2)).sum();
        let (n, half) = (2000, 4.0);
        let step = 2.0 * half / n as f64;
        let mut inside = 0usize;
        for a in 0..n {
            for b in 0..n {
                let (x, y) = (-half + (a as f64 + 0.5) * step, -half + (b as f64 + 0.5) * step);
                inside += usize::from(x.hypot(y) < reach.at(y.atan2(x)));
            }
        }
        let counted = inside as f64 * step * step;
        assert!((weighted - counted).abs() < 5e-3 * counted, "{weighted} vs {counted}");
    }
}
