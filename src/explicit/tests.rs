//! Unit tests of the explicit solver's internals.

// matrices are written with their indices, as in the formulas
#![allow(clippy::needless_range_loop)]

use super::*;
use crate::geometry::{polygons, running_bond, FirstCourse, Rect, RunningBond};
use crate::model::ModelSpec;

#[test]
fn prepared_kinds_change_no_result() {
    // a stack of blocks of 300 widths: more kinds than the table holds
    let stack: Vec<Rect> = (0..300)
        .map(|i| {
            let (w, y) = (0.4 + 1e-3 * i as f64, 0.1 * i as f64);
            Rect::new(-0.5 * w, y, 0.5 * w, y + 0.1)
        })
        .collect();
    let wall = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses: 6,
        height: None,
        length: 2.0,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .unwrap();
    for (blocks, overflow) in [(stack, true), (wall, false)] {
        let model = Model::new(ModelSpec { blocks: polygons(blocks), ..ModelSpec::default() }).unwrap();
        for large in [false, true] {
            // under a horizontal load that makes joints slide and open
            let run = |prepared: bool| {
                let mut s = Stepper::new(&model, 0.4, Damping::Local(0.8), large, 1).unwrap();
                assert_eq!(s.s.shapes.iter().any(|g| g.kind == Kinds::NONE), overflow);
                assert_eq!(s.s.kinds.len() == Kinds::MAX, overflow);
                if !prepared {
                    s.s.kinds = Kinds::default();
                }
                s.run(400);
                let u: Vec<u64> = s.displacements().iter().map(|x| x.to_bits()).collect();
                let f: Vec<u64> = s.interface_forces().iter().flatten().map(|x| x.to_bits()).collect();
                assert!(s.s.flags.iter().any(|&fl| fl != 0), "no joint reached its strength");
                (u, f)
            };
            assert!(run(true) == run(false), "{} blocks, large rotations {large}", model.n_blocks());
        }
    }
}

#[test]
fn parts_change_no_result() {
    // a wall with an opening, under a horizontal load that makes joints slide and open
    let blocks = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses: 8,
        height: None,
        length: 3.0,
        first_course: FirstCourse::Half,
        openings: vec![Rect::new(1.0, 0.4, 1.8, 1.0)],
    })
    .unwrap();
    let model = Model::new(ModelSpec { blocks: polygons(blocks), ..ModelSpec::default() }).unwrap();
    for large in [false, true] {
        // the pass in `n_parts` parts, on the pool if `par` (whatever the wall's size)
        let run = |n_parts: usize, par: bool| {
            let mut s = Stepper::new(&model, 0.4, Damping::Local(0.8), large, 2).unwrap();
            s.s.set_parts(n_parts);
            assert_eq!(s.s.straddlers.blocks.is_empty(), n_parts == 1);
            s.s.par = par;
            s.run(300);
            let u: Vec<u64> = s.displacements().iter().map(|x| x.to_bits()).collect();
            let f: Vec<u64> = s.interface_forces().iter().flatten().map(|x| x.to_bits()).collect();
            (u, f)
        };
        let one = run(1, false);
        for (n_parts, par) in [(3, false), (3, true), (8, true), (40, true), (1000, true)] {
            assert!(run(n_parts, par) == one, "{n_parts} parts, on the pool {par}, large rotations {large}");
        }
    }
}

#[test]
fn packed_geometry_rebuilds_b_bit_for_bit() {
    let blocks = running_bond(&RunningBond {
        block_length: 0.4,
        block_height: 0.175,
        courses: 5,
        height: None,
        length: 2.0,
        first_course: FirstCourse::Half,
        openings: vec![],
    })
    .unwrap();
    let model = Model::new(ModelSpec { blocks: polygons(blocks), ..ModelSpec::default() }).unwrap();
    for it in model.interfaces() {
        let b = Shape::new(it, 0).b_mat();
        for r in 0..3 {
            for j in 0..6 {
                assert_eq!(b[r][j].to_bits(), it.b_mat[r][j].to_bits(), "{it:?} B[{r}][{j}]");
            }
        }
    }
}
