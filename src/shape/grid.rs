//! The broad phase of the contact search, in any dimension: a uniform grid over the blocks'
//! bounding boxes, which hands each pair of boxes within the tolerance of each other to the
//! narrow phase once. It costs O(n) for walls of similar blocks, never O(n^2), and its memory
//! stays linear in the blocks whatever their sizes.

use super::Aabb;
use crate::error::{Error, Result};

/// Blocks (or grid cells) between two polls of a contact search: about 10 ms of work.
pub(crate) const POLL_EVERY: usize = 16_384;

/// Calls `visit(i, j)` (i < j) once for each pair of `boxes` whose sides, each widened by
/// `tol`, meet: the pairs that may touch. `poll` is called every few thousand boxes or cells,
/// and `false` stops the search ([`Error::Interrupted`]); an error of `visit` stops it too.
///
/// The boxes are entered in the cells of a grid (each axis its own cell size, about twice the
/// mean side along it) within `tol` of them, and a pair is visited in the first cell (in the
/// order of the cells' indices, the last axis first) that holds both: the cell whose index is,
/// axis by axis, the larger of the two boxes' lowest. So a pair is seen at once, even where many boxes share
/// many cells (copies of one block are refused at their first cell, not after every pair of
/// every cell has been compared).
pub(crate) fn for_each_pair<const D: usize>(
    boxes: &[Aabb<D>],
    tol: f64,
    poll: &mut dyn FnMut() -> bool,
    mut visit: impl FnMut(usize, usize) -> Result<()>,
) -> Result<()> {
    if boxes.is_empty() {
        return Ok(());
    }
    let grid = Grid::new(boxes, tol);
    let entries = grid.entries(boxes, poll)?;
    let mut start = 0;
    let mut visited = 0usize;
    while start < entries.len() {
        let key = entries[start].0;
        let end = start + entries[start..].iter().take_while(|e| e.0 == key).count();
        visited += 1;
        if visited % POLL_EVERY == 0 && !poll() {
            return Err(Error::Interrupted);
        }
        let members = &entries[start..end];
        for (p, &(_, i)) in members.iter().enumerate() {
            for &(_, j) in &members[p + 1..] {
                let (a, b) = (&boxes[i], &boxes[j]);
                if a.overlap(b).iter().any(|&w| w < -tol) {
                    continue; // apart
                }
                let first: [i64; D] = std::array::from_fn(|k| grid.lowest(a, k).max(grid.lowest(b, k)));
                if first == key {
                    visit(i, j)?;
                }
            }
        }
        start = end;
    }
    Ok(())
}

/// A uniform grid: its origin and the cell's side along each axis.
struct Grid<const D: usize> {
    lo: [f64; D],
    cell: [f64; D],
    tol: f64,
}

impl<const D: usize> Grid<D> {
    fn new(boxes: &[Aabb<D>], tol: f64) -> Grid<D> {
        let (mut lo, mut sum) = ([f64::MAX; D], [0.0; D]);
        for b in boxes {
            for k in 0..D {
                lo[k] = lo[k].min(b.min[k]);
                sum[k] += b.max[k] - b.min[k];
            }
        }
        let nb = boxes.len() as f64;
        let mut grid = Grid { lo, cell: std::array::from_fn(|k| (2.0 * sum[k] / nb).max(tol * 10.0)), tol };
        // A few boxes much larger than the mean (a long lintel over thousands of small blocks)
        // would each cover millions of cells: coarsen the grid until it holds O(n) entries, so
        // that memory stays linear in the number of blocks whatever their sizes.
        while grid.count(boxes) > 16.0 * nb + 1024.0 {
            grid.cell = grid.cell.map(|c| 2.0 * c);
        }
        grid
    }

    fn cell_of(&self, x: f64, k: usize) -> i64 {
        ((x - self.lo[k]) / self.cell[k]).floor() as i64
    }

    /// The index along axis `k` of the lowest cell box `b` is entered in.
    fn lowest(&self, b: &Aabb<D>, k: usize) -> i64 {
        self.cell_of(b.min[k] - self.tol, k)
    }

    /// The number of (cell, box) entries, as a float (it may be huge before coarsening).
    fn count(&self, boxes: &[Aabb<D>]) -> f64 {
        let span = |b: &Aabb<D>, k: usize| {
            ((b.max[k] + self.tol - self.lo[k]) / self.cell[k]).floor()
                - ((b.min[k] - self.tol - self.lo[k]) / self.cell[k]).floor()
                + 1.0
        };
        boxes.iter().map(|b| (0..D).map(|k| span(b, k)).product::<f64>()).sum()
    }

    /// Every (cell, box) pair, sorted by cell (the last axis first: a wall's cells course by
    /// course, so that the pairs come about in the order of the blocks, which are given so, and
    /// sorting them after is cheap): the boxes of one cell are consecutive, in increasing order.
    fn entries(&self, boxes: &[Aabb<D>], poll: &mut dyn FnMut() -> bool) -> Result<Vec<([i64; D], usize)>> {
        let mut out = Vec::with_capacity(4 * boxes.len());
        for (i, b) in boxes.iter().enumerate() {
            if i % POLL_EVERY == POLL_EVERY - 1 && !poll() {
                return Err(Error::Interrupted);
            }
            let first: [i64; D] = std::array::from_fn(|k| self.lowest(b, k));
            let last: [i64; D] = std::array::from_fn(|k| self.cell_of(b.max[k] + self.tol, k));
            // every cell of the box [first, last], the last axis fastest
            let mut key = first;
            loop {
                out.push((key, i));
                let mut k = D;
                loop {
                    if k == 0 {
                        break;
                    }
                    k -= 1;
                    if key[k] < last[k] {
                        key[k] += 1;
                        break;
                    }
                    key[k] = first[k];
                }
                if key == first {
                    break;
                }
            }
        }
        out.sort_unstable_by(|(p, i), (q, j)| p.iter().rev().cmp(q.iter().rev()).then(i.cmp(j)));
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn pairs<const D: usize>(boxes: &[Aabb<D>], tol: f64) -> Vec<(usize, usize)> {
        let mut out = vec![];
        for_each_pair(boxes, tol, &mut || true, |i, j| {
            out.push((i, j));
            Ok(())
        })
        .unwrap();
        out
    }

    fn brute<const D: usize>(boxes: &[Aabb<D>], tol: f64) -> Vec<(usize, usize)> {
        let mut out = vec![];
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if boxes[i].overlap(&boxes[j]).iter().all(|&w| w >= -tol) {
                    out.push((i, j));
                }
            }
        }
        out
    }

    proptest! {
        // every pair of boxes that meet, once, in 2D and 3D, with a few boxes far larger
        // than the rest (the grid coarsens)
        #[test]
        fn every_meeting_pair_is_visited_once(
            seeds in proptest::collection::vec((0.0f64..10.0, 0.0f64..10.0, 0.0f64..10.0, 0.01f64..1.0, 0.01f64..1.0, 0.01f64..1.0), 1..120),
            big in 0usize..3,
        ) {
            let boxes2: Vec<Aabb<2>> = seeds
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    let grow = if i < big { 20.0 } else { 1.0 };
                    Aabb { min: [s.0, s.1], max: [s.0 + grow * s.3, s.1 + s.4] }
                })
                .collect();
            let mut got = pairs(&boxes2, 1e-8);
            got.sort_unstable();
            prop_assert_eq!(got, brute(&boxes2, 1e-8));
            let boxes3: Vec<Aabb<3>> = seeds
                .iter()
                .map(|s| Aabb { min: [s.0, s.1, s.2], max: [s.0 + s.3, s.1 + s.4, s.2 + s.5] })
                .collect();
            let mut got = pairs(&boxes3, 1e-8);
            got.sort_unstable();
            prop_assert_eq!(got, brute(&boxes3, 1e-8));
        }
    }

    #[test]
    fn boxes_that_touch_at_a_side_or_within_the_tolerance_meet() {
        let boxes = [
            Aabb { min: [0.0, 0.0], max: [1.0, 1.0] },
            Aabb { min: [1.0, 0.0], max: [2.0, 1.0] },
            Aabb { min: [0.0, 1.0 + 1e-10], max: [1.0, 2.0] },
            Aabb { min: [3.0, 0.0], max: [4.0, 1.0] },
        ];
        let mut got = pairs(&boxes, 1e-9);
        got.sort_unstable();
        assert_eq!(got, [(0, 1), (0, 2), (1, 2)]);
    }

    #[test]
    fn the_search_stops_when_polled_false() {
        let boxes: Vec<Aabb<2>> =
            (0..2 * POLL_EVERY).map(|i| Aabb { min: [i as f64, 0.0], max: [i as f64 + 1.0, 1.0] }).collect();
        let r = for_each_pair(&boxes, 1e-9, &mut || false, |_, _| Ok(()));
        assert!(matches!(r, Err(Error::Interrupted)));
    }
}
