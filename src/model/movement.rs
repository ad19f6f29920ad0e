//! A support given a movement: one support translated along x or y by the movement delta, the
//! other supports where they are. The analyses that follow it (limit analysis along the
//! movement, the explicit solver driving the support) take the model with that support's dof
//! free and a unit force on it as the live load ([`Model::with_movement`]).

use super::Model;
use crate::error::{Error, Result};
use std::str::FromStr;

/// Which way a support moves: along +x, -x, +y or -y (the model's axes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Towards +x.
    PlusX,
    /// Towards -x.
    MinusX,
    /// Towards +y (up, under the default gravity).
    PlusY,
    /// Towards -y (a settlement, under the default gravity).
    MinusY,
}

impl Direction {
    /// The case file's words, in the order of the variants.
    pub const NAMES: [&'static str; 4] = ["+x", "-x", "+y", "-y"];

    /// The dof along which the support moves (0: u1, 1: u2) and the sign of its motion.
    pub fn axis(self) -> (usize, f64) {
        match self {
            Direction::PlusX => (0, 1.0),
            Direction::MinusX => (0, -1.0),
            Direction::PlusY => (1, 1.0),
            Direction::MinusY => (1, -1.0),
        }
    }

    /// The case file's word.
    pub fn as_str(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

impl FromStr for Direction {
    type Err = Error;
    /// `analysis.move_direction`: "+x", "-x", "+y" or "-y".
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "+x" => Ok(Direction::PlusX),
            "-x" => Ok(Direction::MinusX),
            "+y" => Ok(Direction::PlusY),
            "-y" => Ok(Direction::MinusY),
            o => Err(Error::input_at(
                "analysis.move_direction",
                format!("analysis.move_direction must be \"+x\", \"-x\", \"+y\" or \"-y\", got {o:?}"),
            )),
        }
    }
}

/// A movement imposed on a support: its translation along `direction` by the movement delta
/// \[m\], the parameter of the analysis (`[analysis] move_support`, `move_direction`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SupportMovement {
    /// The support that moves, among the model's supports (0-based, in the order given; an
    /// arch's abutments: 0 the left one, 1 the right one).
    pub support: usize,
    /// Which way it moves.
    pub direction: Direction,
}

impl SupportMovement {
    /// The support's block among the model's blocks and its dof that moves, checked against
    /// `model` (the error names `analysis.move_support`).
    pub fn dof(&self, model: &Model) -> Result<(usize, usize)> {
        let n = model.supports().len();
        if self.support >= n {
            return Err(Error::input_at(
                "analysis.move_support",
                format!(
                    "analysis.move_support = {} names no support: the model has {n} support{} (0-based; an arch's abutments are 0 and 1, the base is not one)",
                    self.support,
                    if n == 1 { "" } else { "s" }
                ),
            ));
        }
        let block = model.supports().start + self.support;
        Ok((block, 3 * block + self.direction.axis().0))
    }
}

impl Model {
    /// The model of a support movement: the support's dof along the movement free (its other
    /// dofs held), the live load replaced by a unit force \[N\] on that dof along the movement
    /// (the dead loads kept: the support carries none). Its multiplier lambda is then the
    /// force applied to the support along the movement: in equilibrium the force the wall
    /// exerts on the support along the movement is `-lambda`.
    pub fn with_movement(&self, movement: &SupportMovement) -> Result<Model> {
        let (_, dof) = movement.dof(self)?;
        let mut m = self.clone();
        m.fixed[dof] = false;
        m.prescribed[dof] = 0.0;
        m.f_live.fill(0.0);
        m.f_live[dof] = movement.direction.axis().1;
        Ok(m)
    }
}
