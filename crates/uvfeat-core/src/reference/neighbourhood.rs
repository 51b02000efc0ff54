//! The reference neighbourhood of a vertex (DESIGN.md §5.1): the vertices reached by a breadth-first
//! search from it over edges whose endpoints both lie within the Euclidean radius.

use super::connectivity::Connectivity;
use super::stamped::StampedValues;
use glam::DVec3;

/// Runs the search from `centre` and leaves in `reached` the distance `|v - p|` of every vertex it
/// looked at; those below `radius` (the centre included, at 0) form the neighbourhood, the others
/// are its rim (looked at, not expanded). Reached in breadth-first order.
///
/// Unlike a plain ball query, the search follows the surface: a part of the mesh that enters the
/// ball without a path inside it (the other side of a thin wall) is not included.
pub fn euclidean_neighbourhood(
    centre: u32,
    radius: f64,
    connectivity: &Connectivity,
    positions: &[DVec3],
    reached: &mut StampedValues,
) {
    let p = positions[centre as usize];
    reached.reset();
    reached.set(centre, 0.0);
    let mut next = 0;
    while let Some(&u) = reached.touched().get(next) {
        next += 1;
        if reached.get(u) >= radius {
            continue;
        }
        for &v in connectivity.neighbours(u) {
            if !reached.contains(v) {
                reached.set(v, positions[v as usize].distance(p));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn search_stops_at_the_radius_and_does_not_jump_gaps() {
        // A strip of triangles along x, and a separate small triangle right above vertex 0.
        let xy = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let p = [
            xy(0.0, 0.0, 0.0),
            xy(1.0, 0.0, 0.0),
            xy(2.0, 0.0, 0.0),
            xy(3.0, 0.0, 0.0),
            xy(0.5, 0.5, 0.0),
            xy(1.5, 0.5, 0.0),
            xy(2.5, 0.5, 0.0),
            xy(0.0, 0.0, 0.2),
            xy(0.2, 0.0, 0.2),
            xy(0.0, 0.2, 0.2),
        ];
        let faces = [[0, 1, 4], [1, 5, 4], [1, 2, 5], [2, 6, 5], [2, 3, 6], [7, 8, 9]];
        let c = Connectivity::build(&p, &faces).unwrap();
        let mut reached = StampedValues::new(p.len());
        euclidean_neighbourhood(0, 1.2, &c, &p, &mut reached);
        let mut inside: Vec<u32> = reached.touched().iter().copied().filter(|&v| reached.get(v) < 1.2).collect();
        inside.sort_unstable();
        assert_eq!(inside, [0, 1, 4]);
        assert!(reached.contains(2) && reached.contains(5), "the rim is looked at");
        assert!(!reached.contains(3) && !reached.contains(7), "nothing beyond the rim or across the gap");
    }
}
