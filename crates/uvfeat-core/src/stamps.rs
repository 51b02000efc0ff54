//! Index sets that forget their members in O(1): a generation stamp per index, the per-thread
//! scratch of the searches over a mesh or an atlas (the reference's neighbourhoods, the surfels'),
//! so that no search allocates or clears a mesh-sized array.

/// A subset of `0..len`.
#[derive(Debug, Clone)]
pub struct Stamps {
    stamp: Vec<u32>,
    generation: u32,
}

impl Stamps {
    /// Room for `0..len`, empty.
    pub fn new(len: usize) -> Self {
        Self { stamp: vec![0; len], generation: 1 }
    }

    /// Empties the set and makes room for `0..len` (at least).
    pub fn reset(&mut self, len: usize) {
        if self.stamp.len() < len {
            self.stamp.resize(len, 0);
        }
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamp.fill(0);
            self.generation = 1;
        }
    }

    /// Whether `i` is in the set.
    #[inline]
    pub fn contains(&self, i: u32) -> bool {
        self.stamp[i as usize] == self.generation
    }

    /// Adds `i`; `true` when it was not in the set.
    #[inline]
    pub fn insert(&mut self, i: u32) -> bool {
        let stamp = &mut self.stamp[i as usize];
        let new = *stamp != self.generation;
        *stamp = self.generation;
        new
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reset_empties_the_set_and_survives_generation_wrap() {
        let mut s = Stamps::new(4);
        assert!(s.insert(2) && !s.insert(2) && s.contains(2));
        s.generation = u32::MAX;
        s.reset(6);
        assert!(!s.contains(2) && !s.contains(5));
        assert!(s.insert(5) && s.contains(5));
    }
}
