//! Bad input gets a typed error naming the problem, never a panic.

use std::sync::Arc;
use uvfeat_core::mesh::{Topology, TriangleMesh};
use uvfeat_core::shapes::plane;
use uvfeat_core::{Atlas, AtlasOptions, UvfeatError};

fn build(positions: &[[f64; 3]], faces: &[[i64; 3]], uvs: &[[f64; 2]]) -> Result<TriangleMesh, UvfeatError> {
    TriangleMesh::new(positions, faces, uvs, faces)
}

#[test]
fn mesh_errors_name_the_problem() {
    let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let uv = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    assert!(matches!(build(&[], &[], &uv), Err(UvfeatError::EmptyMesh { .. })));
    assert!(matches!(build(&p, &[[0, 1, 2]], &[]), Err(UvfeatError::NoUvs)));
    let nan = [[0.0, f64::NAN, 0.0], p[1], p[2]];
    assert!(matches!(build(&nan, &[[0, 1, 2]], &uv), Err(UvfeatError::NonFinitePosition { index: 0, .. })));
    assert!(matches!(build(&p, &[[0, 1, 3]], &uv), Err(UvfeatError::IndexOutOfRange { face: 0, index: 3, .. })));
    assert!(matches!(
        build(&p, &[[0, 1, 2]], &[[0.0, 0.0], [1.5, 0.0], [0.0, 1.0]]),
        Err(UvfeatError::UvOutOfRange { index: 1, .. })
    ));
    let inf_uv = [[0.0, 0.0], [f64::INFINITY, 0.0], [0.0, 1.0]];
    assert!(matches!(build(&p, &[[0, 1, 2]], &inf_uv), Err(UvfeatError::NonFiniteUv { index: 1, .. })));
    let line = [[0.0, 0.0], [0.5, 0.5], [1.0, 1.0]];
    let mesh = build(&p, &[[0, 1, 2]], &line).unwrap();
    assert_eq!(Topology::build(&mesh, 0.0).unwrap_err(), UvfeatError::AllUvDegenerate { faces: 1 });
}

#[test]
fn degenerate_uv_faces_are_skipped_and_counted() {
    let mut shape = plane(1.0, 4);
    let first = shape.uv_faces[0];
    let collapsed = shape.uvs[first[0] as usize];
    // Give face 0 its own collapsed UVs: zero area, the rest of the mesh is intact.
    let base = shape.uvs.len() as i64;
    shape.uvs.extend([collapsed; 3]);
    shape.uv_faces[0] = [base, base + 1, base + 2];
    let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
    let topology = Topology::build(&mesh, 0.0).unwrap();
    assert_eq!(topology.diagnostics.degenerate_uv_faces, 1);
    assert_eq!(topology.face_chart[0], -1);
}

#[test]
fn resolution_and_frame_errors() {
    let shape = plane(1.0, 4);
    let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
    let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
    let zero = AtlasOptions { resolution: 0, ..AtlasOptions::default() };
    assert!(matches!(Atlas::new(topology.clone(), &mesh.positions, &zero), Err(UvfeatError::InvalidResolution { .. })));
    let huge = AtlasOptions { resolution: 30_000, memory_budget: 1 << 30, ..AtlasOptions::default() };
    let err = Atlas::new(topology.clone(), &mesh.positions, &huge).unwrap_err();
    assert!(matches!(err, UvfeatError::ResolutionTooLarge { needed_mib, .. } if needed_mib > 60_000), "{err}");
    let mut atlas =
        Atlas::new(topology, &mesh.positions, &AtlasOptions { resolution: 64, ..Default::default() }).unwrap();
    let err = atlas.update(&mesh.positions[1..]).unwrap_err();
    assert_eq!(err, UvfeatError::FrameVertexCount { expected: mesh.positions.len(), got: mesh.positions.len() - 1 });
}
