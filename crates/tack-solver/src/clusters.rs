//! Connected components of a contact mask (4-neighbour connectivity, wrapping on periodic grids).

use ndarray::{Array2, ArrayView2, s};

/// Number of separate contact clusters in `mask`; neighbours share an edge, and on periodic
/// grids the first and last rows/columns are neighbours.
pub fn count_clusters(mask: &Array2<bool>, periodic: bool) -> usize {
    if periodic {
        return count_in(mask.view(), true);
    }
    // Without wrapping no cluster leaves the set's bounding box: search only that.
    let rows: Vec<usize> = (0..mask.nrows())
        .filter(|&i| mask.row(i).iter().any(|&b| b))
        .collect();
    let (Some(&i0), Some(&i1)) = (rows.first(), rows.last()) else {
        return 0;
    };
    let (mut j0, mut j1) = (usize::MAX, 0);
    for &i in &rows {
        let row = mask.row(i);
        j0 = j0.min(row.iter().position(|&b| b).unwrap_or(j0));
        j1 = j1.max(row.iter().rposition(|&b| b).map_or(j1, |j| j + 1));
    }
    count_in(mask.slice(s![i0..=i1, j0..j1]), false)
}

fn count_in(mask: ArrayView2<bool>, periodic: bool) -> usize {
    let (nx, ny) = mask.dim();
    let mut seen = Array2::from_elem((nx, ny), false);
    let mut stack = Vec::new();
    let mut clusters = 0;
    for start in 0..nx * ny {
        let (i0, j0) = (start / ny, start % ny);
        if !mask[[i0, j0]] || seen[[i0, j0]] {
            continue;
        }
        clusters += 1;
        seen[[i0, j0]] = true;
        stack.push((i0, j0));
        while let Some((i, j)) = stack.pop() {
            for (di, dj) in [(1isize, 0isize), (-1, 0), (0, 1), (0, -1)] {
                let step = |k: usize, d: isize, n: usize| -> Option<usize> {
                    let m = k as isize + d;
                    if (0..n as isize).contains(&m) {
                        Some(m as usize)
                    } else if periodic && n > 1 {
                        Some(m.rem_euclid(n as isize) as usize)
                    } else {
                        None
                    }
                };
                if let (Some(a), Some(b)) = (step(i, di, nx), step(j, dj, ny))
                    && mask[[a, b]]
                    && !seen[[a, b]]
                {
                    seen[[a, b]] = true;
                    stack.push((a, b));
                }
            }
        }
    }
    clusters
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mask(rows: &[&str]) -> Array2<bool> {
        let ny = rows[0].len();
        Array2::from_shape_fn((rows.len(), ny), |(i, j)| rows[i].as_bytes()[j] == b'#')
    }

    #[test]
    fn counts_edge_connected_spots() {
        let m = mask(&["#..#", "#...", "..#.", "...."]);
        assert_eq!(count_clusters(&m, false), 3);
        // Diagonal neighbours are separate clusters.
        assert_eq!(count_clusters(&mask(&["#.", ".#"]), false), 2);
        assert_eq!(count_clusters(&mask(&["..", ".."]), false), 0);
    }

    #[test]
    fn a_set_away_from_the_corner_counts_the_same_as_the_whole_grid_search() {
        let m = mask(&["......", "..#.#.", "..###.", ".....#", "......"]);
        assert_eq!(count_clusters(&m, false), 2);
        assert_eq!(count_in(m.view(), false), 2);
        assert_eq!(count_clusters(&mask(&["...", ".#.", "..."]), false), 1);
    }

    #[test]
    fn periodic_wrap_joins_opposite_edges() {
        let m = mask(&["#..#", "....", "....", "#..."]);
        assert_eq!(count_clusters(&m, false), 3);
        assert_eq!(count_clusters(&m, true), 1);
    }
}
