//! Shortest paths along mesh edges (Dijkstra): the geodesic distance of the paper-style
//! per-vertex geodesic-area K (DESIGN.md §5.1 "as printed"; the paper does not say which distance its
//! reference used, this is the usual cheap choice).
//!
//! Edge paths zig-zag, so they overestimate the surface distance by a factor that depends on the
//! direction and the triangulation, not on the resolution (up to `sqrt 2` on a grid of right
//! triangles): the disk looks too small and K comes out far too high even on a plane (K = 280 at
//! r = 0.1 and 50 at r = 0.25 on a 64 x 64 grid of the unit square; DESIGN.md §3.5 measured +22 on
//! unit icospheres at r = 0.3). Use it to reproduce the paper's reference; the exact-geodesic
//! variant is the accurate one.

use super::connectivity::Connectivity;
use super::stamped::StampedValues;
use glam::DVec3;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Dijkstra's search with reusable buffers.
#[derive(Debug, Clone)]
pub struct EdgePaths {
    /// Distances found by the last search; final where below its bound.
    pub distances: StampedValues,
    queue: BinaryHeap<Reverse<(u64, u32)>>,
}

impl EdgePaths {
    /// Buffers for a mesh of `n_vertices`.
    pub fn new(n_vertices: usize) -> Self {
        Self { distances: StampedValues::new(n_vertices), queue: BinaryHeap::new() }
    }

    /// Edge-path distances from `source` to every vertex closer than `bound`.
    pub fn run(&mut self, source: u32, bound: f64, connectivity: &Connectivity, positions: &[DVec3]) {
        self.distances.reset();
        self.queue.clear();
        self.distances.set(source, 0.0);
        // Non-negative floats order like their bit patterns.
        self.queue.push(Reverse((0f64.to_bits(), source)));
        while let Some(Reverse((key, u))) = self.queue.pop() {
            let d = f64::from_bits(key);
            if d >= bound {
                break;
            }
            if d > self.distances.get(u) {
                continue; // a stale entry
            }
            for &v in connectivity.neighbours(u) {
                let candidate = d + positions[u as usize].distance(positions[v as usize]);
                if candidate < self.distances.get(v) {
                    self.distances.set(v, candidate);
                    self.queue.push(Reverse((candidate.to_bits(), v)));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edge_paths_on_a_square_go_round_the_missing_diagonal() {
        let p = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
        let c = Connectivity::build(&p, &[[0, 1, 3], [1, 2, 3]]).unwrap();
        let mut paths = EdgePaths::new(4);
        paths.run(0, 10.0, &c, &p);
        assert_eq!(paths.distances.get(1), 1.0);
        assert_eq!(paths.distances.get(2), 2.0); // not sqrt(2): no edge 0-2
        paths.run(0, 1.5, &c, &p);
        assert!(paths.distances.get(2) >= 1.5);
    }
}
