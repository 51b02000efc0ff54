//! A picture of per-vertex values on the mesh itself, for the 3D pictures (`uvfeat.render`): the
//! faces the viewer can see, rasterised band by band (`screen.rs`), coloured per pixel by the
//! barycentric value through a colour table, shaded by a headlight on the interpolated vertex
//! normal, and averaged down from supersampled pixels.
//!
//! It was NumPy over the fragments, about 0.25 s per view of a 200K-face mesh (three views are
//! drawn by `uvfeat compute`): here in parallel bands of rows, each shaded as soon as it is drawn.

use super::screen::{rasterise_in_bands, BAND_ROWS};
use crate::error::{Result, UvfeatError};
use crate::mesh::{checked_indices, vertex_normals};
use glam::DVec3;
use rayon::prelude::*;

/// Brightness of a surface seen edge-on (the headlight lights what faces the viewer fully).
pub const AMBIENT: f64 = 0.35;

/// Colour of a pixel whose value is not a number.
const NAN_GREY: [f64; 3] = [0.5; 3];

/// How values become colours: `palette` spans `[low, high]` in equal steps, values outside are
/// clamped, and a value at fraction `t` of the range takes entry `min(floor(t n), n - 1)` (as a
/// matplotlib colormap of `n` entries looks it up).
#[derive(Debug, Clone, Copy)]
pub struct ColourScale<'a> {
    /// RGB entries in `[0, 1]`, from `low` to `high`.
    pub palette: &'a [[f64; 3]],
    /// The value of the first entry.
    pub low: f64,
    /// The value of the last entry's end (a range without width takes 1).
    pub high: f64,
}

impl ColourScale<'_> {
    fn colour(&self, value: f64) -> [f64; 3] {
        if !value.is_finite() {
            return NAN_GREY;
        }
        let span = if self.high > self.low { self.high - self.low } else { 1.0 };
        let t = ((value - self.low) / span).clamp(0.0, 1.0);
        let n = self.palette.len();
        self.palette[((t * n as f64) as usize).min(n - 1)]
    }
}

/// Where the picture lies in view coordinates (x right, y up, z towards the viewer).
#[derive(Debug, Clone, Copy)]
pub struct ViewFrame {
    /// View x of the picture's left edge.
    pub left: f64,
    /// View y of the picture's top edge.
    pub top: f64,
    /// Rasterised pixels per view unit.
    pub scale: f64,
    /// Rasterised rows (before averaging down).
    pub height: usize,
    /// Rasterised columns (before averaging down).
    pub width: usize,
    /// Rasterised pixels per picture pixel along each axis (edges are antialiased by averaging).
    pub supersampling: usize,
}

/// Which side of the faces the viewer can see.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Front {
    /// Both: an open mesh shows its inside through its borders.
    Both,
    /// The side the faces turn counter-clockwise on (a closed mesh wound outwards).
    CounterClockwise,
    /// The other side (a closed mesh wound inwards).
    Clockwise,
}

/// The `(height / s) x (width / s)` RGBA picture (row-major from the top, rounded up; colour 0
/// and alpha 0 off the mesh) of `values` per vertex on `faces`, whose vertices have view
/// coordinates `view`. Vertex normals are the area-weighted normals of the faces drawn.
///
/// # Errors
/// [`UvfeatError::IndexOutOfRange`] for a corner not in `view`; [`UvfeatError::InvalidParameter`]
/// when `values` does not have one value per vertex, the palette is empty or the supersampling is 0.
pub fn shaded_view(
    view: &[[f64; 3]],
    faces: &[[i64; 3]],
    values: &[f64],
    colours: &ColourScale,
    frame: &ViewFrame,
    front: Front,
) -> Result<Vec<[f64; 4]>> {
    let invalid = |name: &'static str, reason: String| Err(UvfeatError::InvalidParameter { name, reason });
    if values.len() != view.len() {
        return invalid("values", format!("{} values for {} vertices", values.len(), view.len()));
    }
    if colours.palette.is_empty() {
        return invalid("palette", "no colours".into());
    }
    if frame.supersampling == 0 {
        return invalid("supersampling", "0 pixels per picture pixel".into());
    }
    let corners = checked_indices(faces, view.len(), "vertex")?;
    let screen: Vec<[f64; 3]> =
        view.par_iter().map(|p| [(p[0] - frame.left) * frame.scale, (frame.top - p[1]) * frame.scale, p[2]]).collect();
    let drawn: Vec<[u32; 3]> = corners.into_par_iter().filter(|t| faces_viewer(&screen, t, front)).collect();
    let points: Vec<DVec3> = view.iter().map(|p| DVec3::from_array(*p)).collect();
    let normals = vertex_normals(&points, &drawn);
    // Bands of whole blocks of supersampled rows, each shaded and averaged down as it is drawn.
    let s = frame.supersampling;
    let band_rows = s * BAND_ROWS.div_ceil(s);
    let bands = rasterise_in_bands(&screen, &drawn, frame.height, frame.width, band_rows, |first_row, band| {
        let pixel = |y: usize, x: usize| -> [f64; 4] {
            let k = (y - first_row) * frame.width + x;
            let Ok(f) = usize::try_from(band.face[k]) else { return [0.0; 4] };
            let (t, w) = (drawn[f].map(|v| v as usize), band.weights[k]);
            let [r, g, b] = colours.colour(interpolated_value(t.map(|v| values[v]), w));
            let normal = (0..3).map(|c| w[c] * normals[t[c]]).sum::<DVec3>();
            let light = AMBIENT + (1.0 - AMBIENT) * normal.z.abs() / normal.length().max(1e-300);
            [r * light, g * light, b * light, 1.0]
        };
        let rows = band_rows.min(frame.height - first_row);
        averaged_down(frame, first_row / s..(first_row + rows).div_ceil(s), pixel)
    });
    Ok(bands.concat())
}

/// Whether face `t` can be seen from `front` (screen y points down, so a face turning
/// counter-clockwise in view coordinates turns clockwise on screen).
fn faces_viewer(screen: &[[f64; 3]], t: &[u32; 3], front: Front) -> bool {
    let [a, b, c] = t.map(|v| screen[v as usize]);
    let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    match front {
        Front::Both => true,
        Front::CounterClockwise => area <= 0.0,
        Front::Clockwise => area >= 0.0,
    }
}

/// The barycentric value over the corners whose value is known, so one unknown vertex does not
/// blank its faces (NaN only where no corner has one).
fn interpolated_value(corner_values: [f64; 3], weights: [f64; 3]) -> f64 {
    let (mut sum, mut total) = (0.0, 0.0);
    for (value, weight) in corner_values.into_iter().zip(weights).filter(|(v, _)| v.is_finite()) {
        sum += weight * value;
        total += weight;
    }
    if corner_values.iter().any(|v| v.is_finite()) {
        sum / total
    } else {
        f64::NAN
    }
}

/// Rows `rows` of the picture averaged down by `frame.supersampling` (padded with empty pixels to
/// whole blocks) from the rasterised `pixel(y, x)`, colours weighted by coverage, so edges blend
/// with the background instead of darkening.
fn averaged_down(
    frame: &ViewFrame,
    rows: std::ops::Range<usize>,
    pixel: impl Fn(usize, usize) -> [f64; 4],
) -> Vec<[f64; 4]> {
    let s = frame.supersampling;
    let width = frame.width.div_ceil(s);
    let mut picture = Vec::with_capacity(rows.len() * width);
    for row in rows {
        for column in 0..width {
            let mut sum = [0.0; 4];
            for y in (row * s..(row + 1) * s).filter(|&y| y < frame.height) {
                for x in (column * s..(column + 1) * s).filter(|&x| x < frame.width) {
                    let p = pixel(y, x);
                    (0..4).for_each(|c| sum[c] += p[c]);
                }
            }
            let alpha = sum[3] / (s * s) as f64;
            picture.push(if alpha > 0.0 {
                [sum[0] / sum[3], sum[1] / sum[3], sum[2] / sum[3], alpha]
            } else {
                [0.0; 4]
            });
        }
    }
    picture
}

#[cfg(test)]
mod tests {
    use super::*;

    const PALETTE: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [0.25, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]];

    /// A square of two triangles facing the viewer (counter-clockwise in view coordinates),
    /// covering view `[0, 1]²`, drawn into 4 x 4 pixels without supersampling.
    fn square(values: [f64; 4], front: Front, supersampling: usize, size: usize) -> Result<Vec<[f64; 4]>> {
        let view = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let frame = ViewFrame { left: 0.0, top: 1.0, scale: size as f64, height: size, width: size, supersampling };
        let colours = ColourScale { palette: &PALETTE, low: 0.0, high: 1.0 };
        shaded_view(&view, &[[0, 1, 2], [0, 2, 3]], &values, &colours, &frame, front)
    }

    #[test]
    fn values_take_the_palette_entry_of_their_share_of_the_range_clamped_and_nan_grey() {
        let colours = ColourScale { palette: &PALETTE, low: 0.0, high: 1.0 };
        let red = |v: f64| colours.colour(v)[0];
        assert_eq!([red(0.0), red(0.24), red(0.25), red(0.74), red(0.75), red(1.0)], [0.0, 0.0, 0.25, 0.5, 1.0, 1.0]);
        assert_eq!([red(-3.0), red(7.0)], [0.0, 1.0]);
        assert_eq!(colours.colour(f64::NAN), NAN_GREY);
        let pixels = square([1.0; 4], Front::CounterClockwise, 1, 4).unwrap();
        // Facing the viewer: fully lit, opaque, the top entry.
        assert!(pixels.iter().all(|p| *p == [1.0, 0.0, 0.0, 1.0]), "{pixels:?}");
    }

    #[test]
    fn faces_turned_away_are_drawn_only_when_both_sides_show() {
        let away = square([1.0; 4], Front::Clockwise, 1, 4).unwrap();
        assert!(away.iter().all(|p| *p == [0.0; 4]));
        let both = square([1.0; 4], Front::Both, 1, 4).unwrap();
        assert!(both.iter().all(|p| p[3] == 1.0));
    }

    #[test]
    fn one_unknown_corner_does_not_blank_its_faces() {
        let pixels = square([1.0, 1.0, f64::NAN, 1.0], Front::Both, 1, 4).unwrap();
        assert!(pixels.iter().all(|p| p[0] == 1.0), "{pixels:?}");
        let none = square([f64::NAN; 4], Front::Both, 1, 4).unwrap();
        assert!(none.iter().all(|p| p[..3] == NAN_GREY), "{none:?}");
    }

    #[test]
    fn averaging_down_blends_edges_with_the_background_without_darkening_them() {
        // 3 x 3 rasterised pixels averaged by 2: the last row and column are half blocks of padding.
        let pixels = square([1.0; 4], Front::Both, 2, 3).unwrap();
        assert_eq!(pixels.len(), 4);
        assert_eq!(pixels[0], [1.0, 0.0, 0.0, 1.0]);
        assert_eq!(pixels[1], [1.0, 0.0, 0.0, 0.5]);
        assert_eq!(pixels[3], [1.0, 0.0, 0.0, 0.25]);
    }

    #[test]
    fn a_picture_over_several_bands_is_whole_and_the_same_on_one_thread() {
        // 40 rows averaged by 3 are drawn in bands of 18: 14 x 14 pixels, the last row and column
        // a third covered.
        let pixels = square([1.0; 4], Front::Both, 3, 40).unwrap();
        assert_eq!(pixels.len(), 14 * 14);
        assert!(pixels[..13 * 14].chunks(14).all(|row| row[..13].iter().all(|p| *p == [1.0, 0.0, 0.0, 1.0])));
        assert!((pixels[13 * 14][3] - 1.0 / 3.0).abs() < 1e-12 && (pixels[13][3] - 1.0 / 3.0).abs() < 1e-12);
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        assert_eq!(
            pool.install(|| square([0.3, 0.9, 0.5, 0.1], Front::Both, 3, 40)).unwrap(),
            square([0.3, 0.9, 0.5, 0.1], Front::Both, 3, 40).unwrap()
        );
    }

    #[test]
    fn bad_arguments_name_the_problem() {
        let frame = ViewFrame { left: 0.0, top: 1.0, scale: 1.0, height: 2, width: 2, supersampling: 1 };
        let colours = ColourScale { palette: &PALETTE, low: 0.0, high: 1.0 };
        let view = [[0.0; 3]; 3];
        let error = |values: &[f64], faces: &[[i64; 3]], colours: &ColourScale, frame: &ViewFrame| {
            shaded_view(&view, faces, values, colours, frame, Front::Both).unwrap_err().to_string()
        };
        assert!(error(&[0.0; 2], &[[0, 1, 2]], &colours, &frame).contains("2 values for 3 vertices"));
        assert!(error(&[0.0; 3], &[[0, 1, 3]], &colours, &frame).contains("vertex"));
        let empty = ColourScale { palette: &[], ..colours };
        assert!(error(&[0.0; 3], &[[0, 1, 2]], &empty, &frame).contains("palette"));
        let zero = ViewFrame { supersampling: 0, ..frame };
        assert!(error(&[0.0; 3], &[[0, 1, 2]], &colours, &zero).contains("supersampling"));
    }
}
