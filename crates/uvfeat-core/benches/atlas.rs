//! The stages of building an atlas, one at a time: the once-per-topology pre-processing,
//! the coverage at 1024² (once per topology and resolution), and what every frame rebuilds (the
//! frame's normals, metrics and seam maps; the faces' patches), on the 200K-face lat-long sphere
//! of docs/PEERS.md and the 102K-face lat-long torus. Medians and minima of 40 builds, 2 threads
//! unless RAYON_NUM_THREADS says otherwise.
//!
//!     cargo bench -p uvfeat-core --bench atlas

use std::hint::black_box;
use std::sync::Arc;
use std::time::Instant;
use uvfeat_core::frame::Frame;
use uvfeat_core::mesh::{Topology, TriangleMesh};
use uvfeat_core::raster::{Coverage, FacePatches};
use uvfeat_core::shapes::ShapeMesh;

const BUILDS: usize = 40;

/// Median and minimum milliseconds of `BUILDS` calls of `build`.
fn timed<T>(mut build: impl FnMut() -> T) -> (f64, f64) {
    let mut ms: Vec<f64> = (0..BUILDS)
        .map(|_| {
            let started = Instant::now();
            black_box(build());
            started.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    ms.sort_by(f64::total_cmp);
    (ms[BUILDS / 2], ms[0])
}

fn main() {
    let shapes: [(&str, ShapeMesh); 2] = [
        ("lat-long sphere", uvfeat_core::shapes::uv_sphere(1.0, 448, 224)),
        ("lat-long torus", uvfeat_core::shapes::torus(2.0, 0.5, 320, 160)),
    ];
    println!("{} threads; ms, median / min of {BUILDS} builds", rayon::current_num_threads());
    println!("| mesh | faces | topology | coverage 1024² | frame | patches |");
    println!("|---|---|---|---|---|---|");
    for (name, shape) in shapes {
        let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
        let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
        let frame = Frame::new(&topology, &mesh.positions).unwrap();
        let cells = [
            timed(|| Topology::build(&mesh, 0.0).unwrap()),
            timed(|| Coverage::build(&topology, 1024)),
            timed(|| Frame::new(&topology, &mesh.positions).unwrap()),
            timed(|| FacePatches::new(&topology, &frame)),
        ];
        let cells: Vec<String> = cells.iter().map(|(median, min)| format!("{median:.1} / {min:.1}")).collect();
        println!("| {name} | {} | {} |", mesh.faces.len(), cells.join(" | "));
    }
}
