//! The centre `p = P(s)` of a neighbourhood: its point, normal and metric, and the face where the
//! walks to its samples start.

use crate::atlas::Atlas;
use crate::distortion::Distortion;
use crate::lookup::Lookup;
use crate::relocation::{home, Home};
use glam::{DVec2, DVec3, Vec3};

/// The centre `p = P(s)` of a neighbourhood.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Centre {
    /// Parametric location `s`.
    pub uv: DVec2,
    /// Chart of `s`.
    pub chart: i32,
    /// `p`.
    pub position: DVec3,
    /// Unit normal at `p`.
    pub normal: DVec3,
    /// The sampler's metric at `s` (see [`crate::frame::Frame::sampling_distortion`]).
    pub distortion: Distortion,
    /// The face containing `s`, where walks to the samples start.
    pub home: Home,
}

/// The centre at parametric location `uv`; `None` off the charts or on a face degenerate in 3D.
pub fn centre_at(atlas: &Atlas, uv: DVec2, lookup: Lookup) -> Option<Centre> {
    let chart = atlas.chart_at(uv);
    centre_from_home(atlas, uv, chart, home(atlas, uv, chart)?, lookup)
}

/// The centre at `uv` of `chart`, whose home face is known.
fn centre_from_home(atlas: &Atlas, uv: DVec2, chart: i32, home: Home, lookup: Lookup) -> Option<Centre> {
    let point = lookup.evaluate(atlas, Some(home.face), home.point, chart)?;
    let distortion = atlas.frame.sampling_distortion(&atlas.topology, home.face, home.point);
    if !(distortion.sigma2 > 1e-12 * distortion.sigma1) {
        return None;
    }
    Some(Centre {
        uv,
        chart,
        position: atlas.precision.round_point(point.position),
        normal: atlas.precision.round_point(point.normal),
        distortion,
        home,
    })
}

/// A texel as a group of the shared lattice sees it (`evaluation/tile.rs`): where its centre lies
/// and its point and normal read from the home face's f32 patch, relative to the patches' origin.
/// Only the group's own centre needs the rest of a [`Centre`] (its f64 point and the sampler's
/// metric): building them for every texel was a tenth of the features (200 ns a texel).
#[derive(Debug, Clone, Copy)]
pub struct TexelPoint {
    /// Parametric location `s`.
    pub uv: DVec2,
    /// Chart of `s`.
    pub chart: i32,
    /// The face containing `s`.
    pub home: Home,
    /// `p`, relative to the patches' origin.
    pub position: Vec3,
    /// Unit normal at `p`.
    pub normal: Vec3,
}

impl Centre {
    /// The centre as a texel point, its point and normal rounded to f32 relative to `origin` (the
    /// patches').
    pub fn texel_point(&self, origin: DVec3) -> TexelPoint {
        TexelPoint {
            uv: self.uv,
            chart: self.chart,
            home: self.home,
            position: (self.position - origin).as_vec3(),
            normal: self.normal.as_vec3(),
        }
    }
}

impl TexelPoint {
    /// The full centre at this texel point ([`centre_at`] without locating its home again).
    pub fn centre(&self, atlas: &Atlas, lookup: Lookup) -> Option<Centre> {
        centre_from_home(atlas, self.uv, self.chart, self.home, lookup)
    }
}

/// The texel point at `uv`: `None` exactly where [`centre_at`] with the triangle lookup is `None`.
pub fn texel_point(atlas: &Atlas, uv: DVec2) -> Option<TexelPoint> {
    let chart = atlas.chart_at(uv);
    let home = home(atlas, uv, chart)?;
    let patch = &atlas.patches().faces[home.face as usize];
    if patch.chart < 0 {
        return None;
    }
    // The sampler's metric is the face's own unless that is more than `SLIVER_ANISOTROPY` times
    // as anisotropic as the smoothed one (`Frame::sampling_distortion`), so where the face's
    // passes `centre_at`'s test, so does the sampler's.
    let passes = |d: &Distortion| d.sigma2 > 1e-12 * d.sigma1;
    if !passes(&atlas.frame.distortion[home.face as usize])
        && !passes(&atlas.frame.sampling_distortion(&atlas.topology, home.face, home.point))
    {
        return None;
    }
    let (position, normal) = patch.point_and_normal_f64(home.point - DVec2::from_array(patch.uv0.map(f64::from)));
    Some(TexelPoint { uv, chart, home, position, normal })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Topology, TriangleMesh};
    use crate::AtlasOptions;
    use std::sync::Arc;

    /// Texel points agree with the centres (same faces, points and normals to f32 precision, and
    /// missing at the same texels) over a lat-long sphere's atlas, poles and seam included.
    #[test]
    fn texel_points_are_the_centres_in_f32() {
        let shape = crate::shapes::uv_sphere(1.0, 48, 24);
        let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
        let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
        let atlas =
            Atlas::new(topology, &mesh.positions, &AtlasOptions { resolution: 128, ..Default::default() }).unwrap();
        let (mut both, mut neither) = (0, 0);
        for j in 0..96 {
            for i in 0..96 {
                let uv = DVec2::new((i as f64 + 0.5) / 96.0, (j as f64 + 0.5) / 96.0);
                match (centre_at(&atlas, uv, Lookup::Triangle), texel_point(&atlas, uv)) {
                    (Some(centre), Some(point)) => {
                        both += 1;
                        assert_eq!((centre.chart, centre.home), (point.chart, point.home));
                        let position = point.position.as_dvec3() + atlas.patches().origin;
                        assert!(position.distance(centre.position) < 1e-6, "{uv}");
                        assert!(point.normal.as_dvec3().distance(centre.normal) < 1e-6, "{uv}");
                    }
                    (None, None) => neither += 1,
                    (centre, point) => panic!("{uv}: centre {centre:?}, texel point {point:?}"),
                }
            }
        }
        assert!(both > 6_000 && neither > 100, "{both} {neither}");
    }
}
