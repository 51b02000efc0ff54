//! Positions along a Z (Morton) curve: cells close on the grid are close along it, so work and data
//! ordered by it stay in cache (the surfels of every pyramid level, the vertices whose balls are
//! summed in turn).

/// Position of cell `(i, j)` along a Z (Morton) curve (coordinates below 2^32).
pub fn morton(i: usize, j: usize) -> u64 {
    let spread = |x: usize| {
        let mut x = x as u64 & 0xffff_ffff;
        x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
        x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
        x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        x = (x | (x << 2)) & 0x3333_3333_3333_3333;
        (x | (x << 1)) & 0x5555_5555_5555_5555
    };
    spread(i) | (spread(j) << 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interleaves_the_bits_so_each_2x2_block_is_consecutive() {
        assert_eq!([morton(0, 0), morton(1, 0), morton(0, 1), morton(1, 1)], [0, 1, 2, 3]);
        assert_eq!(morton(2, 0), 4);
        assert_eq!(morton(0b101, 0b011), 0b011011);
        for (i, j) in [(6, 9), (1023, 512), (70_000, 3)] {
            assert_eq!(morton(i, j) >> 2, morton(i / 2, j / 2));
        }
    }
}
