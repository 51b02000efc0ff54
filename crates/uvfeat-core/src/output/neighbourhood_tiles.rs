//! The weighted neighbourhood samples of many texels at once, as flat arrays, for user-defined
//! operators `F(p, S(p))` (DESIGN.md §2.9). Tiles bound the memory: a tile holds `texels x N` samples.

use crate::atlas::Atlas;
use crate::cancel;
use crate::error::Result;
use crate::evaluation::{integration, prepare};
use crate::sampling::{
    centre_at, disk_pattern, gather_covering, gather_surfels, surfel_centre, Placement, Sample, SamplerSettings,
};
use crate::settings::ComputeSettings;
use glam::DVec2;
use rayon::prelude::*;

/// Samples of the texels of a tile, padded to `N` per texel (`valid` says which are real).
#[derive(Debug, Clone, Default)]
pub struct NeighbourhoodTile {
    /// Samples per texel `N` (the padding width).
    pub samples: usize,
    /// (T) index `j * W_c + i` of each texel of the tile that lies on a chart.
    pub texels: Vec<u32>,
    /// (T) centre `p`.
    pub centres: Vec<[f64; 3]>,
    /// (T) unit normal at `p`.
    pub centre_normals: Vec<[f64; 3]>,
    /// (T * N) sample positions `q_i` (zero where not valid).
    pub positions: Vec<[f64; 3]>,
    /// (T * N) sample normals `n_i` (zero where not valid).
    pub normals: Vec<[f64; 3]>,
    /// (T * N) surface area each sample stands for, `dA_i` (0 where not valid).
    pub areas: Vec<f64>,
    /// (T * N) which entries are accepted samples.
    pub valid: Vec<bool>,
}

/// One texel's index, centre, centre normal and samples.
type TexelSamples = (u32, [f64; 3], [f64; 3], Vec<Sample>);

/// Gathers the neighbourhoods of the texels with index in `texels` (of the `W_c`² texture).
///
/// # Errors
/// [`UvfeatError::Cancelled`](crate::error::UvfeatError::Cancelled) when [`cancel`] stopped the call.
pub fn neighbourhood_tile(
    atlas: &Atlas,
    settings: &ComputeSettings,
    texels: std::ops::Range<usize>,
) -> Result<NeighbourhoodTile> {
    let w = settings.resolution;
    let n = settings.samples;
    let pattern = disk_pattern(n, settings.seed, 0);
    let sampler = SamplerSettings { with_normals: true, ..settings.sampler() };
    prepare(atlas, settings);
    let per_texel: Vec<TexelSamples> = texels
        .into_par_iter()
        .filter_map(|t| {
            if cancel::requested() {
                return None;
            }
            let (i, j) = (t % w, t / w);
            let uv = DVec2::new((i as f64 + 0.5) / w as f64, (j as f64 + 0.5) / w as f64);
            let mut centre = centre_at(atlas, uv, settings.lookup)?;
            let mut samples = Vec::with_capacity(n);
            if integration(atlas, settings).uses_surfels() {
                centre = surfel_centre(atlas, &centre, settings.surface)?;
                gather_surfels(atlas, &centre, &sampler, &mut samples);
            } else {
                let placement = Placement::of_pixel(i as u32, j as u32, settings.seed);
                gather_covering(atlas, &centre, &pattern, placement, &sampler, settings.grow_margin, &mut samples);
            }
            Some((t as u32, centre.position.to_array(), centre.normal.to_array(), samples))
        })
        .collect();
    cancel::check()?;
    // Surfel neighbourhoods hold as many samples as the ball has surfels.
    let n = per_texel.iter().map(|(.., samples)| samples.len()).max().unwrap_or(0).max(n);
    let count = per_texel.len();
    let mut tile = NeighbourhoodTile {
        samples: n,
        texels: Vec::with_capacity(count),
        centres: Vec::with_capacity(count),
        centre_normals: Vec::with_capacity(count),
        positions: vec![[0.0; 3]; count * n],
        normals: vec![[0.0; 3]; count * n],
        areas: vec![0.0; count * n],
        valid: vec![false; count * n],
    };
    for (k, (t, p, normal, samples)) in per_texel.into_iter().enumerate() {
        tile.texels.push(t);
        tile.centres.push(p);
        tile.centre_normals.push(normal);
        for (s, sample) in samples.iter().enumerate() {
            let at = k * n + s;
            tile.positions[at] = sample.position.to_array();
            tile.normals[at] = sample.normal.to_array();
            tile.areas[at] = sample.area;
            tile.valid[at] = true;
        }
    }
    Ok(tile)
}
