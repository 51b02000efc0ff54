//! How a neighbourhood is integrated: the quadrature (pattern samples or surfels, DESIGN.md §1.4
//! and §1.4.8) and, for the pattern, whether a tile's texels share one located lattice. This is
//! the one place that choice is made: the evaluation, the feature maps, the values at the vertices
//! and the neighbourhood tiles ask [`integration`]. (Within a pattern neighbourhood, the sampler
//! itself takes its fast path for interior samples where `sampling::fast_path_applies`.)

use crate::atlas::Atlas;
use crate::features::{CurvatureMethod, VolumeWeighting};
use crate::sampling::{fast_path_applies, Overlaps, Quadrature, SamplingPath};
use crate::settings::ComputeSettings;

/// The ways a neighbourhood is integrated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integration {
    /// The surfels' moments summed straight into the statistics, with no samples: the surfel
    /// quadrature's integral estimators (exact over whole surfels for H).
    SurfelSums,
    /// Every surfel in the ball as a weighted sample: the surfel quadrature with the quadric fit,
    /// which needs the samples rather than their sums.
    SurfelSamples,
    /// One located lattice shared by the texels of a group in a tile (`sampling = "shared"`): the
    /// integral estimators over the whole pattern at once, distance weighting, overlaps kept, no
    /// adaptive stages, batch errors or geodesic distances, and the fast path's choices.
    SharedLattice,
    /// The sample pattern around each point on its own (adaptive stages, standard errors, the fit
    /// and every other choice of the pattern).
    PatternPerPoint,
}

impl Integration {
    /// Whether it reads the atlas's surfel pyramid.
    pub fn uses_surfels(self) -> bool {
        matches!(self, Integration::SurfelSums | Integration::SurfelSamples)
    }
}

/// How `settings` integrate each neighbourhood on `atlas`.
pub fn integration(atlas: &Atlas, settings: &ComputeSettings) -> Integration {
    match settings.quadrature {
        Quadrature::Surfels if settings.method == CurvatureMethod::Integral => Integration::SurfelSums,
        Quadrature::Surfels => Integration::SurfelSamples,
        Quadrature::Pattern if shared_lattice_serves(atlas, settings) => Integration::SharedLattice,
        Quadrature::Pattern => Integration::PatternPerPoint,
    }
}

/// The shared lattice's conditions; the cheap ones first, since [`integration`] is asked per point.
fn shared_lattice_serves(atlas: &Atlas, settings: &ComputeSettings) -> bool {
    if settings.sampling != SamplingPath::Shared
        || settings.adaptive
        || settings.standard_errors
        || settings.method != CurvatureMethod::Integral
        || settings.volume_weighting != VolumeWeighting::Distance
        || settings.overlaps != Overlaps::Keep
    {
        return false;
    }
    let sampler = settings.sampler();
    fast_path_applies(atlas, &sampler) && !sampler.with_geodesic
}
