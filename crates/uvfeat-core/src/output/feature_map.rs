//! Feature maps over the computation texture (DESIGN.md §1.9): every texel centre of a `W_c x W_c`
//! grid is a point `s` where all requested features are evaluated, in parallel over tiles.

use super::sheet_area::sheet_area;
use crate::atlas::Atlas;
use crate::cancel;
use crate::error::Result;
use crate::evaluation::{
    evaluate_point, evaluate_tile, integration, prepare, texel_uv, Integration, Patterns, PixelResult,
};
use crate::features::{CurvatureMethod, Feature};
use crate::sampling::Placement;
use crate::settings::ComputeSettings;
use rayon::prelude::*;

/// Side of the square tiles of texels evaluated together, so that their neighbourhoods' reads of
/// the buffers stay in cache (16 measured faster than 8 and as fast as 32), and the smallest side
/// of the shared lattice's tiles.
const TILE: usize = 16;

/// Largest side of the shared lattice's tiles.
const LARGEST_TILE: usize = 64;

/// The side of the tiles: for the shared lattice, about the ball's radius in texels (a power of
/// two from [`TILE`] to [`LARGEST_TILE`]). A tile's lattice holds the texels' disks around the
/// tile; where the disks are much wider than the tile, each texel's share of the lattice's points
/// (each located, many across seams) falls with the tile's area, while the run of points each
/// texel sums grows only with its side (xatlas torus at r = 16 %: 0.96 s with 16-texel tiles,
/// 0.74 s with 64; at 2 % 16 and 64 alike).
fn tile_side(ball: f64, shared: bool) -> usize {
    if !shared {
        return TILE;
    }
    let below = if ball >= 1.0 { 1usize << ball.log2().floor() as u32 } else { 1 };
    below.clamp(TILE, LARGEST_TILE)
}

/// The texels `j * w + i` of each `side`² tile of a `w`² texture, tile after tile: the parallel
/// evaluation works tile by tile.
fn tiles(w: usize, side: usize) -> Vec<Vec<usize>> {
    let tiles = w.div_ceil(side);
    (0..tiles * tiles)
        .map(|tile| {
            let (ti, tj) = (tile % tiles * side, tile / tiles * side);
            (tj..(tj + side).min(w)).flat_map(|j| (ti..(ti + side).min(w)).map(move |i| j * w + i)).collect()
        })
        .collect()
}

/// The ball's radius in computation texels where the atlas is stretched as on average: `r /
/// sqrt(J)` in parametric units, with `J` the atlas's surface area over its parametric area.
fn ball_texels(atlas: &Atlas, settings: &ComputeSettings) -> f64 {
    let topology = &atlas.topology;
    let (surface, parametric) = atlas
        .patches()
        .faces
        .par_iter()
        .enumerate()
        .filter(|(_, patch)| patch.chart >= 0)
        .map(|(f, patch)| {
            let [a, b, c] = topology.corner_uvs(f);
            let uv_area = 0.5 * (b - a).perp_dot(c - a).abs();
            (f64::from(patch.area_element) * uv_area, uv_area)
        })
        .reduce(|| (0.0, 0.0), |x, y| (x.0 + y.0, x.1 + y.1));
    settings.radius / (surface / parametric).sqrt() * settings.resolution as f64
}

/// Neighbourhood area ratio, in units of one sheet's area (see `output/sheet_area.rs`), above
/// which a neighbourhood holds more than one sheet: one sheet gives about 1 at any curvature, two
/// sheets about 2, overlapping seam routes up to about 1.1.
pub const SEVERAL_SHEETS: f32 = 1.5;

/// Totals over a map, for reports.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MapSummary {
    /// Texels on a chart (where features were evaluated).
    pub texels: usize,
    /// Fraction of those that ran stage 2 of adaptive sampling.
    pub second_stage_fraction: f64,
    /// Fraction whose principal curvatures needed `H^2 - K` clamped.
    pub clamped_fraction: f64,
    /// Missing samples over all pattern samples drawn.
    pub missing_fraction: f64,
    /// Texels whose neighbourhood was cut by a mesh border (some samples dropped there).
    pub truncated_texels: usize,
    /// Texels whose neighbourhood holds more than one sheet of the surface (area ratio above
    /// [`SEVERAL_SHEETS`] times one sheet's): the ball is wider than a thin part there.
    pub several_sheet_texels: usize,
    /// Mean accepted samples per texel.
    pub mean_valid: f64,
}

/// The requested features on a `resolution`² texture, texel `(i, j)` at index `j * W_c + i`
/// (v up), NaN outside charts, plus per-texel diagnostics.
#[derive(Debug, Clone)]
pub struct FeatureMaps {
    /// `W_c`.
    pub resolution: usize,
    /// Features, in the order of `values`.
    pub features: Vec<Feature>,
    /// One map per feature.
    pub values: Vec<Vec<f32>>,
    /// One standard-error map per feature, when requested.
    pub standard_errors: Option<Vec<Vec<f32>>>,
    /// Chart of each texel centre (-1 off the charts).
    pub chart: Vec<i32>,
    /// Accepted samples per texel.
    pub n_valid: Vec<u32>,
    /// Samples whose relocation failed.
    pub n_missing: Vec<u32>,
    /// Samples dropped at a mesh border.
    pub n_border: Vec<u32>,
    /// Texels that ran stage 2 (adaptive sampling).
    pub second_stage: Vec<bool>,
    /// Principal directions `[d1, d2]` of every texel (unit 3D vectors, a line field: the sign is
    /// arbitrary), with the curvature method `Fit`; NaN off the charts.
    pub directions: Option<Vec<[[f32; 3]; 2]>>,
    /// Relative RMS residual of the fit per texel, with the curvature method `Fit`.
    pub fit_residual: Option<Vec<f32>>,
    /// Neighbourhood area over `pi r^2` per texel (see [`PixelResult::area_ratio`]).
    pub area_ratio: Vec<f32>,
    /// The area one sheet of the surface holds in each texel's ball, over `pi r^2` (1 for a smooth
    /// mesh, more for a rough one; NaN off the charts): the unit of the several-sheets flag.
    pub sheet_area: Vec<f32>,
    /// Totals.
    pub summary: MapSummary,
}

impl FeatureMaps {
    /// Evaluates `settings.features` at every texel of the computation texture.
    ///
    /// # Errors
    /// [`crate::UvfeatError::InvalidParameter`] from [`ComputeSettings::validate`].
    pub fn compute(atlas: &Atlas, settings: &ComputeSettings) -> Result<Self> {
        settings.validate()?;
        let w = settings.resolution;
        let patterns = Patterns::new(settings);
        prepare(atlas, settings);
        let shared = integration(atlas, settings) == Integration::SharedLattice;
        let ball = ball_texels(atlas, settings);
        let tiles = tiles(w, tile_side(ball, shared));
        // Kept tile by tile: flattening them into one vector copied 31 MB (a fifth of a 200K-face
        // sphere's features in one thread).
        let results: Vec<Vec<PixelResult>> = tiles
            .par_iter()
            .map_init(Vec::new, |scratch, texels| {
                if cancel::requested() {
                    return Vec::new();
                }
                if shared {
                    return evaluate_tile(atlas, settings, &patterns, texels, scratch);
                }
                let placement = |t: usize| Placement::of_pixel((t % w) as u32, (t / w) as u32, settings.seed);
                texels
                    .iter()
                    .map(|&t| evaluate_point(atlas, texel_uv(t, w), placement(t), settings, &patterns, scratch))
                    .collect()
            })
            .collect();
        cancel::check()?;
        // The results by texel, as references: moving the 120-byte results into texel order took
        // a tenth of a 200K-face torus's features.
        let mut pixels = vec![&PixelResult::EMPTY; w * w];
        for (texels, tile) in tiles.iter().zip(&results) {
            for (&t, result) in texels.iter().zip(tile) {
                pixels[t] = result;
            }
        }
        let chart: Vec<i32> = (0..w * w).into_par_iter().map(|t| atlas.chart_at(texel_uv(t, w))).collect();
        // One pass over the results, band by band: a pass per column read the 120-byte results
        // again each time (50 ms of a 200K-face torus's 0.35 s).
        let sheet_area = sheet_area(atlas, &chart, w, ball.round().max(1.0) as usize);
        let bands: Vec<Columns> = pixels
            .par_chunks(w * TILE)
            .zip(sheet_area.par_chunks(w * TILE))
            .map(|(band, sheets)| Columns::of(band, sheets, settings))
            .collect();
        let columns = bands.into_iter().fold(Columns::new(settings), Columns::append);
        Ok(columns.into_maps(chart, sheet_area, settings))
    }
}

/// The maps' columns over a run of texels, and the totals of the [`MapSummary`].
struct Columns {
    values: Vec<Vec<f32>>,
    errors: Option<Vec<Vec<f32>>>,
    directions: Option<Vec<[[f32; 3]; 2]>>,
    fit_residual: Option<Vec<f32>>,
    n_valid: Vec<u32>,
    n_missing: Vec<u32>,
    n_border: Vec<u32>,
    second_stage: Vec<bool>,
    area_ratio: Vec<f32>,
    totals: Totals,
}

/// Sums over the evaluated texels (those with accepted samples).
#[derive(Default)]
struct Totals {
    evaluated: usize,
    second_stage: usize,
    clamped: usize,
    missing: u64,
    drawn: u64,
    truncated: usize,
    several_sheets: usize,
    valid: u64,
}

impl Columns {
    fn new(settings: &ComputeSettings) -> Self {
        let fitted = settings.method == CurvatureMethod::Fit;
        let per_feature = || vec![Vec::new(); settings.features.len()];
        Self {
            values: per_feature(),
            errors: settings.standard_errors.then(per_feature),
            directions: fitted.then(Vec::new),
            fit_residual: fitted.then(Vec::new),
            n_valid: Vec::new(),
            n_missing: Vec::new(),
            n_border: Vec::new(),
            second_stage: Vec::new(),
            area_ratio: Vec::new(),
            totals: Totals::default(),
        }
    }

    /// The columns of `pixels`, whose balls hold `sheet_area` for one sheet.
    fn of(pixels: &[&PixelResult], sheet_area: &[f32], settings: &ComputeSettings) -> Self {
        let mut columns = Self::new(settings);
        for (p, &sheet) in pixels.iter().zip(sheet_area) {
            for (column, feature) in columns.values.iter_mut().zip(&settings.features) {
                column.push(p.values[feature.index()]);
            }
            for (column, feature) in columns.errors.iter_mut().flatten().zip(&settings.features) {
                column.push(p.errors[feature.index()]);
            }
            columns.directions.iter_mut().for_each(|d| d.push(p.directions));
            columns.fit_residual.iter_mut().for_each(|r| r.push(p.residual));
            columns.n_valid.push(p.counts.valid);
            columns.n_missing.push(p.counts.missing);
            columns.n_border.push(p.counts.border);
            columns.second_stage.push(p.second_stage);
            columns.area_ratio.push(p.area_ratio);
            if p.counts.valid > 0 {
                let totals = &mut columns.totals;
                totals.evaluated += 1;
                totals.second_stage += usize::from(p.second_stage);
                totals.clamped += usize::from(p.clamped);
                totals.missing += u64::from(p.counts.missing);
                totals.drawn += u64::from(p.counts.valid + p.counts.missing + p.counts.border);
                totals.truncated += usize::from(p.counts.border > 0);
                totals.several_sheets += usize::from(p.area_ratio > SEVERAL_SHEETS * sheet);
                totals.valid += u64::from(p.counts.valid);
            }
        }
        columns
    }

    /// `self` followed by `next`.
    fn append(mut self, next: Self) -> Self {
        self.values.iter_mut().zip(next.values).for_each(|(to, from)| to.extend(from));
        if let (Some(to), Some(from)) = (&mut self.errors, next.errors) {
            to.iter_mut().zip(from).for_each(|(to, from)| to.extend(from));
        }
        if let (Some(to), Some(from)) = (&mut self.directions, next.directions) {
            to.extend(from);
        }
        if let (Some(to), Some(from)) = (&mut self.fit_residual, next.fit_residual) {
            to.extend(from);
        }
        self.n_valid.extend(next.n_valid);
        self.n_missing.extend(next.n_missing);
        self.n_border.extend(next.n_border);
        self.second_stage.extend(next.second_stage);
        self.area_ratio.extend(next.area_ratio);
        let (to, from) = (&mut self.totals, next.totals);
        to.evaluated += from.evaluated;
        to.second_stage += from.second_stage;
        to.clamped += from.clamped;
        to.missing += from.missing;
        to.drawn += from.drawn;
        to.truncated += from.truncated;
        to.several_sheets += from.several_sheets;
        to.valid += from.valid;
        self
    }

    fn into_maps(self, chart: Vec<i32>, sheet_area: Vec<f32>, settings: &ComputeSettings) -> FeatureMaps {
        let totals = &self.totals;
        let n = totals.evaluated.max(1) as f64;
        let summary = MapSummary {
            texels: totals.evaluated,
            second_stage_fraction: totals.second_stage as f64 / n,
            clamped_fraction: totals.clamped as f64 / n,
            missing_fraction: totals.missing as f64 / totals.drawn.max(1) as f64,
            truncated_texels: totals.truncated,
            several_sheet_texels: totals.several_sheets,
            mean_valid: totals.valid as f64 / n,
        };
        FeatureMaps {
            resolution: settings.resolution,
            features: settings.features.clone(),
            values: self.values,
            standard_errors: self.errors,
            chart,
            n_valid: self.n_valid,
            n_missing: self.n_missing,
            n_border: self.n_border,
            second_stage: self.second_stage,
            directions: self.directions,
            fit_residual: self.fit_residual,
            area_ratio: self.area_ratio,
            sheet_area,
            summary,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::features::Feature;
    use crate::mesh::{Topology, TriangleMesh};
    use crate::shapes::plane;
    use crate::AtlasOptions;
    use std::sync::Arc;

    #[test]
    fn the_shared_lattice_tiles_follow_the_ball_in_texels() {
        // A plane of side 2 laid out on 0.96 of the unit square: 2 / 0.96 object units per
        // parametric unit, so a ball of radius r spans r * 0.48 * 512 computation texels.
        let shape = plane(2.0, 32);
        let mesh = TriangleMesh::new(&shape.positions, &shape.faces, &shape.uvs, &shape.uv_faces).unwrap();
        let topology = Arc::new(Topology::build(&mesh, 0.0).unwrap());
        let atlas =
            Atlas::new(topology, &mesh.positions, &AtlasOptions { resolution: 256, ..Default::default() }).unwrap();
        let side = |radius: f64| {
            let settings = ComputeSettings::new(vec![Feature::MeanCurvature], radius);
            let ball = ball_texels(&atlas, &settings);
            (ball, tile_side(ball, true), tile_side(ball, false))
        };
        let (ball, shared, per_texel) = side(0.2);
        assert!((ball - 0.2 * 0.48 * 512.0).abs() < 1e-6 * ball, "{ball}");
        assert_eq!((shared, per_texel), (32, TILE));
        assert_eq!(side(0.05).1, TILE);
        assert_eq!(side(0.3).1, 64);
        assert_eq!(side(2.0).1, LARGEST_TILE);
    }
}
