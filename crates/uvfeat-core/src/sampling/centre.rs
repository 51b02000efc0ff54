//! The centre `p = P(s)` of a neighbourhood: its point, normal and metric, and the face where the
//! walks to its samples start.

use crate::atlas::Atlas;
use crate::distortion::Distortion;
use crate::lookup::Lookup;
use crate::relocation::{home, Home};
use glam::{DVec2, DVec3};

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

/// The centre at parametric location `uv`; `None` off the charts or on a face degenerate in 3D.
pub fn centre_at(atlas: &Atlas, uv: DVec2, lookup: Lookup) -> Option<Centre> {
    let chart = atlas.chart_at(uv);
    let home = home(atlas, uv, chart)?;
    let point = lookup.evaluate(atlas, Some(home.face), home.point, chart)?;
    let distortion = atlas.frame.sampling_distortion(&atlas.topology, home.face, home.point);
    if !(distortion.sigma2 > 1e-12 * distortion.sigma1) {
        return None;
    }
    Some(Centre {
        uv,
        chart,
        position: atlas.precision.round_point(point.position),
        normal: atlas.precision.round_point(point.normal),
        distortion,
        home,
    })
}
