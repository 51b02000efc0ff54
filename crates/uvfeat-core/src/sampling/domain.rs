//! The sampling domain of one centre: where each pattern point lands in the parametric plane (its
//! placement, the per-direction reach and the centre's metric ellipse) and the area it stands for.

use super::centre::Centre;
use super::pattern::Placement;
use super::reach::Reach;
use super::sample::unit_ellipse;
use super::settings::SamplerSettings;
use glam::{DMat2, DVec2};

/// A pattern point's parametric offset from the centre and the factor `m(phi)^2` of its area.
pub(super) struct Offset {
    pub uv: DVec2,
    pub area_scale: f64,
}

/// The offsets of `pattern` placed by `placement`, stretched by `reach`, on the centre's ellipse.
pub(super) fn offsets<'a>(
    centre: &Centre,
    pattern: &'a [DVec2],
    placement: Placement,
    reach: &'a Reach,
    settings: &'a SamplerSettings,
) -> impl Iterator<Item = Offset> + 'a {
    let domain = Domain::new(centre, placement, reach, settings);
    pattern.iter().map(move |&disk| domain.offset(disk))
}

/// The sampling domain of one centre: the pattern's placement, the reach and the metric ellipse,
/// with the sampler's settings.
pub(super) struct Domain<'a> {
    pub ellipse: DMat2,
    pub placement: Placement,
    pub reach: &'a Reach,
    /// The margin of every direction when the reach is uniform.
    pub uniform: Option<f64>,
    pub settings: &'a SamplerSettings,
}

impl<'a> Domain<'a> {
    pub fn new(centre: &Centre, placement: Placement, reach: &'a Reach, settings: &'a SamplerSettings) -> Self {
        let uniform = reach.is_uniform().then(|| reach.margin(0));
        Self { ellipse: unit_ellipse(centre, settings), placement, reach, uniform, settings }
    }

    /// `true` when the parametric `offset` from the centre lies inside the domain (the inverse of
    /// [`Domain::offset`]: `ellipse^-1 offset` within its direction's margin).
    pub fn contains(&self, offset: DVec2) -> bool {
        let w = self.ellipse.inverse() * offset;
        w.length() < self.uniform.unwrap_or_else(|| self.reach.at(w.y.atan2(w.x)))
    }

    /// The offset of the pattern point `disk`.
    #[inline]
    pub fn offset(&self, disk: DVec2) -> Offset {
        let w = self.placement.place(disk);
        let margin = self.uniform.unwrap_or_else(|| self.reach.at(w.y.atan2(w.x)));
        Offset { uv: self.ellipse * (margin * w), area_scale: margin * margin }
    }
}
