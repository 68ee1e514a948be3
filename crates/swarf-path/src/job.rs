//! Job files: what `swarf plan` and `swarf compare` read. A job names the part, the
//! tool, the strategy with its parameters, feeds, linking and the output files.
//!
//! ```toml
//! name = "wave, iso-scallop"
//! part = "../parts/wave.toml"    # relative to the job file; "builtin:wave" for a built-in part
//! tool = "ball:d=8"              # a spec string or a table { shape = "bull", d = 10, r = 2 }
//!
//! [strategy]
//! kind = "iso-scallop"           # iso-parametric | iso-planar | iso-scallop | raster
//! scallop = 0.15                 # scallop height limit h, mm
//! tolerance = 0.01               # chordal tolerance along passes, mm
//!
//! [feeds]
//! feed = 300                     # mm/min
//! spindle = 1500                 # rev/min
//!
//! [linking]
//! clearance = 60                 # clearance plane z, mm
//!
//! [output]
//! gcode = "wave-iso-scallop.ngc" # paths relative to the job file; each optional
//! summary = "wave-iso-scallop.json"
//! ```
//!
//! Five-axis jobs add a `positioning` table (how the tool is placed on the CC paths of
//! the strategy, thesis 000 §7.3) and, for G-code, a machine:
//!
//! ```toml
//! positioning = { method = "inclined", alpha = 3, sections = 1.0 }    # fixed lead
//! # positioning = { method = "gouge-free", max_alpha = 25, max_rate = 0.5 }
//!
//! [strategy]
//! kind = "iso-planar"
//! stepover = 3.5                 # fixed cross feed between drive planes, mm
//! angle = 60
//!
//! [output]
//! machine = "builtin:xyzac-trunnion"  # or a machine file relative to the job file
//! feed_mode = "inverse-time"          # G93 (default) or "units-per-minute" (G94)
//! tool_length = 120                   # mm, machines with head axes
//! gcode = "die.ngc"
//! cl = "die.cl"                       # APT CL and pose CSV carry the tool axis
//! ```
//!
//! A tilted tool path is never written as 3-axis G-code: a `positioning` with a
//! `gcode` output needs `output.machine`. A machine without a positioning writes the
//! 3-axis path (vertical tool) as five-axis G-code.
//!
//! Lengths in the job are mm; angles are degrees (converted to radians where they are
//! used, at the input edge).

mod positioning;

pub use positioning::Positioning;

use crate::error::PathError;
use swarf_toolpath::{Feeds, Linking};

/// Linking as a job gives it: the clearance plane may be left to swarf.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct JobLinking {
    /// Clearance plane z, mm; default: 5 mm above the highest CL point of the path.
    pub clearance: Option<f64>,
    /// Distance above a pass start where the plunge feed begins, mm.
    pub approach: f64,
}

impl Default for JobLinking {
    fn default() -> Self {
        JobLinking {
            clearance: None,
            approach: Linking::default().approach,
        }
    }
}

/// Height of the default clearance plane above the highest CL point, mm.
pub const DEFAULT_CLEARANCE_MARGIN: f64 = 5.0;
use serde::{Deserialize, Serialize};
use swarf_io::error::toml_message;
use swarf_tool::Cutter;

/// A planning job.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Job {
    /// Free-text name for reports.
    #[serde(default)]
    pub name: Option<String>,
    /// Part file (`.toml` patches, or `.stl`/`.obj` mesh), relative to the job file,
    /// or `builtin:NAME` for a shared part embedded in swarf.
    pub part: String,
    /// The cutter.
    pub tool: Cutter,
    /// Strategy and its parameters.
    pub strategy: StrategyParams,
    /// Five-axis positioning of the strategy's CC paths (none: a vertical tool).
    #[serde(default)]
    pub positioning: Option<Positioning>,
    /// Feeds and speeds.
    #[serde(default)]
    pub feeds: Feeds,
    /// Linking between passes.
    #[serde(default)]
    pub linking: JobLinking,
    /// Output files.
    #[serde(default)]
    pub output: Output,
}

/// The finishing strategies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StrategyKind {
    /// Passes along constant-parameter curves of each patch (paper 004).
    IsoParametric,
    /// Passes are sections of the part by parallel vertical drive planes (paper 004).
    IsoPlanar,
    /// Each pass is placed so that the scallop to the previous one equals h (paper 004).
    IsoScallop,
    /// Drop-cutter raster on a triangle mesh (iso-planar for meshes).
    Raster,
}

/// Which parameter a pass follows (iso-parametric) or which boundary the first pass
/// starts on (iso-scallop).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ParamDir {
    /// Passes run along u (v constant on each pass).
    #[default]
    U,
    /// Passes run along v (u constant on each pass).
    V,
}

/// Which end of the side-step range the first pass is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StartSide {
    /// Start at the low end (smallest v, or the lowest drive plane offset).
    #[default]
    Min,
    /// Start at the high end.
    Max,
}

/// Strategy parameters. Fields not used by a strategy are ignored by it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrategyParams {
    /// Which strategy.
    pub kind: StrategyKind,
    /// Scallop height limit h, mm (side step from it). Required unless `stepover` is given.
    #[serde(default)]
    pub scallop: Option<f64>,
    /// Fixed side step instead of a scallop limit, mm: the distance between raster
    /// lines, or between the drive planes of iso-planar (the "cross feed" of thesis
    /// 000 ch. 8; then the planes are not spaced by a scallop limit).
    #[serde(default)]
    pub stepover: Option<f64>,
    /// Chordal tolerance along a pass (and gouge tolerance), mm.
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Feed direction along a parameter (iso-parametric, iso-scallop).
    #[serde(default)]
    pub direction: ParamDir,
    /// Feed direction in the XY plane, degrees from +X (iso-planar, raster).
    #[serde(default)]
    pub angle: f64,
    /// Side the first pass starts on.
    #[serde(default)]
    pub start: StartSide,
    /// Alternate the cutting direction of consecutive passes.
    #[serde(default = "default_true")]
    pub zigzag: bool,
    /// Raster boundary `[xmin, ymin, xmax, ymax]`, mm (default: the mesh outline).
    #[serde(default)]
    pub boundary: Option<[f64; 4]>,
}

fn default_tolerance() -> f64 {
    0.01
}

fn default_true() -> bool {
    true
}

/// Output files of a job, relative to the job file. Each is optional.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Output {
    /// RS274/NGC G-code.
    #[serde(default)]
    pub gcode: Option<String>,
    /// APT CL data.
    #[serde(default)]
    pub cl: Option<String>,
    /// Pose CSV (`x,y,z,i,j,k`).
    #[serde(default)]
    pub csv: Option<String>,
    /// JSON summary.
    #[serde(default)]
    pub summary: Option<String>,
    /// Double contacts found by the raster strategy (CSV).
    #[serde(default)]
    pub double_contacts: Option<String>,
    /// Output units: "mm" or "inch".
    #[serde(default)]
    pub units: OutputUnits,
    /// G-code dialect: "linuxcnc" or "fanuc".
    #[serde(default)]
    pub dialect: OutputDialect,
    /// Machine for five-axis G-code: a machine file relative to the job file, or
    /// `builtin:NAME` for a machine shipped with swarf (`builtin:xyzac-trunnion`, ...).
    #[serde(default)]
    pub machine: Option<String>,
    /// Feeds of five-axis G-code: "inverse-time" (G93) or "units-per-minute" (G94).
    #[serde(default)]
    pub feed_mode: OutputFeedMode,
    /// Spindle gauge line to tool tip, mm (machines with head axes).
    #[serde(default)]
    pub tool_length: Option<f64>,
}

/// Feed mode of five-axis G-code (mirrors the five-axis post's, which sits above
/// this crate).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OutputFeedMode {
    /// G93: `F` is the inverse of each move's time.
    #[default]
    InverseTime,
    /// G94: `F` in length units per minute.
    UnitsPerMinute,
}

/// Output length units (mirrors the NC crate's, which sits below this one).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum OutputUnits {
    /// Millimetres.
    #[default]
    Mm,
    /// Inches.
    Inch,
}

/// G-code dialect (mirrors the NC crate's).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum OutputDialect {
    /// LinuxCNC.
    #[default]
    Linuxcnc,
    /// Fanuc-style controls.
    Fanuc,
}

impl Job {
    /// Parses and validates a job from TOML text; `source` names the file in errors.
    ///
    /// # Errors
    /// [`PathError::Job`] with the file, line and field for malformed TOML, unknown
    /// keys, bad tools, and out-of-range parameters.
    pub fn parse(text: &str, source: &str) -> Result<Job, PathError> {
        let job: Job = toml::from_str(text).map_err(|e| PathError::Job {
            file: source.to_string(),
            message: toml_message(text, &e),
        })?;
        job.validate().map_err(|message| PathError::Job {
            file: source.to_string(),
            message,
        })?;
        Ok(job)
    }

    /// Checks parameter ranges that the TOML types cannot express.
    fn validate(&self) -> Result<(), String> {
        let s = &self.strategy;
        positive("strategy.tolerance", Some(s.tolerance))?;
        positive("strategy.scallop", s.scallop)?;
        positive("strategy.stepover", s.stepover)?;
        if s.scallop.is_none() && s.stepover.is_none() {
            return Err(
                "strategy: expected `scallop` (scallop height limit, mm) or `stepover` (mm)".into(),
            );
        }
        match (s.kind, s.scallop, s.stepover) {
            (StrategyKind::Raster, _, _) | (_, _, None) => {}
            (StrategyKind::IsoPlanar, Some(_), Some(_)) => {
                return Err(
                    "strategy.stepover: give either `scallop` (plane spacing from a scallop limit) or `stepover` (a fixed cross feed), not both"
                        .into(),
                );
            }
            (StrategyKind::IsoPlanar, None, Some(step)) => {
                let d = 2.0 * self.tool.radius();
                if step >= d {
                    return Err(format!(
                        "strategy.stepover: {step} mm is not smaller than the tool diameter {d} mm"
                    ));
                }
            }
            (_, _, Some(_)) => {
                return Err(
                    "strategy.stepover: only the raster and iso-planar strategies take a fixed stepover; use `scallop`"
                        .into(),
                );
            }
        }
        if let Some(h) = s.scallop {
            let r = self.tool.radius();
            if h >= r {
                return Err(format!(
                    "strategy.scallop: {h} mm is not smaller than the tool radius {r} mm; expected 0 < scallop < tool radius"
                ));
            }
        }
        if !s.angle.is_finite() {
            return Err("strategy.angle: expected a finite angle in degrees".into());
        }
        if let Some(b) = s.boundary
            && !(b.iter().all(|x| x.is_finite()) && b[0] < b[2] && b[1] < b[3])
        {
            return Err(format!(
                "strategy.boundary: expected [xmin, ymin, xmax, ymax] with xmin < xmax and ymin < ymax, found {b:?}"
            ));
        }
        let f = &self.feeds;
        for (name, v) in [
            ("feeds.feed", f.feed),
            ("feeds.plunge", f.plunge),
            ("feeds.rapid", f.rapid),
            ("feeds.spindle", f.spindle),
        ] {
            positive(name, Some(v))?;
        }
        if self.linking.clearance.is_some_and(|c| !c.is_finite()) {
            return Err("linking.clearance: expected a finite height in mm".into());
        }
        positive("linking.approach", Some(self.linking.approach))?;
        self.validate_five_axis()
    }

    /// The positioning's ranges and the outputs a five-axis job can write.
    fn validate_five_axis(&self) -> Result<(), String> {
        if let Some(p) = &self.positioning {
            p.validate()
                .map_err(|(field, message)| format!("{field}: {message}"))?;
        }
        let o = &self.output;
        if self.positioning.is_some() && o.gcode.is_some() && o.machine.is_none() {
            return Err(
                "output.machine: a tilted tool path needs a machine file for G-code (e.g. machine = \"builtin:xyzac-trunnion\"); or drop output.gcode (output.cl and output.csv carry the tool axis)"
                    .into(),
            );
        }
        if o.machine.as_deref().is_some_and(str::is_empty) {
            return Err("output.machine: expected a machine file or builtin:NAME".into());
        }
        positive("output.tool_length", o.tool_length)
    }

    /// The linking for a path whose highest CL point is at `top_z`: the job's
    /// clearance when given (raised to `top_z` if it is below), else `top_z` plus
    /// [`DEFAULT_CLEARANCE_MARGIN`].
    pub fn linking_for(&self, top_z: f64) -> Linking {
        Linking {
            clearance: self
                .linking
                .clearance
                .map_or(top_z + DEFAULT_CLEARANCE_MARGIN, |c| c.max(top_z)),
            approach: self.linking.approach,
        }
    }

    /// The feed direction angle in radians.
    pub fn angle_rad(&self) -> f64 {
        self.strategy.angle.to_radians()
    }
}

fn positive(name: &str, v: Option<f64>) -> Result<(), String> {
    match v {
        Some(x) if !(x.is_finite() && x > 0.0) => {
            Err(format!("{name}: expected a finite number > 0, found {x}"))
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
part = "builtin:wave"
tool = "ball:d=8"
[strategy]
kind = "iso-scallop"
scallop = 0.15
tolerance = 0.01
[feeds]
feed = 300
spindle = 1500
[linking]
clearance = 60
[output]
gcode = "a.ngc"
"#;

    #[test]
    fn parses_a_good_job() {
        let job = Job::parse(GOOD, "job.toml").unwrap();
        assert_eq!(job.strategy.kind, StrategyKind::IsoScallop);
        assert_eq!(job.strategy.scallop, Some(0.15));
        assert_eq!(job.feeds.feed, 300.0);
        assert_eq!(job.feeds.plunge, Feeds::default().plunge);
        assert!(job.strategy.zigzag);
        assert_eq!(job.output.gcode.as_deref(), Some("a.ngc"));
    }

    #[test]
    fn bad_jobs_name_the_field() {
        let cases = [
            (
                GOOD.replace("scallop = 0.15", "scallop = -1"),
                "strategy.scallop",
            ),
            (
                GOOD.replace("scallop = 0.15", "scallop = 5"),
                "strategy.scallop",
            ),
            (
                GOOD.replace("tolerance = 0.01", "tolerance = 0"),
                "strategy.tolerance",
            ),
            (
                GOOD.replace("scallop = 0.15", ""),
                "strategy: expected `scallop`",
            ),
            (GOOD.replace("feed = 300", "feed = -3"), "feeds.feed"),
            (
                GOOD.replace("kind = \"iso-scallop\"", "kind = \"spiral\""),
                "line 5",
            ),
            (GOOD.replace("feed = 300", "fed = 300"), "fed"),
            (GOOD.replace("ball:d=8", "ball:d=-8"), "line 3"),
        ];
        for (text, want) in cases {
            let e = Job::parse(&text, "job.toml").unwrap_err().to_string();
            assert!(e.starts_with("job.toml: "), "{e}");
            assert!(e.contains(want), "want {want:?} in {e}");
        }
    }
}
