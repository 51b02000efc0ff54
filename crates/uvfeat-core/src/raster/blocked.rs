//! Per-texel tables stored block by block. A neighbourhood's samples land all over an ellipse that
//! spans hundreds of texel rows; in row order every row is its own 4 KiB page (1024 texels of 4
//! bytes), so the sampler's random reads missed the TLB on almost every sample. In 8 x 8 blocks a
//! neighbourhood touches a few dozen pages instead (measured in `docs/BENCHMARKS.md`).

use rayon::prelude::*;

/// Side of a block, in texels.
const BLOCK: usize = 8;

/// A `resolution`² table of `T`, texel `(i, j)` at [`Blocked::index`].
#[derive(Debug, Clone, Default)]
pub struct Blocked<T> {
    blocks_per_row: usize,
    values: Vec<T>,
}

impl<T: Copy> Blocked<T> {
    /// The table of `rows` (texel `(i, j)` at `j * resolution + i`), padded with `fill` up to
    /// whole blocks.
    pub fn from_rows(rows: &[T], resolution: usize, fill: T) -> Self
    where
        T: Send + Sync,
    {
        // Slot by slot in parallel: a scatter of the rows in one thread was 3-5 ms per table at
        // 1024².
        assert_eq!(rows.len(), resolution * resolution, "one value per texel");
        let blocks_per_row = resolution.div_ceil(BLOCK);
        let values = (0..blocks_per_row * blocks_per_row * BLOCK * BLOCK)
            .into_par_iter()
            .map(|index| {
                let (block, within) = (index / (BLOCK * BLOCK), index % (BLOCK * BLOCK));
                let i = (block % blocks_per_row) * BLOCK + within % BLOCK;
                let j = (block / blocks_per_row) * BLOCK + within / BLOCK;
                if i < resolution && j < resolution {
                    rows[j * resolution + i]
                } else {
                    fill
                }
            })
            .collect();
        Self { blocks_per_row, values }
    }

    /// Where texel `(i, j)` is stored.
    #[inline(always)]
    pub fn index(&self, i: usize, j: usize) -> usize {
        ((j / BLOCK) * self.blocks_per_row + i / BLOCK) * (BLOCK * BLOCK) + (j % BLOCK) * BLOCK + i % BLOCK
    }

    /// The value of texel `(i, j)`.
    #[inline(always)]
    pub fn at(&self, i: usize, j: usize) -> T {
        self.values[self.index(i, j)]
    }

    /// The value stored at `index` (from [`Blocked::index`]).
    #[inline(always)]
    pub fn get(&self, index: usize) -> Option<&T> {
        self.values.get(index)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_texel_keeps_its_value_at_any_resolution() {
        for resolution in [1, 7, 8, 13, 64] {
            let rows: Vec<u32> = (0..(resolution * resolution) as u32).collect();
            let table = Blocked::from_rows(&rows, resolution, u32::MAX);
            let padded = table.values.iter().filter(|&&v| v == u32::MAX).count();
            assert_eq!(padded, table.values.len() - rows.len(), "the padding holds the fill");
            for (t, &value) in rows.iter().enumerate() {
                assert_eq!(table.at(t % resolution, t / resolution), value);
            }
            let mut seen: Vec<usize> = (0..rows.len()).map(|t| table.index(t % resolution, t / resolution)).collect();
            seen.sort_unstable();
            seen.dedup();
            assert_eq!(seen.len(), rows.len(), "two texels share a slot");
        }
    }
}
