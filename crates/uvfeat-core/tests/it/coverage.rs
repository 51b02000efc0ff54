//! DESIGN.md §3.2: the coverage check grows the sampling domain until it covers the ball, and no
//! further where the ball holds a whole tube and the rays come back round it.

use crate::support::atlas;
use glam::DVec3;
use std::f64::consts::TAU;
use uvfeat_core::features::Feature;
use uvfeat_core::lookup::Lookup;
use uvfeat_core::sampling::{centre_at, disk_pattern, gather_covering, Centre, Overlaps, Placement, MAX_MARGIN};
use uvfeat_core::settings::ComputeSettings;
use uvfeat_core::shapes::torus;
use uvfeat_core::Atlas;

const MAJOR: f64 = 2.0;
const MINOR: f64 = 0.5;

/// Area of the torus `(MAJOR, MINOR)` inside the ball of `radius` around `p` (midpoint rule).
fn torus_area_in_ball(p: DVec3, radius: f64) -> f64 {
    let n = 2000;
    let step = TAU / n as f64;
    let mut area = 0.0;
    for a in 0..n {
        let phi = (a as f64 + 0.5) * step;
        for b in 0..n {
            let psi = (b as f64 + 0.5) * step;
            let ring = MAJOR + MINOR * psi.cos();
            let q = DVec3::new(ring * phi.cos(), ring * phi.sin(), MINOR * psi.sin());
            if q.distance(p) < radius {
                area += MINOR * ring * step * step;
            }
        }
    }
    area
}

/// The centre at the texel whose surface point is closest to `target`.
fn centre_near(atlas: &Atlas, target: DVec3) -> Centre {
    let side = atlas.resolution();
    (0..side * side)
        .filter(|&t| atlas.coverage().chart[t] >= 0)
        .filter_map(|t| centre_at(atlas, atlas.texel_centre(t), Lookup::Triangle))
        .min_by(|a, b| a.position.distance(target).total_cmp(&b.position.distance(target)))
        .expect("a texel on the torus")
}

/// A ball of radius 1.2 around the top of a tube of diameter 1 holds the tube's whole cross-section,
/// so the rays around the tube never leave it: before the rays were stopped where they came back
/// round, those directions grew to the largest margin and sampled the tube twice over.
#[test]
fn the_domain_stops_growing_where_the_rays_come_back_round_a_tube() {
    let atlas = atlas(&torus(MAJOR, MINOR, 96, 48), 256);
    let centre = centre_near(&atlas, DVec3::new(-MAJOR, 0.0, MINOR));
    let radius = 1.2;
    let mut settings = ComputeSettings::new(vec![Feature::MeanCurvature], radius);
    settings.overlaps = Overlaps::Drop;
    let sampler = settings.sampler();
    let pattern = disk_pattern(4096, 7, 0);
    let mut samples = Vec::new();
    let (_, reach) = gather_covering(&atlas, &centre, &pattern, Placement::new(0.0, 0.0), &sampler, true, &mut samples);

    let margins: Vec<f64> = (0..16).map(|k| reach.margin(k)).collect();
    let largest = margins.iter().copied().fold(0.0, f64::max);
    assert!(largest > 1.2 * settings.margin, "the domain should grow around the tube: {margins:?}");
    assert!(largest < 0.75 * MAX_MARGIN, "the domain grew past the loop round the tube: {margins:?}");

    let gathered: f64 = samples.iter().map(|s| s.area).sum();
    let exact = torus_area_in_ball(centre.position, radius);
    assert!((gathered / exact - 1.0).abs() < 0.03, "area {gathered} vs {exact}, margins {margins:?}");
}
