//! The features of one vertex from its object-space neighbourhood: the samples are the
//! neighbourhood's vertices, fed to the *same* weighted sums and estimators as the parametric
//! samples, so a comparison measures the sampling and nothing else.

use super::connectivity::Connectivity;
use super::disk_area::{clipped_disk, vertex_disk};
use super::edge_paths::EdgePaths;
use super::exact_geodesic::ExactGeodesic;
use super::geometry::Geometry;
use super::neighbourhood::euclidean_neighbourhood;
use super::stamped::StampedValues;
use super::ReferenceGaussian;
use crate::features::{estimate, quadric_fit, CurvatureMethod, EstimatorSettings, NeighbourhoodStats, StatsSettings};
use crate::sampling::{arc_distance, Sample};

/// Everything the per-vertex estimation reads.
pub(super) struct Context<'a> {
    pub connectivity: &'a Connectivity,
    pub geometry: &'a Geometry,
    pub stats: StatsSettings,
    pub estimators: EstimatorSettings,
    /// How the geodesic disk is measured; `None` when no requested feature needs it.
    pub disk: Option<ReferenceGaussian>,
}

/// Per-thread buffers, reused from vertex to vertex.
pub(super) struct Scratch {
    reached: StampedValues,
    samples: Vec<Sample>,
    disk: DiskSearch,
}

enum DiskSearch {
    None,
    EdgePaths(EdgePaths),
    Exact(ExactGeodesic, StampedValues),
}

impl Scratch {
    pub fn new(context: &Context) -> Self {
        let n = context.connectivity.n_vertices();
        let disk = match context.disk {
            Some(ReferenceGaussian::GeodesicArea) => DiskSearch::EdgePaths(EdgePaths::new(n)),
            Some(ReferenceGaussian::ExactGeodesicArea) => {
                DiskSearch::Exact(ExactGeodesic::new(n), StampedValues::new(context.connectivity.faces.len()))
            }
            _ => DiskSearch::None,
        };
        Self { reached: StampedValues::new(n), samples: Vec::new(), disk }
    }
}

/// Every feature (in [`crate::features::Feature::ALL`] order) at welded vertex `centre`, and the
/// number of samples (neighbourhood vertices other than the centre).
///
/// Samples are the vertices `v` of the Euclidean neighbourhood with `q_i = v`, `n_i` the vertex
/// normal and `dA_i = A_v` (mixed Voronoi area); `rho_i = |v - p| > 1e-6 r` as on the parametric
/// side. The geodesic disk, when K needs it, comes from edge paths and vertex areas (paper) or
/// from exact geodesics and clipped triangles, searched up to `r` plus the longest edge of the
/// neighbourhood so that every corner of a clipped triangle has its exact distance.
pub(super) fn vertex_estimate(centre: u32, context: &Context, scratch: &mut Scratch) -> ([f64; 9], u32) {
    let geometry = context.geometry;
    let r = context.stats.radius;
    euclidean_neighbourhood(centre, r, context.connectivity, &geometry.positions, &mut scratch.reached);
    let (p, n) = (geometry.positions[centre as usize], geometry.normals[centre as usize]);
    scratch.samples.clear();
    let mut longest_edge = 0.0f64;
    for &v in scratch.reached.touched() {
        let distance = scratch.reached.get(v);
        if distance >= r {
            continue;
        }
        longest_edge = longest_edge.max(geometry.longest_edge[v as usize]);
        if distance <= 1e-6 * r {
            continue; // the centre itself
        }
        let q = geometry.positions[v as usize];
        let sin_alpha = n.dot(q - p) / distance;
        scratch.samples.push(Sample {
            position: q,
            normal: geometry.normals[v as usize],
            area: geometry.areas[v as usize],
            distance,
            sin_alpha,
            geodesic: arc_distance(distance, sin_alpha),
            pattern_index: 0,
        });
    }
    let mut stats = NeighbourhoodStats::default();
    stats.accumulate(&scratch.samples, n, &context.stats);
    match &mut scratch.disk {
        DiskSearch::None => {}
        DiskSearch::EdgePaths(paths) => {
            paths.run(centre, r, context.connectivity, &geometry.positions);
            stats.geodesic_disk = vertex_disk(&paths.distances, &geometry.areas, r);
        }
        DiskSearch::Exact(search, faces_seen) => {
            let bound = r + longest_edge;
            search.run(centre, bound, context.connectivity, geometry);
            stats.geodesic_disk = clipped_disk(search, context.connectivity, geometry, r, bound, faces_seen);
        }
    }
    let fit = (context.estimators.method == CurvatureMethod::Fit)
        .then(|| quadric_fit(p, n, &scratch.samples, r, false))
        .flatten();
    (estimate(&stats, fit.as_ref(), &context.estimators).values, scratch.samples.len() as u32)
}
