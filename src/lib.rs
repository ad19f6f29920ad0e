//! # masonry-dem
//!
//! Nonlinear in-plane analysis of masonry walls made of rigid blocks joined by zero-thickness
//! Mohr-Coulomb interfaces (dry or mortar joints), after Baraldi & Cecchi (2016). A block is any
//! convex polygon: walls of rectangles, arches of voussoirs, piers on inclined springings, cut
//! or rubble stone.
//!
//! - [`shape`]: the shape layer: convex polygons, their mass properties and where they touch
//!   (nothing above the model knows a block's shape);
//! - [`geometry`]: rectangles and wall generators, and the arch generator; [`interface`]:
//!   interfaces (their detection on the shapes, their kinematics);
//! - [`joint`]: the joint law and its return mapping (shared by every solver);
//! - [`model`]: blocks, interfaces, supports and loads;
//! - [`static_solver`]: the static incremental solver (load or displacement control);
//! - [`limit`]: limit analysis (the collapse multiplier as a linear program, with its certificate);
//! - [`explicit`]: the explicit (molecular dynamics) solver: quasi-static analyses and time histories;
//! - [`modal`]: modal analysis of the elastic model (natural frequencies and mode shapes), and
//!   Rayleigh damping coefficients;
//! - [`analysis`]: what the incremental analyses share (how the load is driven, progress);
//! - [`results`]: what an analysis returns; [`error`]: the error type.
//!
//! Units are SI throughout: m, N, Pa, kg, s. Build with `--release` (`cargo build --release`,
//! `cargo test --release`): the solvers' inner loops are many times slower in a debug build.
//!
//! ```
//! use masonry_dem::geometry::{polygons, running_bond, RunningBond, FirstCourse};
//! use masonry_dem::joint::JointLaw;
//! use masonry_dem::model::{JointLaws, Model, ModelSpec};
//! use masonry_dem::static_solver::{solve, StaticOptions};
//!
//! let blocks = running_bond(&RunningBond { block_length: 0.4, block_height: 0.175, courses: 6, height: None,
//!     length: 2.0, first_course: FirstCourse::Half, openings: vec![] }).unwrap();
//! let law = JointLaw { friction: 0.65, dilatancy: 0.65, ..JointLaw::default() };
//! let model = Model::new(ModelSpec { blocks: polygons(blocks), gravity: 10.0,
//!     joints: JointLaws::uniform(law), ..ModelSpec::default() }).unwrap();
//! let res = solve(&model, &StaticOptions::default()).unwrap();
//! assert!((res.collapse_multiplier - 0.6429).abs() < 0.01 * 0.6429);
//! ```

// `!(x <= limit)` is how the checks refuse NaN together with the values out of range: the
// negated comparison is meant
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![deny(missing_docs)]

pub mod analysis;
pub mod error;
pub mod explicit;
pub mod geometry;
pub mod interface;
pub mod joint;
pub mod limit;
pub(crate) mod linalg;
pub mod modal;
pub mod model;
pub mod results;
pub mod shape;
pub mod space;
pub mod static_solver;

pub use error::{Error, Result};
pub use model::{Model, ModelSpec};
pub use results::{Results, Status};
