//! Per-index values that reset in O(1) between neighbourhoods: the per-thread scratch of the
//! reference (no allocation per vertex, no clearing of mesh-sized arrays).

use crate::stamps::Stamps;

/// Values for a subset of `0..len`, with the indices set since the last reset in set order.
#[derive(Debug, Clone)]
pub struct StampedValues {
    value: Vec<f64>,
    set: Stamps,
    touched: Vec<u32>,
}

impl StampedValues {
    /// Room for indices `0..len`, none set.
    pub fn new(len: usize) -> Self {
        Self { value: vec![0.0; len], set: Stamps::new(len), touched: Vec::new() }
    }

    /// Forgets every value.
    pub fn reset(&mut self) {
        self.set.reset(0);
        self.touched.clear();
    }

    /// The value at `i`, `+inf` when unset.
    #[inline]
    pub fn get(&self, i: u32) -> f64 {
        if self.set.contains(i) {
            self.value[i as usize]
        } else {
            f64::INFINITY
        }
    }

    /// Whether `i` was set since the last reset.
    #[inline]
    pub fn contains(&self, i: u32) -> bool {
        self.set.contains(i)
    }

    /// Sets the value at `i`.
    #[inline]
    pub fn set(&mut self, i: u32, value: f64) {
        if self.set.insert(i) {
            self.touched.push(i);
        }
        self.value[i as usize] = value;
    }

    /// Indices set since the last reset, in the order they were first set.
    pub fn touched(&self) -> &[u32] {
        &self.touched
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reset_forgets_values() {
        let mut s = StampedValues::new(4);
        s.set(2, 1.5);
        s.set(2, 0.5);
        assert_eq!((s.get(2), s.touched()), (0.5, &[2u32][..]));
        s.reset(); // the wrap of the generation is tested with `Stamps`
        assert!(!s.contains(2) && s.get(2).is_infinite() && s.touched().is_empty());
        s.set(1, 3.0);
        assert_eq!(s.get(1), 3.0);
    }
}
