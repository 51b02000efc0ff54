//! Curvedness (DESIGN.md §2.8; Koenderink & van Doorn 1992).

/// `C = sqrt((k1^2 + k2^2) / 2)`: how strongly curved, whatever the shape. Unit sphere 1, unit
/// cylinder `1/sqrt(2)`, plane 0. Units 1/length.
pub fn curvedness(k1: f64, k2: f64) -> f64 {
    ((k1 * k1 + k2 * k2) / 2.0).sqrt()
}
