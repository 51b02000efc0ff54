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

/// Position of cube `(i, j, k)` along a 3D Z (Morton) curve (coordinates below 2^21).
pub fn morton3(i: usize, j: usize, k: usize) -> u64 {
    let spread = |x: usize| {
        let mut x = x as u64 & 0x1f_ffff;
        x = (x | (x << 32)) & 0x001f_0000_0000_ffff;
        x = (x | (x << 16)) & 0x001f_0000_ff00_00ff;
        x = (x | (x << 8)) & 0x100f_00f0_0f00_f00f;
        x = (x | (x << 4)) & 0x10c3_0c30_c30c_30c3;
        (x | (x << 2)) & 0x1249_2492_4924_9249
    };
    spread(i) | (spread(j) << 1) | (spread(k) << 2)
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

    #[test]
    fn interleaves_three_coordinates_so_each_2x2x2_block_is_consecutive() {
        let corners: Vec<u64> = (0..8).map(|c| morton3(c & 1, (c >> 1) & 1, c >> 2)).collect();
        assert_eq!(corners, (0..8).collect::<Vec<u64>>());
        assert_eq!(morton3(0b101, 0, 0), 0b001_000_001);
        for (i, j, k) in [(6, 9, 3), (1023, 512, 77), (2_000_000, 3, 1_048_575)] {
            assert_eq!(morton3(i, j, k) >> 3, morton3(i / 2, j / 2, k / 2));
        }
    }
}
