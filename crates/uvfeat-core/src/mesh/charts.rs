//! Charts (DESIGN.md §1.2.3): connected components of faces joined by UV-continuous edges.

use super::weld::{find, union};

/// Chart id of every face, numbered `0..n_charts` in order of the first face of each chart;
/// `-1` for `excluded` faces (zero-area UV triangles).
///
/// # Returns
/// `(face_chart, n_charts)`.
pub(crate) fn chart_ids(
    n_faces: usize,
    interior_pairs: impl IntoIterator<Item = (u32, u32)>,
    excluded: &[bool],
) -> (Vec<i32>, usize) {
    let mut parent: Vec<u32> = (0..n_faces as u32).collect();
    for (a, b) in interior_pairs {
        union(&mut parent, a, b);
    }
    let mut root_chart = vec![-1i32; n_faces];
    let mut n_charts = 0usize;
    let face_chart = (0..n_faces)
        .map(|f| {
            if excluded[f] {
                return -1;
            }
            let root = find(&mut parent, f as u32) as usize;
            if root_chart[root] < 0 {
                root_chart[root] = n_charts as i32;
                n_charts += 1;
            }
            root_chart[root]
        })
        .collect();
    (face_chart, n_charts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn components_are_numbered_in_face_order() {
        let (charts, n) = chart_ids(5, [(3, 4), (0, 2)], &[false, false, false, false, true]);
        assert_eq!(charts, vec![0, 1, 0, 2, -1]);
        assert_eq!(n, 3);
    }
}
