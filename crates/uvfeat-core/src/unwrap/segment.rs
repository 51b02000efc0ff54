//! Normal-cone charts grown over the face graph, each projected onto the plane of its seed face
//! (DESIGN.md §1.1.1).
//!
//! A chart grows from a seed face in order of distance from the seed (so charts come out round)
//! and takes a face only when
//! - its smoothed normal lies within the cone of half-angle θ around the seed's (the chart's axis)
//!   and its own normal within 85° of the axis, so the orthographic projection keeps the face's
//!   orientation and stretches it by about `1 / cos θ`, and
//! - its projected triangle does not overlap any face the chart already holds, so the chart's
//!   parametrisation is injective even where the surface winds over itself (a spiral ramp).
//!
//! A face refused by one chart seeds a later one: charts tile the surface front by front.

use crate::cancel;
use crate::mesh::has_repeated_corner;
use glam::{DVec2, DVec3};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap, VecDeque};
use std::hash::{BuildHasherDefault, Hasher};

/// No face across this edge (a border, or a non-manifold edge, which charts never cross).
pub(super) const NO_FACE: u32 = u32::MAX;

/// The charts of a mesh and the projected UV vertices (object units, in each chart's own frame).
pub(super) struct Charts {
    /// (n_faces) UV vertex of each face corner.
    pub uv_faces: Vec<[u32; 3]>,
    /// (n_uvs) projected position of each UV vertex.
    pub uvs: Vec<DVec2>,
    /// (n_uvs) chart of each UV vertex.
    pub uv_chart: Vec<u32>,
    /// Number of charts.
    pub n_charts: usize,
    /// (n_charts) the plane each chart is projected onto.
    pub frames: Vec<ChartFrame>,
}

/// The plane a chart is projected onto: a chart's UVs are its vertices' [`ChartFrame::project`]
/// (until the packing moves them).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct ChartFrame {
    pub origin: DVec3,
    pub t1: DVec3,
    pub t2: DVec3,
}

impl ChartFrame {
    /// The point `p`'s UV in the chart.
    pub fn project(&self, p: DVec3) -> DVec2 {
        DVec2::new((p - self.origin).dot(self.t1), (p - self.origin).dot(self.t2))
    }
}

/// What the growth reads of the mesh: welded faces, their neighbours and their shape.
pub(super) struct FaceGraph<'a> {
    pub positions: &'a [DVec3],
    pub faces: &'a [[u32; 3]],
    /// (n_faces) the face across each edge `(k, k + 1)`, or [`NO_FACE`].
    pub neighbours: &'a [[u32; 3]],
    /// (n_faces) unit normal, zero for a face without area.
    pub normals: &'a [DVec3],
    /// (n_faces) the normals averaged over a few rings of neighbours: what the cone test reads.
    pub smoothed_normals: &'a [DVec3],
    pub centroids: &'a [DVec3],
    /// Side of the overlap guard's grid cells (object units).
    pub cell: f64,
}

/// The cosine of the largest angle between a face's own normal and its chart's axis: 85°.
const COS_FACE_LIMIT: f64 = 0.087_155_742_747_658_17;

/// The cosines of a chart's cone half-angle, for any face and for a notch.
#[derive(Clone, Copy)]
pub(super) struct Cone {
    pub cos_max_angle: f64,
    pub cos_notch_angle: f64,
}

impl Cone {
    /// A notch may tilt 30° more than other faces, up to 85° (a stretch of at most 11).
    pub fn new(max_angle_degrees: f64) -> Self {
        let notch = (max_angle_degrees + 30.0).min(85.0).max(max_angle_degrees);
        Self { cos_max_angle: max_angle_degrees.to_radians().cos(), cos_notch_angle: notch.to_radians().cos() }
    }
}

/// Grows the charts.
pub(super) fn grow_charts(graph: &FaceGraph, cone: Cone) -> Charts {
    let n_faces = graph.faces.len();
    let mut charts = Charts {
        uv_faces: vec![[0; 3]; n_faces],
        uvs: Vec::with_capacity(graph.positions.len() * 5 / 4),
        uv_chart: Vec::with_capacity(graph.positions.len() * 5 / 4),
        n_charts: 0,
        frames: Vec::new(),
    };
    let mut face_chart = vec![u32::MAX; n_faces];
    let mut growth = Growth::new(graph.positions.len(), n_faces, graph.cell);
    let mut seeds: VecDeque<u32> = VecDeque::new();
    let mut next_unscanned = 0usize;
    // A stop request leaves the charts unfinished: the caller returns `Cancelled`.
    while !cancel::requested() {
        let seed = match seeds.pop_front() {
            Some(f) if face_chart[f as usize] == u32::MAX => f,
            Some(_) => continue,
            None => {
                match (next_unscanned..n_faces)
                    .find(|&f| face_chart[f] == u32::MAX && !has_repeated_corner(graph.faces[f]))
                {
                    Some(f) => {
                        next_unscanned = f + 1;
                        f as u32
                    }
                    None => break,
                }
            }
        };
        let chart = charts.n_charts as u32;
        growth.grow(graph, seed, chart, cone, &mut face_chart, &mut charts, &mut seeds);
        charts.n_charts += 1;
    }
    // A face whose corners weld together has no edges to grow along and no area to chart: its
    // corners take the UVs their vertices have (the UV triangle is degenerate, and the topology
    // leaves it out, as it leaves the face out in 3D).
    for (f, corners) in graph.faces.iter().enumerate().filter(|(_, t)| has_repeated_corner(**t)) {
        let known =
            corners.map(|v| (growth.vertex_chart[v as usize] != u32::MAX).then(|| growth.vertex_uv[v as usize]));
        let any = known.iter().flatten().next().copied().unwrap_or_else(|| {
            // No corner has a UV (all the faces around collapsed too): a point in a chart of its own.
            charts.uvs.push(DVec2::ZERO);
            charts.uv_chart.push(charts.n_charts as u32);
            charts.frames.push(ChartFrame::default());
            charts.n_charts += 1;
            charts.uvs.len() as u32 - 1
        });
        charts.uv_faces[f] = known.map(|uv| uv.unwrap_or(any));
    }
    charts
}

/// The reusable state of one chart's growth.
struct Growth {
    /// (n_vertices) the chart that last gave the vertex a UV, and that UV's index.
    vertex_chart: Vec<u32>,
    vertex_uv: Vec<u32>,
    /// (n_faces) the chart that last looked at the face, so each chart weighs a face once.
    face_seen: Vec<u32>,
    heap: BinaryHeap<Reverse<(u64, u32)>>,
    /// The overlap guard: the chart's faces by grid cell, its faces too large for the grid, and
    /// all its faces.
    grid: HashMap<(i32, i32), Vec<u32>, BuildHasherDefault<CellHasher>>,
    large: Vec<u32>,
    held: Vec<u32>,
    cell: f64,
}

impl Growth {
    fn new(n_vertices: usize, n_faces: usize, cell: f64) -> Self {
        Self {
            vertex_chart: vec![u32::MAX; n_vertices],
            vertex_uv: vec![0; n_vertices],
            face_seen: vec![u32::MAX; n_faces],
            heap: BinaryHeap::new(),
            grid: HashMap::default(),
            large: Vec::new(),
            held: Vec::new(),
            cell,
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn grow(
        &mut self,
        graph: &FaceGraph,
        seed: u32,
        chart: u32,
        cone: Cone,
        face_chart: &mut [u32],
        charts: &mut Charts,
        seeds: &mut VecDeque<u32>,
    ) {
        // The seed's smoothed normal, unless the seed itself does not face it (then its own); a
        // seed without area (found only when it starts a component) has none: the xy plane.
        let (own, smoothed) = (graph.normals[seed as usize], graph.smoothed_normals[seed as usize]);
        let axis = if own == DVec3::ZERO {
            DVec3::Z
        } else if own.dot(smoothed) >= COS_FACE_LIMIT {
            smoothed
        } else {
            own
        };
        let (t1, t2) = axis.any_orthonormal_pair();
        let frame = ChartFrame { origin: graph.centroids[seed as usize], t1, t2 };
        charts.frames.push(frame);
        let project = |p: DVec3| frame.project(p);
        self.grid.clear();
        self.large.clear();
        self.held.clear();
        self.face_seen[seed as usize] = chart;
        self.heap.push(Reverse((0, seed)));
        while let Some(Reverse((_, f))) = self.heap.pop() {
            let corners = graph.faces[f as usize].map(|v| project(graph.positions[v as usize]));
            let normal = graph.normals[f as usize];
            let held = graph.neighbours[f as usize]
                .iter()
                .filter(|&&g| g != NO_FACE && face_chart[g as usize] == chart)
                .count();
            // The cone test reads the smoothed normal; the face itself must still face the axis,
            // within 85°, so that it projects the right way round and not into a sliver.
            let tilt = graph.smoothed_normals[f as usize].dot(axis);
            let facing = normal.dot(axis) >= COS_FACE_LIMIT;
            // A notch (a face the chart holds on two sides) may tilt further: refusing it would
            // leave it a chart of its own.
            let in_cone = facing && (tilt >= cone.cos_max_angle || (held >= 2 && tilt >= cone.cos_notch_angle));
            // A face without area has no interior to fold over anything: any chart may hold it.
            let fits = f == seed || normal == DVec3::ZERO || (in_cone && !self.overlaps(graph, f, &corners, charts));
            if !fits {
                if held < 2 && tilt >= cone.cos_notch_angle {
                    // It may become a notch as the chart grows: let its next neighbour offer it again.
                    self.face_seen[f as usize] = u32::MAX;
                }
                seeds.push_back(f);
                continue;
            }
            face_chart[f as usize] = chart;
            for (k, &v) in graph.faces[f as usize].iter().enumerate() {
                if self.vertex_chart[v as usize] != chart {
                    self.vertex_chart[v as usize] = chart;
                    self.vertex_uv[v as usize] = charts.uvs.len() as u32;
                    charts.uvs.push(corners[k]);
                    charts.uv_chart.push(chart);
                }
                charts.uv_faces[f as usize][k] = self.vertex_uv[v as usize];
            }
            self.insert(f, &corners);
            for &g in &graph.neighbours[f as usize] {
                if g != NO_FACE && face_chart[g as usize] == u32::MAX && self.face_seen[g as usize] != chart {
                    self.face_seen[g as usize] = chart;
                    let distance = graph.centroids[g as usize].distance_squared(frame.origin);
                    // Non-negative doubles order like their bit patterns.
                    self.heap.push(Reverse((distance.to_bits(), g)));
                }
            }
        }
    }

    /// The grid cells `(x0, y0, x1, y1)` a triangle's box covers, `None` when it spans more than
    /// [`MAX_CELL_SPAN`] on an axis (or is not finite).
    fn cell_span(&self, corners: &[DVec2; 3]) -> Option<(i32, i32, i32, i32)> {
        let low = (corners[0].min(corners[1]).min(corners[2]) / self.cell).floor();
        let high = (corners[0].max(corners[1]).max(corners[2]) / self.cell).floor();
        let span = high - low;
        (span.max_element() <= MAX_CELL_SPAN).then_some((low.x as i32, low.y as i32, high.x as i32, high.y as i32))
    }

    /// Whether face `f` (projected to `corners`) overlaps a face the chart holds. An edge
    /// neighbour cannot: both turn the same way, so they lie on either side of their shared edge.
    fn overlaps(&self, graph: &FaceGraph, f: u32, corners: &[DVec2; 3], charts: &Charts) -> bool {
        let own = uv_box(*corners);
        let overlapping = |&g: &u32| {
            let other = charts.uv_faces[g as usize].map(|k| charts.uvs[k as usize]);
            !boxes_apart(uv_box(other), own)
                && !graph.neighbours[f as usize].contains(&g)
                && interiors_overlap(corners, &other)
        };
        match self.cell_span(corners) {
            Some((x0, y0, x1, y1)) => {
                (x0..=x1)
                    .any(|x| (y0..=y1).any(|y| self.grid.get(&(x, y)).is_some_and(|held| held.iter().any(overlapping))))
                    || self.large.iter().any(overlapping)
            }
            None => self.held.iter().any(overlapping),
        }
    }

    fn insert(&mut self, f: u32, corners: &[DVec2; 3]) {
        self.held.push(f);
        match self.cell_span(corners) {
            Some((x0, y0, x1, y1)) => {
                for x in x0..=x1 {
                    for y in y0..=y1 {
                        self.grid.entry((x, y)).or_default().push(f);
                    }
                }
            }
            None => self.large.push(f),
        }
    }
}

/// Faces whose box spans more grid cells than this on an axis are checked against every face the
/// chart holds, not through the grid: one large face among small ones (a scan's base plate, a
/// CAD part's flat side) would fill millions of cells.
const MAX_CELL_SPAN: f64 = 16.0;

/// A multiplicative hash of grid cells: the guard's cells are small integers, where SipHash's
/// protection against chosen keys only costs time (it was half of the charts' growth).
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_i32(&mut self, value: i32) {
        self.write_u64(value as u32 as u64);
    }

    fn write_u64(&mut self, value: u64) {
        self.0 = (self.0.rotate_left(5) ^ value).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

/// The box `(low, high)` of some UV points.
pub(super) fn uv_box(points: impl IntoIterator<Item = DVec2>) -> (DVec2, DVec2) {
    points.into_iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(low, high), p| (low.min(p), high.max(p)))
}

/// Whether two boxes share no interior point (boxes that only touch are apart): the cheap test
/// before [`interiors_overlap`].
pub(super) fn boxes_apart(a: (DVec2, DVec2), b: (DVec2, DVec2)) -> bool {
    a.0.cmpge(b.1).any() || b.0.cmpge(a.1).any()
}

/// Whether the interiors of two triangles intersect (separating-axis test on their six edge
/// normals). Triangles that only touch, along a shared edge or at a shared corner, do not overlap:
/// shared corners project to bit-identical points, so the touching spans meet exactly.
pub(super) fn interiors_overlap(a: &[DVec2; 3], b: &[DVec2; 3]) -> bool {
    let span = |t: &[DVec2; 3], n: DVec2| {
        let d = [t[0].dot(n), t[1].dot(n), t[2].dot(n)];
        (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]))
    };
    for t in [a, b] {
        for k in 0..3 {
            let n = (t[(k + 1) % 3] - t[k]).perp();
            let ((a_low, a_high), (b_low, b_high)) = (span(a, n), span(b, n));
            let slack = 1e-12 * (a_high - a_low).abs().max(b_high - b_low);
            if a_high <= b_low + slack || b_high <= a_low + slack {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn touching_triangles_do_not_overlap_and_crossing_ones_do() {
        let a = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(0.0, 1.0)];
        let edge_neighbour = [DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];
        let corner_neighbour = [DVec2::new(1.0, 0.0), DVec2::new(2.0, 0.0), DVec2::new(2.0, 1.0)];
        let crossing = [DVec2::new(0.2, 0.2), DVec2::new(2.0, 0.2), DVec2::new(0.2, 2.0)];
        let far = [DVec2::new(3.0, 3.0), DVec2::new(4.0, 3.0), DVec2::new(3.0, 4.0)];
        assert!(!interiors_overlap(&a, &edge_neighbour));
        assert!(!interiors_overlap(&a, &corner_neighbour));
        assert!(interiors_overlap(&a, &crossing));
        assert!(interiors_overlap(&crossing, &a));
        assert!(!interiors_overlap(&a, &far));
    }
}
