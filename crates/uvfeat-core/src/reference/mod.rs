//! The object-space reference (DESIGN.md §5.1): every feature of DESIGN.md §2 estimated per vertex from the
//! mesh itself, in parallel over vertices, to measure the parametric method against.
//!
//! - neighbourhood of vertex `p`: the vertices reached from `p` over edges whose endpoints lie
//!   within Euclidean distance `r` ([`neighbourhood`]);
//! - samples: those vertices except `p`, weighted by their mixed Voronoi areas ([`voronoi`]), fed
//!   to the same weighted sums and estimators as the parametric samples
//!   ([`crate::features::NeighbourhoodStats`], [`crate::features::estimate`]), with the same
//!   names, conventions and departures (ratio estimator for H, `dA rho^2` moments);
//! - Gaussian curvature: the curvature moments (default), the paper's geodesic-disk area as the
//!   sum of vertex areas within edge-path distance `r`, or the accurate variant with exact
//!   polyhedral geodesics and clipped triangle areas ([`ReferenceGaussian`]).
//!
//! Building the [`ReferenceMesh`] (welding, half-edges, adjacency) is the paper's half-edge
//! construction and is left out of its timings; [`ReferenceMesh::compute`] is what they time.

mod connectivity;
mod disk_area;
mod disk_clip;
mod edge_paths;
mod exact_geodesic;
mod geometry;
mod neighbourhood;
mod stamped;
mod vertex_estimate;
mod voronoi;

pub use connectivity::{Connectivity, NO_TWIN};
pub use disk_area::sublevel_fraction;
pub use disk_clip::triangle_disk_area;
pub use edge_paths::EdgePaths;
pub use exact_geodesic::{ExactGeodesic, FieldSample};
pub use geometry::{flat_triangle, Geometry};
pub use neighbourhood::euclidean_neighbourhood;
pub use stamped::StampedValues;
pub use voronoi::{mixed_voronoi_areas, mixed_voronoi_corners};

use crate::cancel;
use crate::error::{Result, UvfeatError};
use crate::features::{CurvatureMethod, Feature, GaussianMethod, VolumeWeighting};
use crate::mesh::{checked_indices, checked_positions};
use crate::settings::ComputeSettings;
use glam::DVec3;
use rayon::prelude::*;
use vertex_estimate::{vertex_estimate, Context, Scratch};

/// How the reference estimates Gaussian curvature (and with it k1, k2, shape index, curvedness).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ReferenceGaussian {
    /// Normal-curvature moments, as the parametric default (DESIGN.md §2.5b).
    #[default]
    Moments,
    /// The paper's reference: `GA = sum A_v` over vertices within edge-path (Dijkstra) distance
    /// `r`. Strongly biased (edge paths overestimate distances); for reproduction only.
    GeodesicArea,
    /// Exact polyhedral geodesic distances and triangle areas clipped at distance `r`.
    ExactGeodesicArea,
}

crate::choice!(
    ReferenceGaussian,
    "gaussian_method",
    [
        ("moments", ReferenceGaussian::Moments),
        ("geodesic_area", ReferenceGaussian::GeodesicArea),
        ("exact_geodesic_area", ReferenceGaussian::ExactGeodesicArea),
    ]
);

/// A reference computation request.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceSettings {
    /// Features to return.
    pub features: Vec<Feature>,
    /// Neighbourhood radius `r` in object units.
    pub radius: f64,
    /// Gaussian-curvature method.
    pub gaussian_method: ReferenceGaussian,
    /// Weighting of the volume integrands (distance, as the parametric default).
    pub volume_weighting: VolumeWeighting,
    /// Inner exclusion of bending energy and curvature moments, as a fraction of `r` (0.1).
    pub rho_min_fraction: f64,
    /// Shape index is NaN where curvedness `< flat_tol / r` (1e-3).
    pub flat_tol: f64,
    /// Curvature estimators: integral (default) or the quadric fit over the neighbourhood's vertices.
    pub method: CurvatureMethod,
}

impl ReferenceSettings {
    /// The parametric defaults (DESIGN.md §1.10) for `features` at `radius`.
    pub fn new(features: Vec<Feature>, radius: f64) -> Self {
        let defaults = ComputeSettings::new(features, radius);
        Self {
            gaussian_method: ReferenceGaussian::Moments,
            volume_weighting: defaults.volume_weighting,
            rho_min_fraction: defaults.rho_min_fraction,
            flat_tol: defaults.flat_tol,
            method: defaults.method,
            features: defaults.features,
            radius,
        }
    }

    /// The same request in the parametric settings, whose validation and estimator settings the
    /// reference shares.
    fn as_compute(&self) -> ComputeSettings {
        let mut s = ComputeSettings::new(self.features.clone(), self.radius);
        s.gaussian_method = match self.gaussian_method {
            ReferenceGaussian::Moments => GaussianMethod::Moments,
            _ => GaussianMethod::GeodesicArea,
        };
        s.volume_weighting = self.volume_weighting;
        s.rho_min_fraction = self.rho_min_fraction;
        s.flat_tol = self.flat_tol;
        s.method = self.method;
        s
    }
}

/// Per-vertex reference values.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceValues {
    /// The features, in the order asked for.
    pub features: Vec<Feature>,
    /// (n_features) arrays of one value per queried vertex; NaN where the neighbourhood holds no
    /// vertex besides the centre (radius below the edge length).
    pub values: Vec<Vec<f64>>,
    /// Samples (neighbourhood vertices other than the centre) per queried vertex.
    pub samples: Vec<u32>,
}

/// A mesh prepared for the reference: validated, welded, with half-edge connectivity.
#[derive(Debug, Clone)]
pub struct ReferenceMesh {
    positions: Vec<DVec3>,
    connectivity: Connectivity,
}

impl ReferenceMesh {
    /// Validates the arrays and builds the connectivity (the untimed half-edge step).
    /// Zero-area faces are kept (a geodesic crosses them like a slit) unless all are.
    ///
    /// # Errors
    /// [`UvfeatError::EmptyMesh`], [`UvfeatError::NonFinitePosition`],
    /// [`UvfeatError::IndexOutOfRange`], [`UvfeatError::DegenerateMesh`].
    pub fn new(positions: &[[f64; 3]], faces: &[[i64; 3]]) -> Result<Self> {
        if positions.is_empty() || faces.is_empty() {
            return Err(UvfeatError::EmptyMesh { vertices: positions.len(), faces: faces.len() });
        }
        let positions = checked_positions(positions)?;
        let faces = checked_indices(faces, positions.len(), "vertex")?;
        let connectivity = Connectivity::build(&positions, &faces)?;
        let corners = |t: &[u32; 3]| t.map(|v| positions[v as usize]);
        if !faces.iter().any(|t| geometry::triangle_area(corners(t)) > 0.0) {
            return Err(UvfeatError::DegenerateMesh { faces: faces.len() });
        }
        Ok(Self { positions, connectivity })
    }

    /// The welded connectivity.
    pub fn connectivity(&self) -> &Connectivity {
        &self.connectivity
    }

    /// Exact polyhedral geodesic distances from input vertex `source` to every input vertex, up
    /// to `max_distance` (`+inf` beyond it and off `source`'s connected part).
    ///
    /// # Errors
    /// [`UvfeatError::InvalidParameter`] for a vertex that does not exist or a `max_distance`
    /// that is not positive.
    pub fn geodesic_distances(&self, source: i64, max_distance: f64) -> Result<Vec<f64>> {
        let n_input = self.positions.len();
        if source < 0 || source as usize >= n_input {
            return Err(UvfeatError::InvalidParameter {
                name: "source",
                reason: format!("vertex {source} does not exist (the mesh has {n_input})"),
            });
        }
        if !(max_distance > 0.0) {
            return Err(UvfeatError::InvalidParameter {
                name: "max_distance",
                reason: format!("must be a positive length (inf for no limit), got {max_distance}"),
            });
        }
        let geometry = Geometry::new(&self.connectivity, &self.positions);
        let mut search = ExactGeodesic::new(self.connectivity.n_vertices());
        let ids = &self.connectivity.vertex_ids;
        search.run(ids[source as usize], max_distance, &self.connectivity, &geometry);
        Ok(ids
            .iter()
            .map(|&g| search.distances.get(g))
            .map(|d| if d <= max_distance { d } else { f64::INFINITY })
            .collect())
    }

    /// The features of `settings` at every input vertex (`vertices = None`) or at the listed
    /// input vertices, in parallel over vertices (`RAYON_NUM_THREADS` caps the threads; results
    /// do not depend on it).
    ///
    /// # Errors
    /// [`UvfeatError::InvalidParameter`] for bad settings or vertex indices.
    pub fn compute(&self, settings: &ReferenceSettings, vertices: Option<&[i64]>) -> Result<ReferenceValues> {
        let compute = settings.as_compute();
        compute.validate()?;
        let n_input = self.positions.len();
        if let Some(bad) = vertices.and_then(|list| list.iter().find(|&&v| v < 0 || v as usize >= n_input)) {
            return Err(UvfeatError::InvalidParameter {
                name: "vertices",
                reason: format!("vertex {bad} does not exist (the mesh has {n_input})"),
            });
        }
        let geometry = Geometry::new(&self.connectivity, &self.positions);
        let needs_disk = settings.features.iter().any(|f| {
            matches!(
                f,
                Feature::GaussianCurvature | Feature::K1 | Feature::K2 | Feature::ShapeIndex | Feature::Curvedness
            )
        });
        let context = Context {
            connectivity: &self.connectivity,
            geometry: &geometry,
            stats: compute.stats(),
            estimators: compute.estimators(),
            disk: (needs_disk
                && settings.method == CurvatureMethod::Integral
                && settings.gaussian_method != ReferenceGaussian::Moments)
                .then_some(settings.gaussian_method),
        };
        let ids = &self.connectivity.vertex_ids;
        // Every welded vertex once (seam copies share it), or the queried ones.
        let centres: Vec<u32> = match vertices {
            None => (0..self.connectivity.n_vertices() as u32).collect(),
            Some(list) => list.iter().map(|&v| ids[v as usize]).collect(),
        };
        let results: Vec<([f64; 9], u32)> = centres
            .par_iter()
            .map_init(
                || Scratch::new(&context),
                |scratch, &c| {
                    if cancel::requested() {
                        return ([f64::NAN; 9], 0);
                    }
                    vertex_estimate(c, &context, scratch)
                },
            )
            .collect();
        cancel::check()?;
        let per_query: Vec<usize> = match vertices {
            None => ids.iter().map(|&g| g as usize).collect(),
            Some(list) => (0..list.len()).collect(),
        };
        Ok(ReferenceValues {
            values: settings
                .features
                .iter()
                .map(|f| per_query.iter().map(|&k| results[k].0[f.index()]).collect())
                .collect(),
            samples: per_query.iter().map(|&k| results[k].1).collect(),
            features: settings.features.clone(),
        })
    }
}
