//! The weighted neighbourhood of one parametric point (SPEC §1.4, §1.7): pattern samples mapped
//! onto the anisotropic ellipse of the centre's metric, relocated across seams, looked up exactly,
//! rejected outside the ball of radius `r`, and weighted by the surface area they represent.

use crate::atlas::Atlas;
use crate::distortion::Distortion;
use crate::lookup::{evaluate_face, surface_point};
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

/// Parametric area of the sampling ellipse, `A_uv = pi m^2 r^2 / (sigma_1 sigma_2)`.
pub fn ellipse_area(centre: &Centre, settings: &SamplerSettings) -> f64 {
    let mr = settings.margin * settings.radius;
    std::f64::consts::PI * mr * mr / centre.distortion.area_element()
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

/// Samples the neighbourhood of `centre` with `pattern` (unit-disk points) rotated by `psi`;
/// `sample_area` is the parametric area each pattern point stands for (`A_uv / N`). Accepted
/// samples are appended to `out` (no allocation once it has grown).
pub fn gather(
    atlas: &Atlas,
    centre: &Centre,
    pattern: &[DVec2],
    psi: f64,
    sample_area: f64,
    settings: &SamplerSettings,
    out: &mut Vec<Sample>,
) -> SampleCounts {
    let d = centre.distortion;
    let mr = settings.margin * settings.radius;
    let ellipse = DMat2::from_angle(d.theta)
        * DMat2::from_diagonal(DVec2::new(mr / d.sigma1, mr / d.sigma2))
        * DMat2::from_angle(psi);
    let r = settings.radius;
    let mut counts = SampleCounts::default();
    for (pattern_index, &disk) in pattern.iter().enumerate() {
        let target = centre.uv + ellipse * disk;
        let located = locate_with(
            atlas,
            settings.relocation,
            centre.uv,
            Some(&centre.home),
            centre.chart,
            target,
            settings.max_jumps,
        );
        let (chart, uv, m_path, face) = match located {
            Located::Inside { chart, uv, m_path, face, .. } => (chart, uv, m_path, face),
            Located::Border => {
                counts.border += 1;
                continue;
            }
            Located::Missing => {
                counts.missing += 1;
                continue;
            }
        };
        let point = match face {
            Some(face) => evaluate_face(atlas, face, uv),
            None => surface_point(atlas, uv, chart),
        };
        let Some(point) = point else {
            counts.missing += 1;
            continue;
        };
        let q = rounded(point.position, atlas.precision);
        let offset = q - centre.position;
        let distance = offset.length();
        if distance <= 1e-6 * r {
            continue;
        }
        let sin_alpha = centre.normal.dot(offset) / distance;
        let inside = match settings.criterion {
            Criterion::Euclidean => distance < r,
            Criterion::Geodesic => arc_distance(distance, sin_alpha) < r,
        };
        if !inside {
            continue;
        }
        counts.valid += 1;
        out.push(Sample {
            position: q,
            normal: rounded(point.normal, atlas.precision),
            area: point.area_element * m_path.determinant().abs() * sample_area,
            distance,
            sin_alpha,
            pattern_index: pattern_index as u32,
        });
    }
    counts
}
