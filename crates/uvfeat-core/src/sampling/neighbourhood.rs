//! The weighted neighbourhood of one parametric point (SPEC §1.4, §1.7): pattern samples mapped
//! onto the anisotropic ellipse of the centre's metric, relocated across seams, looked up exactly,
//! rejected outside the ball of radius `r`, and weighted by the surface area they represent.

use crate::atlas::Atlas;
use crate::distortion::Distortion;
use super::reach::Reach;
use crate::lookup::{evaluate_face, surface_point, SurfacePoint};
use crate::raster::Precision;
use crate::relocation::{home, locate_with, Home, Located, Relocation};
use glam::{DMat2, DVec2, DVec3};
use half::f16;

/// Which samples belong to the neighbourhood `S(p, r)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Criterion {
    /// `|q - p| < r` (default; the paper's).
    #[default]
    Euclidean,
    /// Arc-length geodesic estimate `d_arc(p, q) < r` (SPEC §2.5).
    Geodesic,
}

/// Settings of the sampler.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SamplerSettings {
    /// Neighbourhood radius `r` (object units).
    pub radius: f64,
    /// Ellipse coverage margin `m` (SPEC §3.2; 1.25 default, 1 = paper).
    pub margin: f64,
    /// Seams a sample may cross (SPEC §1.5; 8 default, 1 = paper).
    pub max_jumps: u32,
    /// How samples that leave the chart are relocated.
    pub relocation: Relocation,
    /// Neighbourhood criterion.
    pub criterion: Criterion,
}

/// The centre `p = P(s)` of a neighbourhood.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Centre {
    /// Parametric location `s`.
    pub uv: DVec2,
    /// Chart of `s`.
    pub chart: i32,
    /// `p`.
    pub position: DVec3,
    /// Unit normal at `p`.
    pub normal: DVec3,
    /// The sampler's metric at `s` (see [`crate::frame::Frame::sampling_distortion`]).
    pub distortion: Distortion,
    /// The face containing `s`, where walks to the samples start.
    pub home: Home,
}

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

fn rounded(v: DVec3, precision: Precision) -> DVec3 {
    match precision {
        Precision::F32 => v,
        Precision::F16 => DVec3::from_array(v.to_array().map(|x| f64::from(f16::from_f64(x)))),
    }
}

/// The centre at parametric location `uv`; `None` off the charts or on a face degenerate in 3D.
pub fn centre_at(atlas: &Atlas, uv: DVec2) -> Option<Centre> {
    let chart = atlas.chart_at(uv);
    let home = home(atlas, uv, chart)?;
    let point = evaluate_face(atlas, home.face, home.point)?;
    let distortion = atlas.frame.sampling_distortion(&atlas.topology, home.face, home.point);
    if !(distortion.sigma2 > 1e-12 * distortion.sigma1) {
        return None;
    }
    Some(Centre {
        uv,
        chart,
        position: rounded(point.position, atlas.precision),
        normal: rounded(point.normal, atlas.precision),
        distortion,
        home,
    })
}

/// The centre's metric ellipse for unit margin: maps a disk point `w` to the parametric offset
/// `R(theta) diag(r / sigma_1, r / sigma_2) w`.
pub fn unit_ellipse(centre: &Centre, settings: &SamplerSettings) -> DMat2 {
    let d = centre.distortion;
    let r = settings.radius;
    DMat2::from_angle(d.theta) * DMat2::from_diagonal(DVec2::new(r / d.sigma1, r / d.sigma2))
}

/// Parametric area of the unit-margin ellipse, `A_uv = pi r^2 / (sigma_1 sigma_2)`.
fn unit_ellipse_area(centre: &Centre, settings: &SamplerSettings) -> f64 {
    std::f64::consts::PI * settings.radius * settings.radius / centre.distortion.area_element()
}

/// Arc-length geodesic estimate (SPEC §2.5a, `geodesic = "arc"`): the length of the circle arc
/// tangent to the surface at `p` through `q`, `d = rho asin(y)/y`, `y = min(1, |sin alpha|)`.
pub fn arc_distance(distance: f64, sin_alpha: f64) -> f64 {
    let y = sin_alpha.abs().min(1.0);
    if y < 1e-4 {
        distance * (1.0 + y * y / 6.0)
    } else {
        distance * y.asin() / y
    }
}

/// Where a parametric `target` reached from the centre lies on the surface.
enum Reached {
    Surface { point: SurfacePoint, m_path: DMat2 },
    Border,
    Missing,
}

fn reach_target(atlas: &Atlas, centre: &Centre, target: DVec2, settings: &SamplerSettings) -> Reached {
    let located =
        locate_with(atlas, settings.relocation, centre.uv, Some(&centre.home), centre.chart, target, settings.max_jumps);
    let (chart, uv, m_path, face) = match located {
        Located::Inside { chart, uv, m_path, face, .. } => (chart, uv, m_path, face),
        Located::Border => return Reached::Border,
        Located::Missing => return Reached::Missing,
    };
    let point = match face {
        Some(face) => evaluate_face(atlas, face, uv),
        None => surface_point(atlas, uv, chart),
    };
    match point {
        Some(point) => Reached::Surface { point, m_path },
        None => Reached::Missing,
    }
}

fn is_inside(distance: f64, sin_alpha: f64, settings: &SamplerSettings) -> bool {
    match settings.criterion {
        Criterion::Euclidean => distance < settings.radius,
        Criterion::Geodesic => arc_distance(distance, sin_alpha) < settings.radius,
    }
}

/// Distance `|q - p|` of the surface point `q` reached at `target` when it lies in the ball
/// `S(p, r)`; `None` outside it or off the surface (a mesh border or a failed relocation ends the
/// neighbourhood there too).
pub fn distance_inside(atlas: &Atlas, centre: &Centre, target: DVec2, settings: &SamplerSettings) -> Option<f64> {
    let Reached::Surface { point, .. } = reach_target(atlas, centre, target, settings) else {
        return None;
    };
    let offset = rounded(point.position, atlas.precision) - centre.position;
    let distance = offset.length();
    is_inside(distance, centre.normal.dot(offset) / distance.max(f64::MIN_POSITIVE), settings).then_some(distance)
}

/// Samples the neighbourhood of `centre` with `pattern` (unit-disk points) rotated by `psi` and
/// stretched per direction by `reach`. Each sample stands for `m(phi)^2 A_uv / N` of parametric
/// area (see [`Reach`]). Accepted samples are appended to `out` (no allocation once it has grown).
pub fn gather(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    psi: f64,
    reach: &Reach,
    settings: &SamplerSettings,
    out: &mut Vec<Sample>,
) -> SampleCounts {
    let ellipse = unit_ellipse(centre, settings);
    let turn = DMat2::from_angle(psi);
    let cell_area = unit_ellipse_area(centre, settings) / pattern.len() as f64;
    let uniform = reach.is_uniform().then(|| reach.margin(0));
    let r = settings.radius;
    let mut counts = SampleCounts::default();
    for (pattern_index, &disk) in pattern.iter().enumerate() {
        let w = turn * disk;
        let margin = uniform.unwrap_or_else(|| reach.at(w.y.atan2(w.x)));
        let target = centre.uv + ellipse * (margin * w);
        let (point, m_path) = match reach_target(atlas, centre, target, settings) {
            Reached::Surface { point, m_path } => (point, m_path),
            Reached::Border => {
                counts.border += 1;
                continue;
            }
            Reached::Missing => {
                counts.missing += 1;
                continue;
            }
        };
        let q = rounded(point.position, atlas.precision);
        let offset = q - centre.position;
        let distance = offset.length();
        if distance <= 1e-6 * r {
            continue;
        }
        let sin_alpha = centre.normal.dot(offset) / distance;
        if !is_inside(distance, sin_alpha, settings) {
            continue;
        }
        counts.valid += 1;
        out.push(Sample {
            position: q,
            normal: rounded(point.normal, atlas.precision),
            area: point.area_element * m_path.determinant().abs() * cell_area * margin * margin,
            distance,
            sin_alpha,
            pattern_index: pattern_index as u32,
        });
    }
    counts
}
