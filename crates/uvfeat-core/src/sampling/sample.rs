//! The samples of one neighbourhood (DESIGN.md §1.4, §1.7) and their acceptance: a surface point
//! reached from the centre is kept when it lies in the ball of radius `r`, weighted by the surface
//! area it represents (the gathering itself is in `gather.rs`, `fast_path.rs` and `per_chart.rs`).

use super::centre::Centre;
use super::geodesic::{arc_distance, chord_sum_distance, Geodesic};
use super::settings::{Criterion, SamplerSettings};
use crate::atlas::Atlas;
use crate::lookup::SurfacePoint;
use glam::{DMat2, DVec2, DVec3};

/// One accepted sample `q_i` of a neighbourhood.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// `q_i`.
    pub position: DVec3,
    /// Unit normal `n_i`.
    pub normal: DVec3,
    /// Surface area it represents, `dA_i = J(t*) |det M_path| a`.
    pub area: f64,
    /// `rho_i = |q_i - p|`.
    pub distance: f64,
    /// `sin(alpha_i) = n . (q_i - p) / rho_i`.
    pub sin_alpha: f64,
    /// Geodesic distance estimate `d_i` (DESIGN.md §2.5a).
    pub geodesic: f64,
    /// Index of the pattern point the sample came from.
    pub pattern_index: u32,
}

/// What happened to the pattern samples of one neighbourhood.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SampleCounts {
    /// Accepted samples.
    pub valid: u32,
    /// Relocation failed (no border texel found, or more than `max_jumps` seams).
    pub missing: u32,
    /// Dropped at a mesh border: the neighbourhood is truncated there.
    pub border: u32,
}

impl SampleCounts {
    /// Adds another stage's counts.
    pub fn add(&mut self, other: SampleCounts) {
        self.valid += other.valid;
        self.missing += other.missing;
        self.border += other.border;
    }
}

/// The centre's metric ellipse for unit margin: maps a disk point `w` to the parametric offset
/// `R(theta) diag(r / sigma_1, r / sigma_2) w`.
pub fn unit_ellipse(centre: &Centre, settings: &SamplerSettings) -> DMat2 {
    let d = centre.distortion;
    let r = settings.radius;
    DMat2::from_angle(d.theta) * DMat2::from_diagonal(DVec2::new(r / d.sigma1, r / d.sigma2))
}

/// Parametric area of the unit-margin ellipse, `A_uv = pi r^2 / (sigma_1 sigma_2)`.
pub fn unit_ellipse_area(centre: &Centre, settings: &SamplerSettings) -> f64 {
    std::f64::consts::PI * settings.radius * settings.radius / centre.distortion.area_element()
}

/// `true` when a point at `distance` from the centre, with elevation `sin_alpha`, is in the ball
/// for the probes of the coverage check (the arc estimate stands in for any geodesic).
pub fn is_inside(distance: f64, sin_alpha: f64, settings: &SamplerSettings) -> bool {
    match settings.criterion {
        Criterion::Euclidean => distance < settings.radius,
        Criterion::Geodesic => arc_distance(distance, sin_alpha) < settings.radius,
    }
}

/// Where a linear ramp `width` wide across the ball's edge (both in units of `r`) is centred so
/// that it weighs a disk of radius `r` exactly: a ramp centred at `c` covers `pi (c^2 + width^2 /
/// 12)` (the shared lattice's edge, DESIGN.md §1.4.7, and the surfels', §1.4.8).
pub fn ramp_centre(width: f64) -> f64 {
    (1.0 - width * width / 12.0).sqrt()
}

/// Where a linear ramp `width` wide across the ball's edge (both in units of `r`) is centred so
/// that its area moments of `rho^4` and `rho^2` stand in a disk's ratio, `2 r^2 / 3`. The ratio
/// estimators (`H = -2 sum dA h / sum dA rho^2`, K's moments, the volumes) read their `O(r^2)`
/// term through that ratio, which a ramp centred for the area ([`ramp_centre`]) raises by `2
/// width^2 / 3` (a ball blurred outwards, read as a larger one); centred at `sqrt(1 - 3 width^2 /
/// 4)` it is kept to `O(width^4)`, and the disk weighs `pi (1 - 2 width^2 / 3)`, which no ratio
/// reads. (A ramp centred at `c` has moments `((c + w/2)^(k+3) - (c - w/2)^(k+3)) / ((k+2)(k+3)
/// w)`, so the ratio is `2/3 (c^2 + 3 w^2 / 4) + O(w^4)`.)
pub fn moment_ramp_centre(width: f64) -> f64 {
    (1.0 - 0.75 * width * width).sqrt()
}

/// The area a ramp `width` wide centred by [`moment_ramp_centre`] gives a disk of radius 1, over
/// `pi`: `1 - 2 width^2 / 3` (for an area ratio read under that ramp).
pub fn moment_ramp_area(width: f64) -> f64 {
    1.0 - 2.0 * width * width / 3.0
}

/// A surface point reached by one pattern sample, before the ball test.
pub struct Candidate {
    /// The surface point `q`.
    pub point: SurfacePoint,
    /// Parametric area it stands for, `|det M_path| a m(phi)^2` (times `J` gives `dA`).
    pub uv_area: f64,
    /// Its parametric location when it lies in the centre's chart without a crossing (for the
    /// chord-sum geodesic).
    pub own_chart_uv: Option<DVec2>,
    /// Index of the pattern point.
    pub pattern_index: u32,
}

/// Appends `candidate` to `out` when it lies in the neighbourhood `S(p, r)`; `true` if it did.
/// A geodesic estimate is never below the chord, so the Euclidean test comes first for both
/// criteria.
pub fn accept(
    atlas: &Atlas,
    centre: &Centre,
    candidate: Candidate,
    settings: &SamplerSettings,
    out: &mut Vec<Sample>,
) -> bool {
    let r = settings.radius;
    let q = atlas.precision.round_point(candidate.point.position);
    let offset = q - centre.position;
    let distance = offset.length();
    if distance <= 1e-6 * r || distance >= r {
        return false;
    }
    let sin_alpha = centre.normal.dot(offset) / distance;
    let geodesic = if settings.with_geodesic {
        match (settings.geodesic, candidate.own_chart_uv) {
            (Geodesic::ChordSum, Some(uv)) => chord_sum_distance(atlas, centre, uv, settings.lookup),
            _ => None,
        }
        .unwrap_or_else(|| arc_distance(distance, sin_alpha))
    } else {
        f64::NAN
    };
    if settings.criterion == Criterion::Geodesic && geodesic >= r {
        return false;
    }
    out.push(Sample {
        position: q,
        normal: atlas.precision.round_point(candidate.point.normal),
        area: candidate.point.area_element * candidate.uv_area,
        distance,
        sin_alpha,
        geodesic,
        pattern_index: candidate.pattern_index,
    });
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `integral rho^k w(rho) rho d rho` of a linear ramp from 1 at `c - w/2` to 0 at `c + w/2`.
    fn moment(k: i32, c: f64, w: f64) -> f64 {
        ((c + w / 2.0).powi(k + 3) - (c - w / 2.0).powi(k + 3)) / (f64::from((k + 2) * (k + 3)) * w)
    }

    #[test]
    fn each_ramp_keeps_its_disk_moment() {
        for w in [0.05, 0.1, 0.3] {
            // The area's: a unit disk's pi exactly; the moments' gives it `moment_ramp_area`.
            assert!((moment(0, ramp_centre(w), w) / 0.5 - 1.0).abs() < 1e-12, "w = {w}");
            assert!((moment(0, moment_ramp_centre(w), w) / 0.5 - moment_ramp_area(w)).abs() < 1e-12, "w = {w}");
            // The moments': rho^4 over rho^2 as the disk's 2/3, to O(w^4); the area's ramp is off by
            // 2 w^2 / 3 (the moment a wrong centring would break).
            let ratio = |c: f64| moment(4, c, w) / moment(2, c, w) / (2.0 / 3.0) - 1.0;
            assert!(ratio(moment_ramp_centre(w)).abs() < 2.0 * w.powi(4), "w = {w}: {}", ratio(moment_ramp_centre(w)));
            assert!((ratio(ramp_centre(w)) / (2.0 * w * w / 3.0) - 1.0).abs() < 0.1, "w = {w}");
        }
    }
}
