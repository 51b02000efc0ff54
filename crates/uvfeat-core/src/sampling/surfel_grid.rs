//! The atlas resolution the surfel sums at the vertices are built at (DESIGN.md §1.4.9): the
//! coarsest grid whose pyramid still holds the level each face's balls ask for.
//!
//! A ball sums the pyramid level that puts about its surfels per ball in it where a finest surfel is
//! as long as the face's texels along their longer side ([`surfel_level`]). A grid of half the
//! width builds its surfels in about a quarter of the time, and its level `k` is the wider grid's
//! level `k + 1`: every face that asks for level 1 or coarser sums the same surfels on it. Only the
//! faces that ask for the wider grid's finest level lose, to a quarter of their surfels.

use super::surfels::{level_side, surfel_level};
use crate::distortion::Distortion;
use crate::mesh::{Jacobian, Topology};
use glam::DVec3;
use rayon::prelude::*;

/// The coarsest surfel grid [`surfel_grid_width`] gives: below it a chart of a scan's atlas spans
/// few texels.
const SMALLEST_GRID: usize = 128;

/// The share of the surface that may sum one level coarser than its balls ask for on a grid of
/// half the width. On the shared meshes of fewer than 300 charts half the grid moved H and K by at
/// most 0.04 % of their range in 0.35-0.75x the time; on the 1,119-chart dragon, whose small
/// charts leave many small surfels, it costs more (DESIGN.md §1.4.9).
const COARSER_SHARE: f64 = 0.25;

/// What the grid rule reads of one face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceScale {
    /// Area in object units squared.
    pub area: f64,
    /// Area of its UV triangle (of the unit square).
    pub uv_area: f64,
    /// Object length of one uv unit along the face's longer direction: the largest singular value
    /// of its Jacobian (a texel of a `W`² grid is `sigma_1 / W` long).
    pub sigma1: f64,
}

impl FaceScale {
    /// The scale of a face with corners `positions` at `uvs`; `None` where the UV triangle is
    /// degenerate.
    pub fn new(positions: [DVec3; 3], uvs: [glam::DVec2; 3]) -> Option<Self> {
        let jacobian = Jacobian::of_triangle(positions, uvs)?;
        let (d1, d2) = (uvs[1] - uvs[0], uvs[2] - uvs[0]);
        Some(Self {
            area: 0.5 * (positions[1] - positions[0]).cross(positions[2] - positions[0]).length(),
            uv_area: 0.5 * d1.perp_dot(d2).abs(),
            sigma1: Distortion::from_metric(jacobian.metric()).sigma1,
        })
    }

    /// The side of the square a uv unit of the face counts as in the choice of a level
    /// ([`level_side`]).
    pub fn level_side(&self) -> f64 {
        level_side(self.sigma1, (self.area / self.uv_area).sqrt())
    }
}

/// The surfel grid for balls of `radius` summed over about `per_ball` surfels on the mesh of
/// `topology` at the input vertices' `positions` ([`grid_width`] of its faces); `largest` where the
/// positions are not one finite row per input vertex (the computation names the problem).
pub fn surfel_grid_width(
    topology: &Topology,
    positions: &[DVec3],
    radius: f64,
    per_ball: f64,
    largest: usize,
) -> usize {
    if positions.len() != topology.vertex_ids.len() {
        return largest;
    }
    let position = |v: u32| positions[topology.representative[v as usize] as usize];
    let faces: Vec<FaceScale> = (0..topology.faces.len())
        .into_par_iter()
        .filter(|&f| topology.face_chart[f] >= 0)
        .filter_map(|f| FaceScale::new(topology.faces[f].map(position), topology.corner_uvs(f)))
        .collect();
    // A NaN area makes the grid `largest`.
    grid_width(&faces, radius, per_ball, largest)
}

/// The surfel grid, a power of two from 128 up to `largest`, for balls of `radius` summed over
/// about `per_ball` surfels on `faces`: the smallest whose finest surfels, of the mean size, put at
/// least `per_ball` in a plane's ball, halved while at most [`COARSER_SHARE`] of the surface asks for
/// its finest level. `largest` where the areas, the radius or `per_ball` are not positive and finite.
pub fn grid_width(faces: &[FaceScale], radius: f64, per_ball: f64, largest: usize) -> usize {
    let surface_area: f64 = faces.iter().map(|f| f.area).sum();
    let uv_area: f64 = faces.iter().map(|f| f.uv_area).sum();
    let needed = (per_ball * surface_area / (std::f64::consts::PI * radius * radius * uv_area)).sqrt();
    if !(needed.is_finite() && needed > 0.0) {
        return largest;
    }
    let mut width = SMALLEST_GRID.min(largest);
    while (width as f64) < needed && width < largest {
        width *= 2;
    }
    let asking_finest = |width: usize| -> f64 {
        let w = width as f64;
        faces
            .par_iter()
            .filter(|f| surfel_level(usize::MAX, f.level_side() / w, radius, per_ball) == 0)
            .map(|f| f.area)
            .sum()
    };
    while width > SMALLEST_GRID && asking_finest(width) <= COARSER_SHARE * surface_area {
        width /= 2;
    }
    width.min(largest)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;
    use std::f64::consts::PI;

    /// The default surfels per ball.
    const PER_BALL: f64 = 256.0;

    /// `n` equal faces of a unit sphere's area on half the unit square, the `stretched` share of
    /// them four times as long as wide (at the same area: twice the longer side of the others,
    /// which counts as a square `sqrt(2)` times theirs, [`level_side`]).
    fn sphere_faces(n: usize, stretched: f64) -> Vec<FaceScale> {
        let (area, uv_area) = (4.0 * PI / n as f64, 0.5 / n as f64);
        let side = (area / uv_area).sqrt();
        (0..n)
            .map(|i| {
                let long = (i as f64) < stretched * n as f64;
                FaceScale { area, uv_area, sigma1: if long { 2.0 * side } else { side } }
            })
            .collect()
    }

    #[test]
    fn the_grid_puts_the_target_in_a_ball_of_the_faces_asking_for_the_finest_level() {
        // Texels of the mean size are sqrt(8 pi) / W long. A face asks for level 0 of a grid of
        // width W when log2(W r sqrt(pi / 256) / sigma_1) rounds to 0 or below.
        let uniform = sphere_faces(100, 0.0);
        let asks_finest =
            |width: usize, r: f64, sigma1: f64| surfel_level(usize::MAX, sigma1 / width as f64, r, PER_BALL) == 0;
        let side = (8.0 * PI).sqrt();
        for (r, expected) in [(1.0, 128), (0.2, 256), (0.15, 256), (0.1, 512), (0.05, 512)] {
            let width = grid_width(&uniform, r, PER_BALL, 512);
            assert_eq!(width, expected, "r = {r}");
            // The grid's finest level is asked for, or it is the smallest or largest grid.
            assert!(width == 128 || width == 512 || asks_finest(width, r, side), "r = {r}");
            // A grid twice as wide would be summed one level coarser everywhere.
            assert!(width == 512 || !asks_finest(2 * width, r, side), "r = {r}");
        }
    }

    #[test]
    fn the_grid_stays_where_more_than_a_quarter_of_the_surface_asks_for_its_finest_level() {
        // At r = 0.15 the mean-size faces ask for level 1 of the 512² grid and the faces stretched
        // 4 : 1 for its level 0.
        let side = (8.0 * PI).sqrt();
        assert_eq!(surfel_level(usize::MAX, side / 512.0, 0.15, PER_BALL), 1);
        assert_eq!(surfel_level(usize::MAX, 2.0_f64.sqrt() * side / 512.0, 0.15, PER_BALL), 0);
        assert_eq!(grid_width(&sphere_faces(100, 0.2), 0.15, PER_BALL, 512), 256);
        assert_eq!(grid_width(&sphere_faces(100, 0.3), 0.15, PER_BALL, 512), 512);
    }

    #[test]
    fn a_texel_counts_as_the_square_of_its_area_up_to_a_stretch_of_two() {
        // 1.5 : 1 and 2 : 1 at unit area: the unit square.
        for stretch in [1.0, 1.5, 2.0] {
            assert!((level_side(f64::sqrt(stretch), 1.0) - 1.0).abs() < 1e-12, "{stretch}");
        }
        // 8 : 1 (sides sqrt(8) and 1 / sqrt(8)): a square of side 2, four times the area's.
        assert!((level_side(8.0_f64.sqrt(), 1.0) - 2.0).abs() < 1e-12);
        let side = (8.0 * PI).sqrt();
        assert_eq!(FaceScale { area: 1.0, uv_area: 1.0 / (side * side), sigma1: 1.2 * side }.level_side(), side);
    }

    #[test]
    fn more_surfels_per_ball_take_a_wider_grid() {
        // The mean-size grid is sqrt(8 n) / r texels wide for n surfels per ball.
        let uniform = sphere_faces(100, 0.0);
        assert_eq!(grid_width(&uniform, 0.2, 64.0, 512), 128);
        assert_eq!(grid_width(&uniform, 0.2, PER_BALL, 512), 256);
        assert_eq!(grid_width(&uniform, 0.2, 1024.0, 512), 512);
    }

    #[test]
    fn a_degenerate_mesh_or_radius_takes_the_largest_grid() {
        let faces = sphere_faces(10, 0.0);
        assert_eq!(grid_width(&faces, f64::NAN, PER_BALL, 1024), 1024);
        assert_eq!(grid_width(&[], 0.2, PER_BALL, 1024), 1024);
        assert_eq!(grid_width(&faces, 1.0, PER_BALL, 64), 64);
        assert_eq!(grid_width(&faces, 0.2, 0.0, 1024), 1024);
    }

    #[test]
    fn a_face_scale_is_its_jacobian_s() {
        let uvs = [DVec2::ZERO, DVec2::new(0.1, 0.0), DVec2::new(0.0, 0.1)];
        let positions = [DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 0.0, 0.5)];
        let scale = FaceScale::new(positions, uvs).unwrap();
        assert!((scale.sigma1 - 20.0).abs() < 1e-12 && (scale.area - 0.5).abs() < 1e-12);
        assert!((scale.uv_area - 0.005).abs() < 1e-15);
        assert_eq!(FaceScale::new(positions, [DVec2::ZERO; 3]), None);
    }
}
