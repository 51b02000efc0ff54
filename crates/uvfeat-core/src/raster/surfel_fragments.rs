//! The pieces surfels are built from (DESIGN.md §1.4.8): each face's UV triangle clipped to the
//! texels of the grid, with its 3D area, centroid and normal; and points along the chart
//! boundaries that tell which surfels a seam joins and which a mesh border passes through.

use crate::cancel;
use crate::frame::Frame;
use crate::mesh::{EdgeLink, SideKind, Topology};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// The part of one face in one texel (or, summed, a surfel): area and area-weighted sums, and
/// how the area spreads about its centroid.
#[derive(Debug, Clone, Copy)]
pub(super) struct Fragment {
    pub texel: u32,
    pub chart: i32,
    pub area: f64,
    pub moment: DVec3,
    pub normal: DVec3,
    /// `sum dA |q - c|^2` about the centroid `c`.
    pub spread: f64,
    /// [`JOINS_LEFT`] and [`JOINS_BELOW`]: a face has parts both here and in the texel to the left
    /// (below) of this one, so the surface crosses their common side.
    pub joins: u8,
}

/// [`Fragment::joins`]: joined with the texel to the left.
pub(super) const JOINS_LEFT: u8 = 1;
/// [`Fragment::joins`]: joined with the texel below.
pub(super) const JOINS_BELOW: u8 = 2;

impl Fragment {
    /// Nothing of `chart` in `texel` yet.
    pub fn empty(texel: u32, chart: i32) -> Self {
        Self { texel, chart, area: 0.0, moment: DVec3::ZERO, normal: DVec3::ZERO, spread: 0.0, joins: 0 }
    }

    /// Area centroid (the origin without area).
    pub fn centroid(&self) -> DVec3 {
        if self.area > 0.0 {
            self.moment / self.area
        } else {
            DVec3::ZERO
        }
    }

    /// Adds `other`'s surface, its spread by the parallel-axis theorem (about each part's own
    /// centroid, so that far from the origin nothing cancels).
    pub fn absorb(&mut self, other: &Fragment) {
        self.joins |= other.joins;
        if !(other.area > 0.0) {
            return;
        }
        if !(self.area > 0.0) {
            *self = Fragment { texel: self.texel, chart: self.chart, joins: self.joins, ..*other };
            return;
        }
        let (a, b) = (self.centroid(), other.centroid());
        let area = self.area + other.area;
        let moment = self.moment + other.moment;
        self.spread += other.spread + self.area * other.area / area * (a - b).length_squared();
        self.area = area;
        self.moment = moment;
        self.normal += other.normal;
    }
}

/// The same seam point seen from its two faces: parametric point and chart on each side.
pub(super) type SeamPoints = ((DVec2, i32), (DVec2, i32));

/// Texel rows a band of the grid holds: the fragments of one band are summed on their own, so
/// that the pieces of all faces are never held at once (3 per texel, 64 bytes each).
const BAND_ROWS: usize = 16;

/// The surfels of a `width`² grid: every face's pieces summed per texel and chart, in texel order
/// (then chart), band by band in parallel. A band's pieces are listed in face order and sorted by
/// one thread, so the order they are summed in, and the sums, do not depend on the thread count.
pub(super) fn texel_sums(topology: &Topology, frame: &Frame, width: usize, smooth: bool) -> Vec<Fragment> {
    let bands = width.div_ceil(BAND_ROWS);
    let rows: Vec<Option<(usize, usize)>> =
        (0..topology.faces.len()).into_par_iter().map(|f| face_rows(topology, f, width)).collect();
    let mut first = vec![0usize; bands + 1];
    for &(j0, j1) in rows.iter().flatten() {
        for band in j0 / BAND_ROWS..=j1 / BAND_ROWS {
            first[band + 1] += 1;
        }
    }
    for band in 0..bands {
        first[band + 1] += first[band];
    }
    let mut faces = vec![0u32; first[bands]];
    let mut next = first.clone();
    for (f, &(j0, j1)) in rows.iter().enumerate().filter_map(|(f, r)| Some((f, r.as_ref()?))) {
        for band in j0 / BAND_ROWS..=j1 / BAND_ROWS {
            faces[next[band]] = f as u32;
            next[band] += 1;
        }
    }
    (0..bands)
        .into_par_iter()
        .flat_map_iter(|band| {
            let rows = band * BAND_ROWS..=((band + 1) * BAND_ROWS).min(width) - 1;
            let mut pieces = Vec::new();
            if cancel::requested() {
                return pieces;
            }
            for &f in &faces[first[band]..first[band + 1]] {
                face_fragments(topology, frame, f as usize, width, smooth, rows.clone(), &mut pieces);
            }
            summed_by_texel(pieces, *rows.start() * width, (rows.end() + 1) * width)
        })
        .collect()
}

/// The pieces of texels `start..end` summed per texel and chart, in texel order (then chart):
/// counted into their texels in the order given (face order), then the few pieces of each texel
/// ordered by chart, so the sums do not depend on the thread count. A counting sort: with a
/// comparison sort of the whole band the pyramid took 1.04-1.2x as long (512², Spot to dragon).
fn summed_by_texel(pieces: Vec<Fragment>, start: usize, end: usize) -> Vec<Fragment> {
    let mut first = vec![0u32; end - start + 1];
    for piece in &pieces {
        first[piece.texel as usize - start + 1] += 1;
    }
    for t in 0..end - start {
        first[t + 1] += first[t];
    }
    let mut order = vec![0u32; pieces.len()];
    let mut next = first.clone();
    for (k, piece) in pieces.iter().enumerate() {
        let slot = &mut next[piece.texel as usize - start];
        order[*slot as usize] = k as u32;
        *slot += 1;
    }
    let mut sums: Vec<Fragment> = Vec::new();
    for t in 0..end - start {
        let texel = &mut order[first[t] as usize..first[t + 1] as usize];
        texel.sort_by_key(|&k| pieces[k as usize].chart);
        for &k in texel.iter() {
            let piece = &pieces[k as usize];
            match sums.last_mut() {
                Some(sum) if (sum.texel, sum.chart) == (piece.texel, piece.chart) => sum.absorb(piece),
                _ => sums.push(*piece),
            }
        }
    }
    sums
}

/// The rows of the grid face `f`'s UV triangle spans; `None` off the charts.
fn face_rows(topology: &Topology, f: usize, width: usize) -> Option<(usize, usize)> {
    if topology.face_chart[f] < 0 {
        return None;
    }
    let v = topology.corner_uvs(f).map(|uv| uv.y * width as f64);
    let (lo, hi) = (v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2]));
    (hi >= 0.0 && lo < width as f64).then(|| (lo.floor().max(0.0) as usize, (hi.floor() as usize).min(width - 1)))
}

/// Appends the parts of face `f` in each texel of rows `rows` of a `width`² grid to `out`, each
/// marked with the texels to its left and below that the face has parts in too
/// ([`Fragment::joins`]). Texels are joined only through a face in both: a face is convex, so its
/// parts in two side-adjacent texels meet across their common side, where two pieces of a chart
/// that only come near each other in UV (across a notch of the chart narrower than a texel) do
/// not.
fn face_fragments(
    topology: &Topology,
    frame: &Frame,
    f: usize,
    width: usize,
    smooth: bool,
    rows: std::ops::RangeInclusive<usize>,
    out: &mut Vec<Fragment>,
) {
    let chart = topology.face_chart[f];
    let Some(map) = frame.face_map(topology, f as u32) else { return };
    let w = width as f64;
    let corners = topology.corner_uvs(f).map(|uv| uv * w);
    let texel_area = map.area_element / (w * w);
    let (lo, hi) = (corners[0].min(corners[1]).min(corners[2]), corners[0].max(corners[1]).max(corners[2]));
    let (i0, j0) = ((lo.x.floor().max(0.0)) as usize, (lo.y.floor().max(0.0)) as usize);
    let (i1, j1) = ((hi.x.floor() as usize).min(width - 1), (hi.y.floor() as usize).min(width - 1));
    // The row below the band too, when the face reaches it, for the joins of the band's first row
    // (no part of it is kept here).
    let below = usize::from(j0 < *rows.start());
    let (j0, j1) = (j0.max(*rows.start()) - below, j1.min(*rows.end()));
    let triangle = Polygon::from(&corners);
    // The columns holding parts of the face in the row before (contiguous: the face is convex).
    let mut previous: Option<(usize, usize)> = None;
    for j in j0..=j1 {
        let row = triangle.clip(1, j as f64, j as f64 + 1.0);
        let mut held: Option<(usize, usize)> = None;
        for i in i0..=i1 {
            let piece = row.clip(0, i as f64, i as f64 + 1.0);
            let (uv_area, centroid) = piece.area_centroid();
            // No 3D area (a face collapsed in space but not in UV): nothing to sum, and no centroid.
            let area = uv_area * texel_area;
            if !(area > 0.0) {
                continue;
            }
            let first = held.map_or(i, |(first, _)| first);
            held = Some((first, i));
            if j < *rows.start() {
                continue;
            }
            let joins = if i > first { JOINS_LEFT } else { 0 }
                | if previous.is_some_and(|(a, b)| a <= i && i <= b) { JOINS_BELOW } else { 0 };
            let uv = centroid / w;
            let position = if smooth { map.smooth_position(uv) } else { map.position(uv) };
            // The face's map is affine: texel offsets from the centroid map to 3D through J / W.
            let to_3d = |d: DVec2| (map.jacobian.pu * d.x + map.jacobian.pv * d.y) / w;
            let [cxx, cxy, cyy] = piece.covariance(centroid);
            let (pu, pv) = (to_3d(DVec2::X), to_3d(DVec2::Y));
            let spread = area * (cxx * pu.length_squared() + 2.0 * cxy * pu.dot(pv) + cyy * pv.length_squared());
            out.push(Fragment {
                texel: (j * width + i) as u32,
                chart,
                area,
                moment: position * area,
                normal: map.normal(uv) * area,
                spread: spread.max(0.0),
                joins,
            });
        }
        previous = held;
    }
}

/// Points sampled every half texel along the chart boundaries: seam points paired with the same
/// point seen from the face across (and so the points of interior edges along texel sides), and
/// points of mesh borders; each nudged into its face so that it falls in a texel that holds part
/// of the face.
pub(super) fn boundary_points(topology: &Topology, width: usize) -> (Vec<SeamPoints>, Vec<(DVec2, i32)>) {
    let w = width as f64;
    let inward = |face: u32, uv: DVec2| {
        let c = topology.corner_uvs(face as usize);
        uv + ((c[0] + c[1] + c[2]) / 3.0 - uv) * 1e-4
    };
    let along = |a: [DVec2; 2], extra: DVec2| {
        let n = ((a[1] - a[0]).length().max(extra.x) * 2.0 * w).ceil().clamp(1.0, 8.0 * w) as usize;
        (0..n).map(move |k| (k as f64 + 0.5) / n as f64)
    };
    let mut seams: Vec<SeamPoints> = topology
        .sides
        .par_iter()
        .enumerate()
        .filter(|(s, side)| matches!(side.kind, SideKind::Seam { .. }) && (*s as i32) < side.reverse)
        .flat_map_iter(|(_, side)| {
            let other = &topology.sides[side.reverse as usize];
            let (ids, uv) = topology.side_endpoints(side);
            let (other_ids, other_uv) = topology.side_endpoints(other);
            let other_uv = if other_ids[0] == ids[0] { other_uv } else { [other_uv[1], other_uv[0]] };
            let longer = DVec2::splat((other_uv[1] - other_uv[0]).length());
            along(uv, longer).map(move |t| {
                let a = inward(side.face, uv[0].lerp(uv[1], t));
                let b = inward(other.face, other_uv[0].lerp(other_uv[1], t));
                ((a, side.chart), (b, other.chart))
            })
        })
        .collect();
    // An interior edge along a texel side: its two faces have parts on either side of it and none
    // across (`face_fragments` joins no texels for them), so it is walked as a seam is.
    let on_grid_line = |a: DVec2, b: DVec2| {
        let on = |x: f64, y: f64| (x - y).abs() < 1e-9 && (x - x.round()).abs() < 1e-9;
        on(a.x * w, b.x * w) || on(a.y * w, b.y * w)
    };
    seams.par_extend((0..topology.faces.len()).into_par_iter().flat_map_iter(|f| {
        let uv = topology.corner_uvs(f);
        (0..3)
            .filter_map(move |k| match topology.walk_faces[f].link(k) {
                EdgeLink::Face { face: g, .. } if (f as u32) < g && on_grid_line(uv[k], uv[(k + 1) % 3]) => {
                    Some((k, g))
                }
                _ => None,
            })
            .flat_map(move |(k, g)| {
                let (a, b) = (uv[k], uv[(k + 1) % 3]);
                let chart = topology.face_chart[f];
                along([a, b], DVec2::ZERO).map(move |t| {
                    let point = a.lerp(b, t);
                    ((inward(f as u32, point), chart), (inward(g, point), topology.face_chart[g as usize]))
                })
            })
    }));
    let borders = topology
        .sides
        .par_iter()
        .filter(|side| !matches!(side.kind, SideKind::Seam { .. }))
        .flat_map_iter(|side| {
            let (_, uv) = topology.side_endpoints(side);
            along(uv, DVec2::ZERO).map(move |t| (inward(side.face, uv[0].lerp(uv[1], t)), side.chart))
        })
        .collect();
    (seams, borders)
}

/// A convex polygon of at most 9 vertices (a triangle clipped by a square).
#[derive(Debug, Clone, Copy)]
struct Polygon {
    points: [DVec2; 9],
    len: usize,
}

impl Polygon {
    fn from(triangle: &[DVec2; 3]) -> Self {
        let mut points = [DVec2::ZERO; 9];
        points[..3].copy_from_slice(triangle);
        Self { points, len: 3 }
    }

    /// The part with coordinate `axis` in `[lo, hi]` (Sutherland–Hodgman, two half-planes).
    fn clip(&self, axis: usize, lo: f64, hi: f64) -> Self {
        self.clip_half(axis, lo, 1.0).clip_half(axis, hi, -1.0)
    }

    /// The part where `sign (x[axis] - bound) >= 0`.
    fn clip_half(&self, axis: usize, bound: f64, sign: f64) -> Self {
        let mut out = Self { points: [DVec2::ZERO; 9], len: 0 };
        let inside = |p: DVec2| sign * (p[axis] - bound);
        for k in 0..self.len {
            let (a, b) = (self.points[k], self.points[(k + 1) % self.len]);
            let (da, db) = (inside(a), inside(b));
            if da >= 0.0 && out.len < 9 {
                out.points[out.len] = a;
                out.len += 1;
            }
            if (da >= 0.0) != (db >= 0.0) && out.len < 9 {
                out.points[out.len] = a + (b - a) * (da / (da - db));
                out.len += 1;
            }
        }
        out
    }

    /// Unsigned area and centroid (shoelace).
    fn area_centroid(&self) -> (f64, DVec2) {
        if self.len < 3 {
            return (0.0, DVec2::ZERO);
        }
        let (mut twice_area, mut moment) = (0.0, DVec2::ZERO);
        for k in 0..self.len {
            let (a, b) = (self.points[k], self.points[(k + 1) % self.len]);
            let cross = a.perp_dot(b);
            twice_area += cross;
            moment += (a + b) * cross;
        }
        if twice_area == 0.0 {
            return (0.0, DVec2::ZERO);
        }
        (twice_area.abs() / 2.0, moment / (3.0 * twice_area))
    }

    /// Area covariance `[xx, xy, yy]` about `centroid` (per unit area): the polygon's second
    /// moments by the shoelace formulas, taken about the centroid so nothing cancels.
    fn covariance(&self, centroid: DVec2) -> [f64; 3] {
        let (mut twice_area, mut xx, mut xy, mut yy) = (0.0, 0.0, 0.0, 0.0);
        for k in 0..self.len {
            let (a, b) = (self.points[k] - centroid, self.points[(k + 1) % self.len] - centroid);
            let cross = a.perp_dot(b);
            twice_area += cross;
            xx += (a.x * a.x + a.x * b.x + b.x * b.x) * cross;
            yy += (a.y * a.y + a.y * b.y + b.y * b.y) * cross;
            xy += (a.x * b.y + 2.0 * a.x * a.y + 2.0 * b.x * b.y + b.x * a.y) * cross;
        }
        if twice_area == 0.0 {
            return [0.0; 3];
        }
        // Integrals are (1/12, 1/24, 1/12) of the sums; the area is half of `twice_area`.
        [xx / (6.0 * twice_area), xy / (12.0 * twice_area), yy / (6.0 * twice_area)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_area_and_centroid() {
        let triangle = Polygon::from(&[DVec2::new(0.2, 0.1), DVec2::new(2.7, 0.4), DVec2::new(1.1, 2.9)]);
        let (area, centroid) = triangle.area_centroid();
        let (mut sum, mut moment) = (0.0, DVec2::ZERO);
        for j in 0..3 {
            for i in 0..3 {
                let (a, c) =
                    triangle.clip(1, j as f64, j as f64 + 1.0).clip(0, i as f64, i as f64 + 1.0).area_centroid();
                sum += a;
                moment += c * a;
            }
        }
        assert!((sum - area).abs() < 1e-12 && (moment / sum - centroid).length() < 1e-12);
    }

    #[test]
    fn covariance_of_a_unit_square_and_a_right_triangle() {
        let square = Polygon {
            points: [
                DVec2::ZERO,
                DVec2::X,
                DVec2::ONE,
                DVec2::Y,
                DVec2::ZERO,
                DVec2::ZERO,
                DVec2::ZERO,
                DVec2::ZERO,
                DVec2::ZERO,
            ],
            len: 4,
        };
        let [xx, xy, yy] = square.covariance(DVec2::splat(0.5));
        assert!((xx - 1.0 / 12.0).abs() < 1e-15 && xy.abs() < 1e-15 && (yy - 1.0 / 12.0).abs() < 1e-15);
        // Right triangle (0,0), (1,0), (0,1): Var x = Var y = 1/18, Cov = -1/36.
        let triangle = Polygon::from(&[DVec2::ZERO, DVec2::X, DVec2::Y]);
        let (_, c) = triangle.area_centroid();
        let [xx, xy, yy] = triangle.covariance(c);
        assert!((xx - 1.0 / 18.0).abs() < 1e-15 && (xy + 1.0 / 36.0).abs() < 1e-15 && (yy - 1.0 / 18.0).abs() < 1e-15);
    }

    #[test]
    fn absorbed_fragments_keep_the_spread_of_the_whole() {
        // Two points of area 1 at x = 0 and x = 2: spread about x = 1 is 2.
        let at = |x: f64| Fragment { moment: DVec3::new(x, 0.0, 0.0), area: 1.0, ..Fragment::empty(0, 0) };
        let mut sum = Fragment::empty(0, 0);
        sum.absorb(&at(0.0));
        sum.absorb(&at(2.0));
        assert!((sum.spread - 2.0).abs() < 1e-15);
        assert_eq!(sum.centroid(), DVec3::new(1.0, 0.0, 0.0));
    }
}
