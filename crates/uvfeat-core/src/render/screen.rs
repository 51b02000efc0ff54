//! Z-buffer rasterisation of a mesh seen on screen, for the 3D pictures (`shaded_view` shades
//! and colours what this finds, band by band).
//!
//! Pixel `(x, y)` (x right, y down) is sampled at its centre `(x + 0.5, y + 0.5)`; a triangle
//! covers it when its three barycentric weights are at least `-1e-9` (a hair of tolerance, so a
//! pixel on an edge two triangles share is never lost to rounding); the nearest triangle (largest
//! screen `z`, towards the viewer) wins, the first in face order on an exact tie. Rows are
//! rasterised in parallel bands, each from the list of faces that reach it, in face order, so the
//! picture does not depend on the number of threads.

use crate::error::Result;
use crate::mesh::checked_indices;
use rayon::prelude::*;

/// Rows per band of the parallel rasterisation.
pub(super) const BAND_ROWS: usize = 16;

/// No triangle covers the pixel.
pub const NO_FACE: i64 = -1;

/// The nearest triangle under every pixel of a `height x width` picture, row-major from the top.
#[derive(Debug, Clone)]
pub struct ScreenFragments {
    /// Face id per pixel, [`NO_FACE`] where no triangle covers it.
    pub face: Vec<i64>,
    /// Barycentric weights of the face's three corners at the pixel centre (zero where uncovered).
    pub weights: Vec<[f64; 3]>,
}

/// A face's barycentric weights of corners 0 and 1 and its depth, as affine functions of the
/// pixel position relative to corner 2, and the pixels of its bounding box.
struct ScreenTriangle {
    corner: [f64; 3],
    w0: [f64; 2],
    w1: [f64; 2],
    depth: [f64; 2],
    columns: (usize, usize),
    rows: (usize, usize),
}

impl ScreenTriangle {
    fn new([a, b, c]: [[f64; 3]; 3], height: usize, width: usize) -> Option<Self> {
        if ![a, b, c].iter().flatten().all(|v| v.is_finite()) {
            return None;
        }
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        // Without area, or so large that the weights would not be numbers: nothing to draw.
        if area == 0.0 || !area.is_finite() {
            return None;
        }
        let inverse = 1.0 / area;
        let span = |k: usize, size: usize| {
            let low = (a[k].min(b[k]).min(c[k]) - 0.5).ceil().max(0.0);
            let high = (a[k].max(b[k]).max(c[k]) - 0.5).floor().min(size as f64 - 1.0);
            (low <= high).then_some((low as usize, high as usize))
        };
        Some(Self {
            corner: c,
            w0: [(b[1] - c[1]) * inverse, (c[0] - b[0]) * inverse],
            w1: [(c[1] - a[1]) * inverse, (a[0] - c[0]) * inverse],
            depth: [a[2] - c[2], b[2] - c[2]],
            columns: span(0, width)?,
            rows: span(1, height)?,
        })
    }
}

/// Rasterises `faces` (corner indices into `screen`) whose corners are in pixel units:
/// `screen[v] = [x right, y down, z towards the viewer]`. Faces with a non-finite corner or no
/// area on screen draw nothing.
///
/// # Errors
/// [`crate::UvfeatError::IndexOutOfRange`] naming the first face with a corner not in `screen`.
pub fn rasterise_screen(
    screen: &[[f64; 3]],
    faces: &[[i64; 3]],
    height: usize,
    width: usize,
) -> Result<ScreenFragments> {
    let faces = checked_indices(faces, screen.len(), "screen point")?;
    let bands = rasterise_in_bands(screen, &faces, height, width, BAND_ROWS, |_, band| (band.face, band.weights));
    let (face, weights): (Vec<_>, Vec<_>) = bands.into_iter().unzip();
    Ok(ScreenFragments { face: face.concat(), weights: weights.concat() })
}

/// The fragments of one band of rows, row-major (see [`ScreenFragments`]).
pub(super) struct BandFragments {
    /// Face id per pixel, [`NO_FACE`] where no triangle covers it.
    pub face: Vec<i64>,
    /// Barycentric weights of the face's three corners at the pixel centre.
    pub weights: Vec<[f64; 3]>,
}

/// Rasterises `faces` as [`rasterise_screen`] does, in bands of `band_rows` rows from the top, and
/// hands each band's fragments with its first row to `consume` as soon as they are drawn (in
/// parallel; results in band order), so that a caller shading them reads them while they are in
/// cache instead of from a whole picture's buffers (32 bytes a pixel, 19 MB for a 3D view).
pub(super) fn rasterise_in_bands<R: Send>(
    screen: &[[f64; 3]],
    faces: &[[u32; 3]],
    height: usize,
    width: usize,
    band_rows: usize,
    consume: impl Fn(usize, BandFragments) -> R + Sync,
) -> Vec<R> {
    let band_rows = band_rows.max(1);
    let triangles: Vec<Option<ScreenTriangle>> =
        faces.par_iter().map(|f| ScreenTriangle::new(f.map(|v| screen[v as usize]), height, width)).collect();
    let mut band_faces: Vec<Vec<u32>> = vec![Vec::new(); height.div_ceil(band_rows)];
    for (f, triangle) in triangles.iter().enumerate() {
        if let Some(t) = triangle {
            for band in band_faces.iter_mut().take(t.rows.1 / band_rows + 1).skip(t.rows.0 / band_rows) {
                band.push(f as u32);
            }
        }
    }
    band_faces
        .par_iter()
        .enumerate()
        .map(|(band, faces_here)| {
            let first_row = band * band_rows;
            let rows = band_rows.min(height - first_row);
            let pixels = rows * width;
            let mut fragments = BandFragments { face: vec![NO_FACE; pixels], weights: vec![[0.0; 3]; pixels] };
            let mut depth_buffer = vec![f64::NEG_INFINITY; pixels];
            for &f in faces_here {
                let t = triangles[f as usize].as_ref().expect("only faces with pixels are binned");
                for y in t.rows.0.max(first_row)..=t.rows.1.min(first_row + rows - 1) {
                    let dy = y as f64 + 0.5 - t.corner[1];
                    for x in t.columns.0..=t.columns.1 {
                        let dx = x as f64 + 0.5 - t.corner[0];
                        let w0 = t.w0[0] * dx + t.w0[1] * dy;
                        let w1 = t.w1[0] * dx + t.w1[1] * dy;
                        let w2 = 1.0 - w0 - w1;
                        if w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9 {
                            continue;
                        }
                        let depth = t.corner[2] + w0 * t.depth[0] + w1 * t.depth[1];
                        let pixel = (y - first_row) * width + x;
                        if depth > depth_buffer[pixel] {
                            depth_buffer[pixel] = depth;
                            fragments.face[pixel] = i64::from(f);
                            fragments.weights[pixel] = [w0, w1, w2];
                        }
                    }
                }
            }
            consume(first_row, fragments)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nearest_triangle_wins_in_any_order_and_on_any_number_of_threads() {
        // Two overlapping right triangles, the second nearer; 55 pixel centres on or below the diagonal.
        let screen =
            [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 10.0, 0.0], [0.0, 0.0, 1.0], [10.0, 0.0, 1.0], [0.0, 10.0, 1.0]];
        for faces in [[[0, 1, 2], [3, 4, 5]], [[3, 4, 5], [0, 1, 2]]] {
            let nearer = faces.iter().position(|f| f[0] == 3).unwrap() as i64;
            let fragments = rasterise_screen(&screen, &faces, 10, 10).unwrap();
            let covered: Vec<usize> = (0..100).filter(|&p| fragments.face[p] != NO_FACE).collect();
            assert_eq!(covered.len(), 55);
            assert!(covered.iter().all(|&p| fragments.face[p] == nearer));
            assert!(covered.iter().all(|&p| (fragments.weights[p].iter().sum::<f64>() - 1.0).abs() < 1e-12));
        }
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let faces = [[0, 1, 2], [3, 4, 5]];
        let tall: Vec<[f64; 3]> = screen.iter().map(|p| [p[0], 4.0 * p[1], p[2]]).collect();
        let one = pool.install(|| rasterise_screen(&tall, &faces, 40, 10)).unwrap();
        let many = rasterise_screen(&tall, &faces, 40, 10).unwrap();
        assert_eq!(one.face, many.face);
    }

    #[test]
    fn faces_off_screen_or_without_area_draw_nothing() {
        let screen = [
            [-5.0, -5.0, 0.0],
            [-1.0, -5.0, 0.0],
            [-5.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
            [f64::NAN, 0.0, 0.0],
        ];
        let fragments = rasterise_screen(&screen, &[[0, 1, 2], [3, 4, 3], [3, 4, 5]], 8, 8).unwrap();
        assert!(rasterise_screen(&screen, &[[0, 1, 6]], 8, 8).is_err());
        assert!(fragments.face.iter().all(|&f| f == NO_FACE));
    }
}
