//! The atlas resolution the surfel sums at the vertices are built at (DESIGN.md §1.4.9): the grid
//! whose finest surfels, of the mean texel size on the charts, put the surfels per ball asked for
//! in a plane's ball of the radius.
//!
//! A ball sums the pyramid level nearest its count ([`surfel_level`](super::surfels::surfel_level)), so on a grid whose width
//! does not follow the radius the count a ball gets lies anywhere between half and twice what it
//! asks for, by where the radius falls between the levels: on powers of two the dragon's time went
//! 0.39 / 0.22 / 0.40 / 0.30 s at r = 3 / 4 / 6 / 8 %, its error the other way. Fitted to the
//! radius, the mean ball sums level 0 at its count at every radius; a grid any finer only costs
//! the build (on the flat facets its level 1 holds the same pieces as level 0 of half the width).

/// The coarsest surfel grid [`surfel_grid_width`] gives.
const SMALLEST_GRID: usize = 64;

/// The widths [`surfel_grid_width`] gives are multiples of this: a ball's count then lies within
/// `(1 +- 8 / W)^2` of the one asked for (12 % at the coarsest grid).
const GRID_STEP: usize = 16;

/// The surfel grid for balls of `radius` summed over about `per_ball` surfels on charts of
/// `surface_area` (object units squared) over `uv_area` of the unit square: the width whose texels
/// of the mean size put `per_ball` in a plane's ball, to the nearest [`GRID_STEP`], from
/// [`SMALLEST_GRID`] up to `largest`. `largest` where the areas, the radius or `per_ball` are not
/// positive and finite.
pub fn surfel_grid_width(surface_area: f64, uv_area: f64, radius: f64, per_ball: f64, largest: usize) -> usize {
    // A texel of a W² grid covers surface_area / (uv_area W²); per_ball of them fill pi r^2.
    let needed = (per_ball * surface_area / (std::f64::consts::PI * radius * radius * uv_area)).sqrt();
    if !(needed.is_finite() && needed > 0.0) {
        return largest;
    }
    let width = (needed / GRID_STEP as f64).round() as usize * GRID_STEP;
    width.clamp(SMALLEST_GRID.min(largest), largest)
}

#[cfg(test)]
mod tests {
    use super::super::surfels::surfel_level;
    use super::*;
    use std::f64::consts::PI;

    /// A unit sphere's area on half the unit square: a texel of a W² grid is `sqrt(8 pi) / W` on
    /// the side, and a plane's ball of radius r holds `r^2 W^2 / 8` of them.
    const SPHERE: (f64, f64) = (4.0 * PI, 0.5);

    #[test]
    fn the_mean_texels_ball_holds_the_surfels_asked_for_on_its_finest_level() {
        // W = sqrt(8 n) / r: 160 at r = 0.2 for n = 128, 106.7 -> 112 at r = 0.3.
        for (r, expected) in [(0.2, 160), (0.3, 112), (0.13, 240)] {
            let width = surfel_grid_width(SPHERE.0, SPHERE.1, r, 128.0, 512);
            assert_eq!(width, expected, "r = {r}");
            let per_ball = r * r * (width * width) as f64 / 8.0;
            assert!((per_ball / 128.0 - 1.0).abs() < 0.15, "r = {r}: {per_ball}");
            assert_eq!(surfel_level(usize::MAX, (8.0 * PI).sqrt() / width as f64, r, 128.0), 0, "r = {r}");
        }
    }

    #[test]
    fn more_surfels_per_ball_take_a_wider_grid() {
        let width = |n: f64| surfel_grid_width(SPHERE.0, SPHERE.1, 0.2, n, 512);
        assert_eq!([width(32.0), width(128.0), width(512.0)], [80, 160, 320]);
    }

    #[test]
    fn the_grid_stays_between_the_smallest_and_the_largest() {
        assert_eq!(surfel_grid_width(SPHERE.0, SPHERE.1, 1.0, 128.0, 512), SMALLEST_GRID);
        assert_eq!(surfel_grid_width(SPHERE.0, SPHERE.1, 0.05, 128.0, 512), 512);
        assert_eq!(surfel_grid_width(SPHERE.0, SPHERE.1, 1.0, 128.0, 32), 32);
    }

    #[test]
    fn a_degenerate_mesh_or_radius_takes_the_largest_grid() {
        assert_eq!(surfel_grid_width(SPHERE.0, SPHERE.1, f64::NAN, 128.0, 1024), 1024);
        assert_eq!(surfel_grid_width(0.0, 0.0, 0.2, 128.0, 1024), 1024);
        assert_eq!(surfel_grid_width(SPHERE.0, 0.0, 0.2, 128.0, 1024), 1024);
        assert_eq!(surfel_grid_width(SPHERE.0, SPHERE.1, 0.2, 0.0, 1024), 1024);
    }
}
