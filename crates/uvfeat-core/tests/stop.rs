//! A stop request is process-wide, so its tests run in a binary of their own: a stage built on
//! first use and cut short by a stop is not kept, and the next use builds it whole.

use std::sync::Arc;
use uvfeat_core::mesh::{Topology, TriangleMesh};
use uvfeat_core::raster::Surface;
use uvfeat_core::shapes::torus;
use uvfeat_core::{cancel, Atlas, AtlasOptions};

#[test]
fn a_stopped_first_use_keeps_nothing_and_the_next_builds_it_whole() {
    let shape = torus(2.0, 0.5, 64, 32);
    let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
    let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
    let options = AtlasOptions { resolution: 128, ..AtlasOptions::default() };
    let eager = Atlas::new(topology.clone(), &mesh.positions, &options).unwrap();
    let deferred =
        Atlas::new(topology, &mesh.positions, &AtlasOptions { coverage_on_first_use: true, ..options }).unwrap();

    cancel::request();
    let stopped = (deferred.coverage().chart.clone(), deferred.surfels(Surface::Smooth).n_levels());
    cancel::clear();
    assert!(stopped.0.iter().all(|&c| c < 0), "a stopped rasterisation shows no chart");
    assert_eq!(stopped.1, 0, "a stopped pyramid has no level");

    assert_eq!(deferred.coverage().chart, eager.coverage().chart);
    assert_eq!(deferred.coverage().face, eager.coverage().face);
    assert_eq!(deferred.surfels(Surface::Smooth).n_levels(), eager.surfels(Surface::Smooth).n_levels());
}
