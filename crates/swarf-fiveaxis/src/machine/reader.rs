//! A machine file as the G-code reader's forward kinematics: [`MachineKinematics`]
//! implements [`swarf_nc::read::Kinematics`] with [`Machine::forward`] for the pose of
//! an axis position and [`joint_path`] for the straight moves in axis space (module
//! docs of [`super::kinematics`] and [`super::joints`]), so that `swarf verify` reads
//! five-axis programs (`X Y Z` and `A C`, `B C`, ... words) from any CAM system that
//! posts for the machine.
//!
//! The programs are read as [`crate::post::write_gcode_5x`] writes them: on table-table
//! machines `X Y Z` are the tool tip (G43 tool length compensation), on machines with
//! head axes the head's reference point, with the tool length (spindle gauge line to
//! tip) part of the kinematics.

use super::Machine;
use super::joints::joint_path;
use super::kinematics::Joints;
use crate::error::FiveAxisError;
use swarf_geom::Vec3;
use swarf_nc::read::{AxisPosition, Kinematics};
use swarf_tool::Pose;

/// A machine with a tool in it, as forward kinematics for the G-code reader.
#[derive(Debug, Clone, PartialEq)]
pub struct MachineKinematics {
    machine: Machine,
    tool_length: f64,
}

impl MachineKinematics {
    /// `machine` with a tool `tool_length` long from the spindle gauge line to the
    /// tip (used only by machines with head axes).
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] for a tool length that is not a finite
    /// number >= 0.
    pub fn new(machine: Machine, tool_length: f64) -> Result<Self, FiveAxisError> {
        if !(tool_length.is_finite() && tool_length >= 0.0) {
            return Err(FiveAxisError::parameter(
                "tool_length",
                format!("expected a finite length >= 0 mm, found {tool_length}"),
            ));
        }
        Ok(MachineKinematics {
            machine,
            tool_length,
        })
    }

    /// The machine.
    pub fn machine(&self) -> &Machine {
        &self.machine
    }

    /// The tool length, mm.
    pub fn tool_length(&self) -> f64 {
        self.tool_length
    }
}

fn joints(p: &AxisPosition) -> Joints {
    Joints {
        linear: Vec3::new(p[0], p[1], p[2]),
        rotary: [p[3], p[4]],
    }
}

impl Kinematics for MachineKinematics {
    fn rotary_letters(&self) -> [char; 2] {
        self.machine.rotary_names()
    }

    fn pose(&self, axes: &AxisPosition) -> Pose {
        self.machine.forward(&joints(axes), self.tool_length)
    }

    fn path(&self, from: &AxisPosition, to: &AxisPosition, tol: f64) -> Vec<Pose> {
        joint_path(
            &self.machine,
            &joints(from),
            &joints(to),
            self.tool_length,
            tol,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::TRUNNION;
    use super::*;
    use swarf_geom::Point3;
    use swarf_nc::read::{GcodeReadOptions, parse_gcode};

    #[test]
    fn a_turn_of_c_reads_as_the_circle_the_table_draws() {
        // TRUNNION's C axis passes through (3, -4) and the part's origin sits at
        // (10, -20, 30): at A = 0 a turn of C moves the fixed tip on a circle about
        // the C axis over the part.
        let m = Machine::parse(TRUNNION, "m").unwrap();
        let k = MachineKinematics::new(m, 0.0).unwrap();
        assert_eq!(k.rotary_letters(), ['A', 'C']);
        let opts = GcodeReadOptions {
            kinematics: Some(&k),
            kinematics_tol: 1e-3,
            ..GcodeReadOptions::default()
        };
        let text = "G21 G90 G94\nG0 X30 Y0 Z40\nG1 C90 F360\nM30\n";
        let p = parse_gcode(text, "c.ngc", &opts).unwrap();
        assert!(p.stopped.is_none(), "{:?}", p.stopped);
        let turn: Vec<_> = p.motions.iter().filter(|m| m.line == 3).collect();
        assert!(turn.len() >= 16, "{}", turn.len());
        let centre = Point3::new(3.0 - 10.0, -4.0 + 20.0, 0.0);
        let radius = 27.0f64.hypot(4.0);
        for m in &turn {
            assert!(((m.end.cl - centre).xy().norm() - radius).abs() < 1e-9);
            assert!((m.end.cl.z - 10.0).abs() < 1e-12);
            // Each chord stays within the tolerance of the circle at its middle.
            let mid = m.point_at(0.5).cl;
            assert!(radius - (mid - centre).xy().norm() <= 1e-3);
        }
        // 90 degrees of C at 360 degrees/min: a quarter minute for a quarter circle.
        let length: f64 = turn.iter().map(|m| m.length()).sum();
        assert!((length - radius * std::f64::consts::FRAC_PI_2).abs() < 1e-3);
        assert!((turn[0].feed - length / 0.25).abs() < 1e-9);
    }

    #[test]
    fn tool_length_must_be_a_length() {
        let m = Machine::parse(TRUNNION, "m").unwrap();
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            let e = MachineKinematics::new(m.clone(), bad).unwrap_err();
            assert!(e.to_string().contains("tool_length"), "{e}");
        }
    }
}
