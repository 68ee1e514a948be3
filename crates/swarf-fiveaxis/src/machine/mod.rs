//! Five-axis machines: the machine file, forward and inverse kinematics, and the choice
//! of rotary solutions along passes.
//!
//! A machine has three linear axes `X Y Z` and two rotary axes. Each rotary axis turns
//! either the **table** (and the part on it) or the **head** (and the tool in it); the
//! three kinds are table-table (a tilt-rotary table such as the A/C trunnion of thesis
//! 000 fig. 5.8), head-head (a B/C spindle head) and table-head. The machine frame is
//! the program frame of the G-code. At home (all rotary angles 0) the tool axis points
//! along `+Z` (tip toward shank) and the part frame sits at `part_origin` in the machine
//! frame.
//!
//! ```toml
//! name = "A/C trunnion table"
//! kind = "table-table"            # table-table | head-head | table-head
//! part_origin = [0, 0, 0]         # part-frame origin in the machine frame at home, mm
//!
//! [linear]                        # travel limits of the linear axes, mm (required)
//! x = [-500, 500]
//! y = [-300, 300]
//! z = [-400, 200]
//!
//! [[rotary]]                      # outermost first: the axis on the base carries the next
//! name = "A"                      # the word in the G-code: A, B or C
//! on = "table"                    # table | head
//! axis = [1, 0, 0]                # direction at home; positive turns are right-handed about it
//! point = [0, 0, -50]             # a point on the axis at home, mm (head axes: relative
//!                                 # to the head's reference point, which X Y Z position)
//! limits = [-30, 110]             # degrees; required unless continuous
//!
//! [[rotary]]
//! name = "C"
//! on = "table"
//! axis = [0, 0, 1]
//! point = [0, 0, 0]
//! continuous = true               # turns without end (no limits)
//!
//! [head]
//! pivot_length = 0                # head reference point to the spindle gauge line, mm
//!
//! [solution]
//! prefer = "A+"                   # on a fresh start, the branch with A >= 0 (or "A-", ...)
//! singular_cone = 0.05            # degrees: tool axes this close to the singular
//!                                 # direction keep an interpolated angle
//! ```
//!
//! The kinematics are in [`kinematics`] (forward, and inverse by the Paden-Kahan
//! subproblems), the solution choice along a pass in [`joints`].

mod builtin;
pub mod joints;
pub mod kinematics;
pub mod reader;

use crate::error::FiveAxisError;
use serde::{Deserialize, Serialize};
use swarf_geom::{Point3, Vec3};
use swarf_io::error::toml_message;

pub use builtin::{BUILTIN_MACHINES, load_machine};

/// The three machine kinds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MachineKind {
    /// Both rotary axes turn the table.
    TableTable,
    /// Both rotary axes turn the head.
    HeadHead,
    /// One turns the table, the other the head.
    TableHead,
}

/// What a rotary axis turns.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mount {
    /// The table (and the part).
    Table,
    /// The spindle head (and the tool).
    Head,
}

/// One rotary axis as the machine file gives it (angles in degrees).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotaryFile {
    /// G-code word: `A`, `B` or `C`.
    pub name: String,
    /// What it turns.
    pub on: Mount,
    /// Direction at home.
    pub axis: [f64; 3],
    /// A point on the axis at home, mm.
    #[serde(default)]
    pub point: [f64; 3],
    /// Travel limits, degrees.
    #[serde(default)]
    pub limits: Option<[f64; 2]>,
    /// Turns without end.
    #[serde(default)]
    pub continuous: bool,
}

/// Linear travel limits, mm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinearFile {
    /// X travel.
    pub x: Option<[f64; 2]>,
    /// Y travel.
    pub y: Option<[f64; 2]>,
    /// Z travel.
    pub z: Option<[f64; 2]>,
}

/// The `[head]` table.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeadFile {
    /// From the head reference point to the spindle gauge line along the tool, mm.
    #[serde(default)]
    pub pivot_length: f64,
}

/// The `[solution]` table.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolutionFile {
    /// Preferred branch on a fresh start, e.g. `"A+"`.
    #[serde(default)]
    pub prefer: Option<String>,
    /// Half-angle of the cone around the singular direction, degrees.
    #[serde(default)]
    pub singular_cone: Option<f64>,
}

/// A machine file as written.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MachineFile {
    /// Free text.
    #[serde(default)]
    pub name: Option<String>,
    /// The kind of chain.
    pub kind: MachineKind,
    /// Part-frame origin in the machine frame at home, mm.
    #[serde(default)]
    pub part_origin: [f64; 3],
    /// Linear travel.
    pub linear: Option<LinearFile>,
    /// The two rotary axes, outermost first.
    #[serde(default)]
    pub rotary: Vec<RotaryFile>,
    /// Head geometry.
    #[serde(default)]
    pub head: HeadFile,
    /// Solution choice.
    #[serde(default)]
    pub solution: SolutionFile,
}

/// A validated rotary axis (radians).
#[derive(Debug, Clone, PartialEq)]
pub struct Rotary {
    /// G-code word.
    pub name: char,
    /// What it turns.
    pub on: Mount,
    /// Unit direction at home.
    pub axis: Vec3,
    /// A point on the axis at home, mm.
    pub point: Point3,
    /// Travel limits, radians; `None` for a continuous axis.
    pub limits: Option<[f64; 2]>,
}

/// A validated machine; build it with [`Machine::parse`] or [`Machine::from_file`].
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    /// Free text.
    pub name: String,
    /// The kind of chain.
    pub kind: MachineKind,
    /// Part-frame origin in the machine frame at home, mm.
    pub part_origin: Vec3,
    /// Linear travel `[[x0, x1], [y0, y1], [z0, z1]]`, mm.
    pub linear: [[f64; 2]; 3],
    /// The rotary axes in file order (outermost first).
    pub rotary: [Rotary; 2],
    /// Head reference point to spindle gauge line, mm.
    pub pivot_length: f64,
    /// Preferred branch on a fresh start: rotary index and sign.
    pub prefer: Option<(usize, f64)>,
    /// Half-angle of the singular cone, radians.
    pub singular_cone: f64,
}

/// Default half-angle of the singular cone (radians, 0.05 degree).
pub const DEFAULT_SINGULAR_CONE: f64 = 8.726_646_259_971_648e-4;

impl Machine {
    /// Parses and validates a machine file; `source` names it in errors.
    ///
    /// # Errors
    /// [`FiveAxisError::Machine`] with the line for malformed TOML and unknown keys, and
    /// with the field for an impossible chain (not two rotary axes, a zero or parallel
    /// pair of axes, a kind that does not match what the axes turn), missing or empty
    /// limits, and bad preferences.
    pub fn parse(text: &str, source: &str) -> Result<Machine, FiveAxisError> {
        let file: MachineFile = toml::from_str(text).map_err(|e| FiveAxisError::Machine {
            file: source.to_string(),
            message: toml_message(text, &e),
        })?;
        Machine::from_file(&file).map_err(|message| FiveAxisError::Machine {
            file: source.to_string(),
            message,
        })
    }

    /// Validates a parsed machine file.
    ///
    /// # Errors
    /// A message naming the field, as for [`Machine::parse`].
    pub fn from_file(f: &MachineFile) -> Result<Machine, String> {
        if f.rotary.len() != 2 {
            return Err(format!(
                "rotary: a five-axis machine needs exactly two rotary axes, found {}",
                f.rotary.len()
            ));
        }
        let r0 = rotary(&f.rotary[0], 0)?;
        let r1 = rotary(&f.rotary[1], 1)?;
        if r0.name == r1.name {
            return Err(format!("rotary[1].name: {} is used twice", r1.name));
        }
        if r0.axis.cross(&r1.axis).norm() < 1e-6 {
            return Err(
                "rotary: impossible chain: the two rotary axes are parallel, so they cannot \
                 point the tool in every direction"
                    .into(),
            );
        }
        let mounts = (r0.on, r1.on);
        let ok = match f.kind {
            MachineKind::TableTable => mounts == (Mount::Table, Mount::Table),
            MachineKind::HeadHead => mounts == (Mount::Head, Mount::Head),
            MachineKind::TableHead => mounts.0 != mounts.1,
        };
        if !ok {
            return Err(format!(
                "kind: a {:?} machine does not match rotary axes on {:?} and {:?}",
                f.kind, r0.on, r1.on
            ));
        }
        let linear = linear_limits(f.linear.as_ref())?;
        let prefer = prefer(f.solution.prefer.as_deref(), [r0.name, r1.name])?;
        let singular_cone = match f.solution.singular_cone {
            None => DEFAULT_SINGULAR_CONE,
            Some(d) if d.is_finite() && d > 0.0 && d < 10.0 => d.to_radians(),
            Some(d) => {
                return Err(format!(
                    "solution.singular_cone: expected 0 < cone < 10 degrees, found {d}"
                ));
            }
        };
        let finite = |name: &str, v: &[f64]| {
            if v.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(format!("{name}: expected finite numbers"))
            }
        };
        finite("part_origin", &f.part_origin)?;
        finite("head.pivot_length", &[f.head.pivot_length])?;
        let tool_axis = Vec3::z();
        let inner = if r1.on == Mount::Head { &r1 } else { &r0 };
        if f.kind != MachineKind::TableTable && inner.axis.cross(&tool_axis).norm() < 1e-6 {
            return Err(format!(
                "rotary: impossible chain: the head axis {} is parallel to the tool and \
                 cannot tilt it",
                inner.name
            ));
        }
        Ok(Machine {
            name: f.name.clone().unwrap_or_else(|| "machine".into()),
            kind: f.kind,
            part_origin: Vec3::from(f.part_origin),
            linear,
            rotary: [r0, r1],
            pivot_length: f.head.pivot_length,
            prefer,
            singular_cone,
        })
    }

    /// The G-code words of the rotary axes, in file order.
    pub fn rotary_names(&self) -> [char; 2] {
        [self.rotary[0].name, self.rotary[1].name]
    }
}

fn rotary(r: &RotaryFile, k: usize) -> Result<Rotary, String> {
    let field = |f: &str| format!("rotary[{k}].{f}");
    let name = match r.name.trim().to_ascii_uppercase().as_str() {
        "A" => 'A',
        "B" => 'B',
        "C" => 'C',
        other => {
            return Err(format!(
                "{}: expected A, B or C, found {other:?}",
                field("name")
            ));
        }
    };
    let axis = Vec3::from(r.axis);
    let axis = axis
        .try_normalize(1e-12)
        .filter(|a| a.iter().all(|c| c.is_finite()))
        .ok_or_else(|| format!("{}: expected a non-zero finite direction", field("axis")))?;
    if !r.point.iter().all(|c| c.is_finite()) {
        return Err(format!("{}: expected finite coordinates", field("point")));
    }
    let limits = match (r.limits, r.continuous) {
        (Some(_), true) => {
            return Err(format!(
                "{}: a continuous axis has no limits; remove one of them",
                field("limits")
            ));
        }
        (None, false) => {
            return Err(format!(
                "{}: missing: give [min, max] in degrees, or continuous = true",
                field("limits")
            ));
        }
        (None, true) => None,
        (Some([lo, hi]), false) => {
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(format!(
                    "{}: expected [min, max] with min < max, found [{lo}, {hi}]",
                    field("limits")
                ));
            }
            Some([lo.to_radians(), hi.to_radians()])
        }
    };
    Ok(Rotary {
        name,
        on: r.on,
        axis,
        point: Point3::from(r.point),
        limits,
    })
}

fn linear_limits(l: Option<&LinearFile>) -> Result<[[f64; 2]; 3], String> {
    let l = l.ok_or("linear: missing: give x, y and z travel as [min, max] in mm")?;
    let mut out = [[0.0; 2]; 3];
    for (k, (name, v)) in [("x", l.x), ("y", l.y), ("z", l.z)].into_iter().enumerate() {
        let [lo, hi] = v.ok_or_else(|| format!("linear.{name}: missing: give [min, max] in mm"))?;
        if !(lo.is_finite() && hi.is_finite() && lo < hi) {
            return Err(format!(
                "linear.{name}: expected [min, max] with min < max, found [{lo}, {hi}]"
            ));
        }
        out[k] = [lo, hi];
    }
    Ok(out)
}

fn prefer(p: Option<&str>, names: [char; 2]) -> Result<Option<(usize, f64)>, String> {
    let Some(p) = p else { return Ok(None) };
    let p = p.trim().to_ascii_uppercase();
    let mut chars = p.chars();
    let (name, sign) = (chars.next(), chars.as_str());
    let index = names.iter().position(|n| Some(*n) == name);
    match (index, sign) {
        (Some(i), "+") => Ok(Some((i, 1.0))),
        (Some(i), "-") => Ok(Some((i, -1.0))),
        _ => Err(format!(
            "solution.prefer: expected a rotary axis and a sign such as \"{}+\", found {p:?}",
            names[0]
        )),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) const TRUNNION: &str = r#"
name = "A/C trunnion"
kind = "table-table"
part_origin = [10, -20, 30]
[linear]
x = [-1000, 1000]
y = [-1000, 1000]
z = [-1000, 1000]
[[rotary]]
name = "A"
on = "table"
axis = [1, 0, 0]
point = [0, 5, -60]
limits = [-120, 120]
[[rotary]]
name = "C"
on = "table"
axis = [0, 0, 1]
point = [3, -4, 0]
continuous = true
[solution]
prefer = "A+"
"#;

    #[test]
    fn parses_a_trunnion() {
        let m = Machine::parse(TRUNNION, "m.toml").unwrap();
        assert_eq!(m.kind, MachineKind::TableTable);
        assert_eq!(m.rotary_names(), ['A', 'C']);
        assert_eq!(m.prefer, Some((0, 1.0)));
        assert!(m.rotary[1].limits.is_none());
        assert!((m.rotary[0].limits.unwrap()[1] - 120f64.to_radians()).abs() < 1e-15);
    }

    #[test]
    fn bad_machines_name_the_field() {
        let cases = [
            (
                TRUNNION.replace("limits = [-120, 120]\n", ""),
                "rotary[0].limits: missing",
            ),
            (
                TRUNNION.replace("axis = [0, 0, 1]", "axis = [2, 0, 0]"),
                "impossible chain",
            ),
            (
                TRUNNION.replace("axis = [1, 0, 0]", "axis = [0, 0, 0]"),
                "rotary[0].axis",
            ),
            (
                TRUNNION.replace("name = \"C\"", "name = \"A\""),
                "used twice",
            ),
            (
                TRUNNION.replace("name = \"C\"", "name = \"Q\""),
                "rotary[1].name",
            ),
            (
                TRUNNION.replace("kind = \"table-table\"", "kind = \"head-head\""),
                "kind:",
            ),
            (
                TRUNNION.replace("z = [-1000, 1000]\n", ""),
                "linear.z: missing",
            ),
            (
                TRUNNION.replace("x = [-1000, 1000]", "x = [5, 1]"),
                "linear.x",
            ),
            (
                TRUNNION.replace("prefer = \"A+\"", "prefer = \"B+\""),
                "solution.prefer",
            ),
            (
                TRUNNION.replace("kind = \"table-table\"", "kind = \"spider\""),
                "line 3",
            ),
            (
                TRUNNION.replace("continuous = true", "continuous = true\nlimits = [0, 1]"),
                "continuous axis",
            ),
            (
                TRUNNION.replace("[[rotary]]\nname = \"C\"", "[[rotarY]]\nname = \"C\""),
                "line",
            ),
        ];
        for (text, want) in cases {
            let e = Machine::parse(&text, "m.toml").unwrap_err().to_string();
            assert!(e.starts_with("m.toml: "), "{e}");
            assert!(e.contains(want), "want {want:?} in {e}");
        }
        let one_axis = TRUNNION
            .split("[[rotary]]\nname = \"C\"")
            .next()
            .unwrap()
            .to_string();
        let e = Machine::parse(&one_axis, "m.toml").unwrap_err().to_string();
        assert!(e.contains("exactly two rotary axes"), "{e}");
    }
}
