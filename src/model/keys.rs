//! The words of the case file (docs/case-format.md) that name the core's choices, parsed in one
//! place: the live load, the joint families and a joint law's keys, the top beam's supports, how
//! the load is driven, and the explicit solver's damping. Every error names the key.

use super::{LiveLoad, TopBeam};
use crate::analysis::{Control, DEFAULT_MAX_DISPLACEMENT};
use crate::error::{Error, Result};
use crate::explicit::Damping;
use crate::geometry::FirstCourse;
use crate::interface::Family;
use crate::joint::JointLaw;
use std::str::FromStr;

/// `"a", "b" or "c"` for messages.
fn choices(words: &[&str]) -> String {
    let quoted: Vec<String> = words.iter().map(|w| format!("\"{w}\"")).collect();
    match quoted.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// The error of a word that is not one of `words` at `key`.
fn not_one_of(key: &str, words: &[&str], got: &str) -> Error {
    Error::input_at(key, format!("{key} must be {}, got {got:?}", choices(words)))
}

impl LiveLoad {
    /// The case file's words, in the order of the variants.
    pub const NAMES: [&'static str; 2] = ["horizontal_weight", "top_horizontal"];

    /// The case file's word for the live load (`loads.live`).
    pub fn as_str(self) -> &'static str {
        match self {
            LiveLoad::HorizontalWeight => Self::NAMES[0],
            LiveLoad::TopHorizontal => Self::NAMES[1],
        }
    }
}

impl FromStr for LiveLoad {
    type Err = Error;
    /// `loads.live`: "horizontal_weight" or "top_horizontal".
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "horizontal_weight" => Ok(LiveLoad::HorizontalWeight),
            "top_horizontal" => Ok(LiveLoad::TopHorizontal),
            o => Err(not_one_of("loads.live", &Self::NAMES, o)),
        }
    }
}

impl FromStr for Family {
    type Err = Error;
    /// A family of joints in `[joints.<family>]`: "bed", "head", "base" or "top".
    fn from_str(s: &str) -> Result<Self> {
        [Family::Bed, Family::Head, Family::Base, Family::Top]
            .into_iter()
            .find(|f| f.name() == s)
            .ok_or_else(|| {
                Error::input_at(
                    "joints",
                    format!("joints: unknown family {s:?} (expected default, bed, head, base or top)"),
                )
            })
    }
}

impl JointLaw {
    /// The keys of a joint law in the case file, in the order of the struct's fields.
    pub const KEYS: [&'static str; 9] = [
        "normal_stiffness",
        "shear_stiffness",
        "friction",
        "cohesion",
        "tensile_strength",
        "dilatancy",
        "fracture_energy_tension",
        "fracture_energy_shear",
        "restitution",
    ];

    /// Sets the parameter named by case-file key `key` to `value`; `table` names the law in
    /// messages ("joints", "joints.bed"). The value is checked by [`JointLaw::validate`].
    pub fn set(&mut self, table: &str, key: &str, value: f64) -> Result<()> {
        let slot = match key {
            "normal_stiffness" => &mut self.normal_stiffness,
            "shear_stiffness" => &mut self.shear_stiffness,
            "friction" => &mut self.friction,
            "cohesion" => &mut self.cohesion,
            "tensile_strength" => &mut self.tensile_strength,
            "dilatancy" => &mut self.dilatancy,
            "fracture_energy_tension" => &mut self.fracture_energy_tension,
            "fracture_energy_shear" => &mut self.fracture_energy_shear,
            "restitution" => &mut self.restitution,
            _ => {
                return Err(Error::input_at(
                    table,
                    format!("{table}: unknown key {key:?} (expected one of {})", Self::KEYS.join(", ")),
                ))
            }
        };
        *slot = value;
        Ok(())
    }
}

impl TopBeam {
    /// The dead force on the beam where `top.force` is left out \[N\].
    pub const DEFAULT_FORCE: [f64; 2] = [0.0, 0.0];
    /// `top.vertical` where it is left out: the beam is free to rise.
    pub const DEFAULT_VERTICAL: &'static str = "free";

    /// The top beam of the `[top]` table: `rotation` "fixed" or "free", the dead `force`
    /// [Fx, Fy] \[N\], `vertical` "free" or "held" (left out: [`Self::DEFAULT_FORCE`],
    /// [`Self::DEFAULT_VERTICAL`]). `None` for `rotation` means no beam, which only
    /// `vertical = "free"` allows.
    pub fn from_keys(rotation: Option<&str>, force: Option<&[f64]>, vertical: Option<&str>) -> Result<Option<TopBeam>> {
        let force = force.unwrap_or(&Self::DEFAULT_FORCE);
        if force.len() != 2 {
            return Err(Error::input_at(
                "top.force",
                format!("top.force: expected 2 numbers [Fx, Fy] in N, got {}", force.len()),
            ));
        }
        let vertical_held = match vertical.unwrap_or(Self::DEFAULT_VERTICAL) {
            "free" => false,
            "held" => true,
            o => return Err(not_one_of("top.vertical", &["free", "held"], o)),
        };
        let Some(rotation) = rotation else {
            if vertical_held {
                return Err(Error::input_at("top.vertical", "top.vertical = \"held\" needs a top beam (top.rotation)"));
            }
            return Ok(None);
        };
        let rotation_fixed = match rotation {
            "fixed" => true,
            "free" => false,
            o => return Err(not_one_of("top.rotation", &["fixed", "free"], o)),
        };
        Ok(Some(TopBeam { rotation_fixed, force: [force[0], force[1]], vertical_held }))
    }
}

impl FromStr for FirstCourse {
    type Err = Error;
    /// `geometry.running_bond.first_course`: "half" or "full".
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "half" => Ok(FirstCourse::Half),
            "full" => Ok(FirstCourse::Full),
            o => Err(not_one_of("geometry.running_bond.first_course", &["half", "full"], o)),
        }
    }
}

impl Control {
    /// The case file's word for the control ("load" or "displacement").
    pub fn name(self) -> &'static str {
        match self {
            Control::Load => "load",
            Control::Displacement { .. } => "displacement",
        }
    }

    /// `analysis.control`: "load", or "displacement" up to `max_displacement` \[m\] (left out:
    /// `default`'s, else [`DEFAULT_MAX_DISPLACEMENT`]); `None`: `default`'s. A `max_displacement`
    /// under load control is refused: it would be ignored.
    pub fn from_keys(control: Option<&str>, max_displacement: Option<f64>, default: Control) -> Result<Control> {
        match control.unwrap_or(default.name()) {
            "load" => match max_displacement {
                Some(d) => Err(Error::input_at(
                    "analysis.max_displacement",
                    format!("analysis.max_displacement = {d} applies to displacement control only (analysis.control = \"displacement\"); this analysis is under load control"),
                )),
                None => Ok(Control::Load),
            },
            "displacement" => Ok(Control::Displacement {
                max_displacement: max_displacement.unwrap_or(match default {
                    Control::Displacement { max_displacement } => max_displacement,
                    Control::Load => DEFAULT_MAX_DISPLACEMENT,
                }),
            }),
            o => Err(not_one_of("analysis.control", &["load", "displacement"], o)),
        }
    }
}

impl Damping {
    /// The case file's word for the damping's kind ("local", "viscous" or "none").
    pub fn kind(self) -> &'static str {
        match self {
            Damping::None => "none",
            Damping::Local(_) => "local",
            Damping::Viscous(_) => "viscous",
        }
    }

    /// The damping of `[analysis] damping` ("local", "viscous" or "none") and
    /// `damping_coefficient`, each left out (`None`) taking the one of `default`.
    pub fn from_keys(kind: Option<&str>, coefficient: Option<f64>, default: Damping) -> Result<Damping> {
        let (default_kind, default_coefficient) = match default {
            Damping::None => ("none", 0.0),
            Damping::Local(c) => ("local", c),
            Damping::Viscous(c) => ("viscous", c),
        };
        let c = coefficient.unwrap_or(default_coefficient);
        match kind.unwrap_or(default_kind) {
            "local" => Ok(Damping::Local(c)),
            "viscous" => Ok(Damping::Viscous(c)),
            "none" => Ok(Damping::None),
            o => Err(not_one_of("damping", &["local", "viscous", "none"], o)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_word_reads_back() {
        for l in [LiveLoad::HorizontalWeight, LiveLoad::TopHorizontal] {
            assert_eq!(l.as_str().parse::<LiveLoad>().unwrap(), l);
        }
        for f in [Family::Bed, Family::Head, Family::Base, Family::Top] {
            assert_eq!(f.name().parse::<Family>().unwrap(), f);
        }
        let mut law = JointLaw::default();
        for (k, key) in JointLaw::KEYS.iter().enumerate() {
            law.set("joints", key, k as f64 + 0.5).unwrap();
        }
        assert_eq!(law.fracture_energy_shear, 7.5);
        assert_eq!(law.normal_stiffness, 0.5);
    }

    #[test]
    fn errors_name_the_key() {
        let e = "sideways".parse::<LiveLoad>().unwrap_err();
        assert_eq!(e.key(), Some("loads.live"));
        assert_eq!(e.to_string(), "loads.live must be \"horizontal_weight\" or \"top_horizontal\", got \"sideways\"");
        let e = Damping::from_keys(Some("x"), None, Damping::None).unwrap_err();
        assert_eq!(e.to_string(), "damping must be \"local\", \"viscous\" or \"none\", got \"x\"");
        let e = TopBeam::from_keys(None, None, Some("held")).unwrap_err();
        assert_eq!(e.key(), Some("top.vertical"));
    }
}
