//! Packing of the charts into the unit square (DESIGN.md §1.1.1).
//!
//! Every chart is turned onto its principal axes and all charts share one scale, so a texel
//! covers the same surface area everywhere (up to the projection's stretch). Charts are placed as
//! bitmaps, not boxes: the surface charts of a scan are ragged (their boxes hold twice their
//! area), and bitmaps let small charts fill the gaps of large ones. The bitmaps are at a block of
//! `padding` texels, and a chart's blocks keep one free block from every other chart's, so any
//! two charts are at least `padding` texels apart.

use glam::DVec2;
use rayon::prelude::*;

/// Charts whose box has at most this many blocks are placed as their box.
const SMALL_BOX_BLOCKS: usize = 16;

/// Charts narrower than this many texels are enlarged until they are not: a smaller chart may
/// cover no texel centre, and its faces would have no texels of their own. Their texels then
/// cover less surface than elsewhere, which each face's metric accounts for.
const MIN_CHART_TEXELS: f64 = 3.0;

/// An enlarged chart's long side grows to at most this many texels (slivers stay small) ...
const MAX_ENLARGED_TEXELS: f64 = 48.0;

/// ... and its scale to at most this multiple of the atlas's, so that every chart still shrinks
/// with the atlas's scale while the packing searches for one that fits.
const MAX_ENLARGEMENT: f64 = 64.0;

/// The scale of a chart of `size` (object units) when the atlas's scale is `scale`.
fn chart_scale(size: DVec2, scale: f64) -> f64 {
    let (narrow, long) = (size.min_element() * scale, size.max_element() * scale);
    if narrow >= MIN_CHART_TEXELS || long == 0.0 {
        return scale;
    }
    scale * (MIN_CHART_TEXELS / narrow).min(MAX_ENLARGED_TEXELS / long).clamp(1.0, MAX_ENLARGEMENT)
}

/// Moves `uvs` (object units, per chart) into `[0, 1]^2`.
///
/// # Returns
/// The scale in texels of `resolution` per object unit (charts narrower than
/// [`MIN_CHART_TEXELS`] are enlarged beyond it), or `None` when even the gutters do not fit (more
/// charts than the resolution has room for).
pub(super) fn pack(
    uvs: &mut [DVec2],
    uv_faces: &[[u32; 3]],
    uv_chart: &[u32],
    n_charts: usize,
    resolution: usize,
    padding: f64,
) -> Option<f64> {
    let frames = chart_frames(uvs, uv_chart, n_charts);
    let local: Vec<DVec2> = uvs.iter().zip(uv_chart).map(|(uv, &c)| frames[c as usize].place(*uv)).collect();
    let chart_faces = faces_by_chart(uv_faces, uv_chart, n_charts);
    let block = padding.max(1.0);
    let grid = (resolution as f64 / block).floor() as usize;
    // However small, every chart takes a block and a free block beside it on both axes.
    if n_charts > grid.div_ceil(2).pow(2) {
        return None;
    }
    let area: f64 = frames.iter().map(|f| f.size.x * f.size.y).sum::<f64>().max(f64::MIN_POSITIVE);
    // Boxes bound the scale only loosely: ragged charts nest into each other's boxes. So walk by
    // 10 % steps from the box-area bound, down to the first scale that packs or up to the first
    // that does not, then bisect that step once.
    let mut scale = (resolution as f64) / area.sqrt();
    let sizes: Vec<DVec2> = frames.iter().map(|f| f.size).collect();
    let pack_at = |scale: f64| place(&local, uv_faces, &chart_faces, &sizes, scale, block, grid);
    let smallest = 1e-3 / frames.iter().map(|f| f.size.max_element()).fold(f64::MIN_POSITIVE, f64::max);
    let (mut packed, failed) = match pack_at(scale) {
        Some(origins) => {
            // At most 64 steps up (850x): charts without area fit at any scale.
            let mut packed = (scale, origins);
            let mut failed = f64::INFINITY;
            for _ in 0..64 {
                scale /= 0.9;
                match pack_at(scale).filter(|_| scale.is_finite()) {
                    Some(origins) => packed = (scale, origins),
                    None => {
                        failed = scale;
                        break;
                    }
                }
            }
            (packed, failed)
        }
        None => loop {
            let failed = scale;
            scale *= 0.9;
            // `!(a >= b)` also ends the search on a NaN scale.
            if !(scale >= smallest) {
                return None;
            }
            if let Some(origins) = pack_at(scale) {
                break ((scale, origins), failed);
            }
        },
    };
    let middle = (packed.0 * failed).sqrt();
    if let Some(origins) = pack_at(middle).filter(|_| middle.is_finite()) {
        packed = (middle, origins);
    }
    let (scale, origins) = packed;
    for (uv, (&chart, p)) in uvs.iter_mut().zip(uv_chart.iter().zip(&local)) {
        let chart_scale = chart_scale(sizes[chart as usize], scale);
        *uv = (origins[chart as usize] * block + *p * chart_scale) / resolution as f64;
    }
    Some(scale)
}

/// A chart's principal axes (the eigenvectors of its UV vertices' covariance) and bounds:
/// `place` turns a UV by `rotation` and moves it to start at the origin.
struct ChartFrame {
    rotation: DVec2,
    low: DVec2,
    size: DVec2,
}

impl ChartFrame {
    fn place(&self, uv: DVec2) -> DVec2 {
        self.rotation.rotate(uv) - self.low
    }
}

fn chart_frames(uvs: &[DVec2], uv_chart: &[u32], n_charts: usize) -> Vec<ChartFrame> {
    let mut moments = vec![[0.0f64; 6]; n_charts];
    for (uv, &chart) in uvs.iter().zip(uv_chart) {
        let m = &mut moments[chart as usize];
        *m = [m[0] + 1.0, m[1] + uv.x, m[2] + uv.y, m[3] + uv.x * uv.x, m[4] + uv.x * uv.y, m[5] + uv.y * uv.y];
    }
    let mut frames: Vec<ChartFrame> = moments
        .iter()
        .map(|m| {
            let mean = DVec2::new(m[1], m[2]) / m[0];
            let (xx, xy, yy) =
                (m[3] / m[0] - mean.x * mean.x, m[4] / m[0] - mean.x * mean.y, m[5] / m[0] - mean.y * mean.y);
            // Turning by -angle brings the major axis onto u.
            let angle = 0.5 * (2.0 * xy).atan2(xx - yy);
            ChartFrame { rotation: DVec2::from_angle(-angle), low: DVec2::INFINITY, size: DVec2::NEG_INFINITY }
        })
        .collect();
    for (uv, &chart) in uvs.iter().zip(uv_chart) {
        let frame = &mut frames[chart as usize];
        let turned = frame.rotation.rotate(*uv);
        frame.low = frame.low.min(turned);
        frame.size = frame.size.max(turned);
    }
    for frame in &mut frames {
        frame.size -= frame.low;
    }
    frames
}

/// The faces of every chart (a chart's faces all have their corners in it).
fn faces_by_chart(uv_faces: &[[u32; 3]], uv_chart: &[u32], n_charts: usize) -> Vec<Vec<u32>> {
    let mut lists = vec![Vec::new(); n_charts];
    for (f, corners) in uv_faces.iter().enumerate() {
        lists[uv_chart[corners[0] as usize] as usize].push(f as u32);
    }
    lists
}

/// The blocks a chart covers, one bit each, rows of `words` 64-bit words.
struct Mask {
    width: usize,
    height: usize,
    words: usize,
    bits: Vec<u64>,
}

impl Mask {
    fn new(width: usize, height: usize) -> Self {
        let words = width.div_ceil(64);
        Self { width, height, words, bits: vec![0; words * height] }
    }

    fn set(&mut self, x: usize, y: usize) {
        self.bits[y * self.words + x / 64] |= 1 << (x % 64);
    }

    fn get(&self, x: usize, y: usize) -> bool {
        self.bits[y * self.words + x / 64] >> (x % 64) & 1 == 1
    }

    /// The mask with every block of its box set.
    fn filled(&self) -> Mask {
        let mut out = Mask::new(self.width, self.height);
        for y in 0..self.height {
            for x in 0..self.width {
                out.set(x, y);
            }
        }
        out
    }

    /// The mask grown by one block in all eight directions (one block larger on every side).
    fn dilated(&self) -> Mask {
        let mut out = Mask::new(self.width + 2, self.height + 2);
        for y in 0..self.height {
            for x in (0..self.width).filter(|&x| self.get(x, y)) {
                for (dx, dy) in (0..3).flat_map(|dx| (0..3).map(move |dy| (dx, dy))) {
                    out.set(x + dx, y + dy);
                }
            }
        }
        out
    }

    /// Bits `x..x + 64` of row `y`, zeros past the end.
    fn window(&self, x: usize, y: usize) -> u64 {
        let (word, shift) = (x / 64, x % 64);
        let row = &self.bits[y * self.words..(y + 1) * self.words];
        let low = row.get(word).map_or(0, |w| w >> shift);
        let high = if shift == 0 { 0 } else { row.get(word + 1).map_or(0, |w| w << (64 - shift)) };
        low | high
    }
}

/// The blocks of a chart at `scale`, `None` when it spans more than `grid` blocks: every block its
/// triangles may touch (their bounding boxes, refined by a separating-axis test for triangles
/// wider than a block).
fn chart_mask(
    local: &[DVec2],
    uv_faces: &[[u32; 3]],
    faces: &[u32],
    scale: f64,
    block: f64,
    grid: usize,
) -> Option<Mask> {
    let to_blocks = |k: u32| local[k as usize] * (scale / block);
    let corners: Vec<[DVec2; 3]> = faces.iter().map(|&f| uv_faces[f as usize].map(to_blocks)).collect();
    let extent = corners.iter().flatten().fold(DVec2::ZERO, |m, p| m.max(*p));
    // Larger than the atlas (or not a number): no mask to build.
    if !(extent.max_element() < grid as f64) {
        return None;
    }
    let mut mask = Mask::new(extent.x as usize + 1, extent.y as usize + 1);
    for tri in &corners {
        let low = tri[0].min(tri[1]).min(tri[2]).max(DVec2::ZERO).floor();
        let high = tri[0].max(tri[1]).max(tri[2]).floor();
        let small = high.x - low.x <= 1.0 && high.y - low.y <= 1.0;
        for y in low.y as usize..=high.y as usize {
            for x in low.x as usize..=high.x as usize {
                if small || touches_block(tri, DVec2::new(x as f64, y as f64)) {
                    mask.set(x, y);
                }
            }
        }
    }
    Some(mask)
}

/// Whether a triangle meets the unit square at `corner` (boundaries included).
fn touches_block(tri: &[DVec2; 3], corner: DVec2) -> bool {
    let square = [corner, corner + DVec2::X, corner + DVec2::ONE, corner + DVec2::Y];
    let separated = |n: DVec2| {
        let (t_low, t_high) =
            tri.iter().map(|p| p.dot(n)).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), d| (l.min(d), h.max(d)));
        let (s_low, s_high) =
            square.iter().map(|p| p.dot(n)).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), d| (l.min(d), h.max(d)));
        t_high < s_low || s_high < t_low
    };
    let axes = [DVec2::X, DVec2::Y, (tri[1] - tri[0]).perp(), (tri[2] - tri[1]).perp(), (tri[0] - tri[2]).perp()];
    !axes.into_iter().any(separated)
}

/// Places every chart's mask, largest first, at the first free spot in row order. Returns the
/// origin of every chart in blocks, or `None` when one does not fit in the `grid`-block square.
fn place(
    local: &[DVec2],
    uv_faces: &[[u32; 3]],
    chart_faces: &[Vec<u32>],
    sizes: &[DVec2],
    scale: f64,
    block: f64,
    grid: usize,
) -> Option<Vec<DVec2>> {
    let masks: Vec<Mask> = chart_faces
        .par_iter()
        .zip(sizes)
        .map(|(faces, &size)| chart_mask(local, uv_faces, faces, chart_scale(size, scale), block, grid))
        .collect::<Option<_>>()?;
    let mut order: Vec<usize> = (0..masks.len()).collect();
    order.sort_by_key(|&c| (std::cmp::Reverse(masks[c].width * masks[c].height), c));
    // The occupancy has a free ring one block wide around the atlas, where dilated masks may hang.
    let mut occupied = Mask::new(grid + 2, grid + 2);
    let mut origins = vec![DVec2::ZERO; masks.len()];
    // Where the search for a solid rectangle of a given size stopped: nothing earlier can hold it.
    let mut resume: std::collections::HashMap<(usize, usize), usize> = std::collections::HashMap::new();
    for chart in order {
        let mask = &masks[chart];
        // Small charts are placed as their whole box: it costs them little room and lets their
        // search resume where the last box of their size was placed.
        let boxed;
        let mask = if mask.width * mask.height <= SMALL_BOX_BLOCKS {
            boxed = mask.filled();
            &boxed
        } else {
            mask
        };
        let grown = mask.dilated();
        let solid = mask.bits.iter().enumerate().all(|(k, &w)| w.count_ones() as usize == full_bits(mask, k));
        let start = if solid { resume.get(&(mask.width, mask.height)).copied().unwrap_or(0) } else { 0 };
        let span = grid - mask.width + 1;
        let spot = (start..span * (grid - mask.height + 1)).find(|&k| fits(&occupied, &grown, k % span, k / span))?;
        if solid {
            resume.insert((mask.width, mask.height), spot);
        }
        let (x, y) = (spot % span, spot / span);
        for my in 0..mask.height {
            for mx in (0..mask.width).filter(|&mx| mask.get(mx, my)) {
                occupied.set(x + 1 + mx, y + 1 + my);
            }
        }
        origins[chart] = DVec2::new(x as f64, y as f64);
    }
    Some(origins)
}

/// Bits of word `k` of a mask that lie inside its width.
fn full_bits(mask: &Mask, k: usize) -> usize {
    let column = (k % mask.words) * 64;
    (mask.width - column).min(64)
}

/// Whether the dilated mask `grown`, its corner at `(x, y)` of the occupancy, meets nothing.
fn fits(occupied: &Mask, grown: &Mask, x: usize, y: usize) -> bool {
    (0..grown.height).all(|row| {
        (0..grown.words).all(|k| occupied.window(x + 64 * k, y + row) & grown.bits[row * grown.words + k] == 0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles per unit square at each `cell`, corners shared within a chart.
    fn squares(
        cells: &[(f64, f64)],
        chart: u32,
        uvs: &mut Vec<DVec2>,
        uv_faces: &mut Vec<[u32; 3]>,
        uv_chart: &mut Vec<u32>,
    ) {
        for &(x, y) in cells {
            let base = uvs.len() as u32;
            uvs.extend([
                DVec2::new(x, y),
                DVec2::new(x + 1.0, y),
                DVec2::new(x + 1.0, y + 1.0),
                DVec2::new(x, y + 1.0),
            ]);
            uv_chart.extend([chart; 4]);
            uv_faces.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
        }
    }

    #[test]
    fn charts_keep_their_shape_and_their_gutters_and_nest_as_bitmaps() {
        let (mut uvs, mut uv_faces, mut uv_chart) = (Vec::new(), Vec::new(), Vec::new());
        // A large L (its box is a third empty) and sixteen small squares of a ninth of its side.
        let l_cells: Vec<(f64, f64)> = (0..3).flat_map(|i| [(i as f64, 0.0), (0.0, i as f64)]).collect();
        squares(&l_cells, 0, &mut uvs, &mut uv_faces, &mut uv_chart);
        for c in 1..=16 {
            let start = uvs.len();
            squares(&[(5.0 * c as f64, 0.0)], c, &mut uvs, &mut uv_faces, &mut uv_chart);
            for uv in &mut uvs[start..] {
                *uv /= 3.0;
            }
        }
        let before = uvs.clone();
        let (resolution, padding) = (128, 2.0);
        let scale = pack(&mut uvs, &uv_faces, &uv_chart, 17, resolution, padding).expect("packs");
        let texels: Vec<DVec2> = uvs.iter().map(|uv| *uv * resolution as f64).collect();
        assert!(texels.iter().all(|t| t.min_element() >= 0.0 && t.max_element() <= resolution as f64));
        for face in &uv_faces {
            let (a, b) = (face[0] as usize, face[2] as usize);
            let (original, packed) = (before[a].distance(before[b]), texels[a].distance(texels[b]));
            assert!((packed - original * scale).abs() < 1e-9, "a chart changed shape");
        }
        for a in 0..uvs.len() {
            for b in 0..uvs.len() {
                if uv_chart[a] != uv_chart[b] {
                    let gap = (texels[a] - texels[b]).abs().max_element();
                    assert!(gap >= padding - 1e-9, "charts {} and {} are {gap} texels apart", uv_chart[a], uv_chart[b]);
                }
            }
        }
        // Boxes could not fill more than 5/9 of the L's box; the small charts sit in its notch.
        let l_box =
            texels[..24].iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(l, h), t| (l.min(*t), h.max(*t)));
        let nested =
            (24..uvs.len()).filter(|&k| texels[k].cmpgt(l_box.0).all() && texels[k].cmplt(l_box.1).all()).count();
        assert!(nested > 0, "no small chart inside the L's box");
    }

    #[test]
    fn charts_too_narrow_for_a_texel_are_enlarged() {
        let (mut uvs, mut uv_faces, mut uv_chart) = (Vec::new(), Vec::new(), Vec::new());
        squares(&[(0.0, 0.0)], 0, &mut uvs, &mut uv_faces, &mut uv_chart);
        let start = uvs.len();
        squares(&[(3.0, 0.0)], 1, &mut uvs, &mut uv_faces, &mut uv_chart);
        for uv in &mut uvs[start..] {
            *uv = DVec2::new(uv.x * 0.01, uv.y * 0.001);
        }
        let scale = pack(&mut uvs, &uv_faces, &uv_chart, 2, 64, 2.0).expect("packs");
        let texels = |k: usize| uvs[k] * 64.0;
        assert!((texels(2) - texels(0)).x > 0.8 * scale, "the large chart keeps the atlas's scale");
        let narrow = (texels(start + 2) - texels(start)).abs().min_element();
        assert!(narrow >= MIN_CHART_TEXELS - 1e-9, "the small chart is {narrow} texels narrow");
    }

    #[test]
    fn too_many_charts_for_the_resolution_do_not_pack() {
        let (mut uvs, mut uv_faces, mut uv_chart) = (Vec::new(), Vec::new(), Vec::new());
        for c in 0..300 {
            squares(&[(2.0 * c as f64, 0.0)], c, &mut uvs, &mut uv_faces, &mut uv_chart);
        }
        assert!(pack(&mut uvs, &uv_faces, &uv_chart, 300, 32, 4.0).is_none());
    }
}
