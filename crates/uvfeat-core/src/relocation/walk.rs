//! The exact triangle walk: follows the straight parametric segment from a point to a target face
//! by face through the UV triangulation, and where it crosses a seam, carries the rest of the
//! segment across with that seam's transition map. Unlike the texel march it needs no border texel,
//! so charts narrower than a texel and corners where several seams meet are crossed exactly, and it
//! ends in the face that contains the point (or, for a point well inside a chart, the face of its
//! texel), so the lookup never extrapolates into a gutter.

use super::{interior_face, Located};
use crate::atlas::Atlas;
use crate::mesh::{EdgeLink, WalkFace};
use glam::{DMat2, DVec2};

/// Faces one walk may cross inside a chart before it is given up as lost (a guard against
/// numerical cycles; real walks cross `r / edge length` faces).
const MAX_FACES: usize = 1 << 16;

/// A point inside a face, from which walks start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Home {
    /// The face containing `point`.
    pub face: u32,
    /// A point of the face's parametric triangle (boundary included).
    pub point: DVec2,
}

/// Where a walk inside one chart stopped.
enum Stop {
    /// The target lies in `face`.
    Arrived { face: u32 },
    /// The segment left the chart through `side` at `point`.
    Boundary { side: u32, point: DVec2 },
    /// The guard ran out or a face was unusable.
    Lost,
}

/// Signed edge functions of `uv` for the three edges of a parametric triangle, positive inside
/// (whatever the triangle's orientation).
#[inline]
fn edge_functions(face: &WalkFace, uv: DVec2) -> [f64; 3] {
    let (corners, orientation) = (&face.corners, f64::from(face.orientation));
    std::array::from_fn(|k| {
        let (a, b) = (corners[k], corners[(k + 1) % 3]);
        (b - a).perp_dot(uv - a) * orientation
    })
}

/// Walks from `from` (in `face`, entered through edge `entry`) towards `target` inside one chart;
/// from face `first_skip` on, every few faces it tries to jump ahead over texels no boundary
/// touches (`None`: never).
fn walk_in_chart(
    atlas: &Atlas,
    mut face: u32,
    mut entry: Option<u8>,
    mut from: DVec2,
    target: DVec2,
    first_skip: Option<usize>,
) -> Stop {
    let topology = &atlas.topology;
    let chart = topology.face_chart[face as usize];
    for step in 0..MAX_FACES {
        if first_skip.is_some_and(|first| step >= first && (step - first) % SKIP_EVERY == 0) {
            if let Some((ahead, point)) = skip_ahead(atlas, chart, from, target) {
                (face, entry, from) = (ahead, None, point);
            }
        }
        let record = &topology.walk_faces[face as usize];
        let at_target = edge_functions(record, target);
        let at_from = edge_functions(record, from);
        let mut exit: Option<(usize, f64)> = None;
        for k in 0..3 {
            if Some(k as u8) == entry || at_target[k] >= 0.0 {
                continue;
            }
            let inside = at_from[k].max(0.0);
            let t = inside / (inside - at_target[k]);
            if exit.is_none_or(|(_, best)| t < best) {
                exit = Some((k, t));
            }
        }
        let Some((k, t)) = exit else {
            return Stop::Arrived { face };
        };
        from += (target - from) * t;
        match record.link(k) {
            EdgeLink::Face { face: next, local } => {
                face = next;
                entry = Some(local);
            }
            EdgeLink::Side(side) => return Stop::Boundary { side, point: from },
            EdgeLink::Closed => return Stop::Lost,
        }
    }
    Stop::Lost
}

/// The face of `chart` containing `uv`: found from the face of its texel by a short walk, which
/// stops at the chart boundary (then `point` is the boundary point closest along the way).
pub fn home(atlas: &Atlas, uv: DVec2, chart: i32) -> Option<Home> {
    let coverage = atlas.coverage();
    let texel = atlas.nearest_texel(uv, |t| coverage.chart[t] == chart)?;
    let face = u32::try_from(coverage.face[texel]).ok()?;
    let topology = &atlas.topology;
    let corners = topology.corner_uvs(face as usize);
    let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
    match walk_in_chart(atlas, face, None, centroid, uv, None) {
        Stop::Arrived { face } => Some(Home { face, point: uv }),
        Stop::Boundary { side, point } => Some(Home { face: topology.sides[side as usize].face, point }),
        Stop::Lost => None,
    }
}

/// Moves the start of a walk from `from` towards `target` over the texels that no chart boundary
/// touches (sphere tracing on [`Coverage::chart_distance`]): a point of a texel at distance `d`
/// has only such texels of its own chart within `(d - 2)` texels, so the straight segment crosses
/// nothing there and the walk can resume further on, in the face under the texel's centre. Returns
/// the face and point to resume from, or `None` when no step was possible.
///
/// [`Coverage::chart_distance`]: crate::raster::Coverage::chart_distance
fn skip_ahead(atlas: &Atlas, chart: i32, from: DVec2, target: DVec2) -> Option<(u32, DVec2)> {
    let coverage = atlas.coverage();
    let texel_size = 1.0 / coverage.resolution as f64;
    let mut point = from;
    let side = coverage.resolution;
    let (mut i, mut j) = atlas.texel_coordinates(point).filter(|&(i, j)| coverage.chart[j * side + i] == chart)?;
    let mut skipped = false;
    loop {
        let distance = f64::from(coverage.chart_distance.at(i, j));
        if distance < MIN_SKIP {
            break;
        }
        // The free texels form a square around the texel: a step may move `distance - 2` texels
        // along each axis, so its length is measured in the maximum norm (up to 1.41x longer
        // steps than a Euclidean bound on diagonal segments).
        let safe = (distance - 2.0) * texel_size;
        let remaining = target - point;
        let length = remaining.abs().max_element();
        let reaches_target = length <= safe;
        point = if reaches_target { target } else { point + remaining * (safe / length) };
        // Within `distance - 1` texels every texel is of `chart`, so the texel reached needs no
        // chart check (one load fewer per step).
        (i, j) = atlas.texel_coordinates(point)?;
        skipped = true;
        if reaches_target {
            break;
        }
    }
    if !skipped {
        return None;
    }
    let texel = j * side + i;
    let (face, under_centre) = coverage.anchor(&atlas.topology, texel)?;
    match walk_in_chart(atlas, face, None, under_centre, point, None) {
        Stop::Arrived { face } => Some((face, point)),
        Stop::Boundary { .. } | Stop::Lost => None,
    }
}

/// Chart distance (texels) from which a skip is worth a texel lookup and a short walk.
const MIN_SKIP: f64 = 3.0;

/// Faces walked between two attempts to skip ahead.
const SKIP_EVERY: usize = 4;

/// Locates `target` by walking from `home`, crossing at most `max_jumps` seams. After each seam, a
/// target that lies well inside the chart across ([`interior_face`]) ends the walk at once, as the
/// loop of DESIGN.md §1.5.2 does: walking on to it would cross that chart's texels one face at a time, the
/// larger part of a crossing sample's cost at large radii.
pub fn walk(atlas: &Atlas, home: &Home, target: DVec2, max_jumps: u32) -> Located {
    walk_across(atlas, home, target, max_jumps, Seams::Any)
}

/// Which seams a walk may cross.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Seams {
    /// Any.
    Any,
    /// Only those with the same chart on both sides (the slits between a lat-long pole's fan
    /// triangles, a chart's own wrap-around); a seam into another chart ends the walk as
    /// [`Located::Missing`].
    WithinChart,
}

/// [`walk`], crossing only the `seams` allowed.
pub fn walk_across(atlas: &Atlas, home: &Home, target: DVec2, max_jumps: u32, seams: Seams) -> Located {
    let topology = &atlas.topology;
    let (mut face, mut entry, mut from, mut target) = (home.face, None, home.point, target);
    let mut m_path = DMat2::IDENTITY;
    let mut jumps = 0;
    loop {
        // Right after a seam the walk stands on the boundary, where no skip is possible.
        let first_skip = if jumps == 0 { 0 } else { SKIP_EVERY };
        match walk_in_chart(atlas, face, entry, from, target, Some(first_skip)) {
            Stop::Arrived { face } => {
                let chart = topology.face_chart[face as usize];
                return Located::Inside { chart, uv: target, m_path, jumps, face: Some(face) };
            }
            Stop::Lost => return Located::Missing,
            Stop::Boundary { side, point } => {
                let Some(map) = atlas.seam_maps()[side as usize] else {
                    return Located::Border;
                };
                if jumps == max_jumps {
                    return Located::Missing;
                }
                let across = &topology.sides[topology.sides[side as usize].reverse as usize];
                if seams == Seams::WithinChart
                    && topology.face_chart[across.face as usize] != topology.face_chart[face as usize]
                {
                    return Located::Missing;
                }
                target = map.apply(target);
                m_path = map.m * m_path;
                jumps += 1;
                let chart = topology.face_chart[across.face as usize];
                if let Some(face) = interior_face(atlas, target, chart) {
                    return Located::Inside { chart, uv: target, m_path, jumps, face: Some(face) };
                }
                face = across.face;
                entry = Some(across.local);
                from = map.apply(point);
            }
        }
    }
}
