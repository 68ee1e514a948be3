//! Job files: what `swarf plan` and `swarf compare` read. A job names the part, the
//! tool, the strategy with its parameters, feeds, linking and the output files.
//!
//! ```toml
//! name = "wave, iso-scallop"
//! part = "../parts/wave.toml"    # relative to the job file; "builtin:wave" for a built-in part
//! tool = "ball:d=8"              # a spec string or a table { shape = "bull", d = 10, r = 2 }
//!
//! [strategy]
//! kind = "iso-scallop"           # iso-parametric | iso-planar | iso-scallop | raster |
//!                                # waterline | steep-shallow | cleanup | drop-spin | roughing
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
//! A STEP or IGES part may be machined in part, and read with options:
//!
//! ```toml
//! part = "mold.step"
//! faces = [3, 7, "cavity-floor"]  # indices as `swarf inspect` lists them, or names
//!
//! [import]
//! unsupported = "refuse"          # or "warn" (default): skip the face, say so
//! trim_chord = 0.0001             # trimming edges sampled within this, mm
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
//! post = "linuxcnc"                   # or fanuc, mach3, grbl, heidenhain, or a post
//!                                     # file (.toml) relative to the job file
//! gcode = "die.ngc"
//! cl = "die.cl"                       # APT CL and pose CSV carry the tool axis
//! ```
//!
//! `arcs = true` in `[output]` writes runs of feed moves that lie on an arc or helix
//! as arc blocks in the post's convention (`G2`/`G3`, Heidenhain `CC`/`C`), within
//! `arc_tolerance` mm (default 0.01) of the moves; 3-axis programs only, off by
//! default ([`swarf_nc::arc_fit`]).
//!
//! With a tool library the tool may be one of its tools, by T number or name:
//!
//! ```toml
//! tools = "../tooling/library.toml"   # relative to the job file
//! tool = "ball6-long"                 # or tool = 3
//! ```
//!
//! The library gives the cutter, the program's T number and the feeds the job's
//! `[feeds]` leave out; `swarf plan` then checks the tool's shank and holder at the
//! library's stick-out at every pose of the planned path and refuses a path where
//! they reach into the part, naming the pass, the pose, the G-code line and the
//! shortest stick-out that clears (five-axis: the extra tilt that clears), as a
//! sequence job does ([`crate::holder::path`]).
//!
//! A tilted tool path is never written as 3-axis G-code: a `positioning` with a
//! `gcode` output needs `output.machine`. A machine without a positioning writes the
//! 3-axis path (vertical tool) as five-axis G-code.
//!
//! Lengths in the job are mm; angles are degrees (converted to radians where they are
//! used, at the input edge).

use crate::error::{AppError, bail};
use crate::model::{FaceRef, LoadOptions, Model};
use crate::stock::Stock;
use crate::strategy::Strategy;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_fiveaxis::positioning::Positioning;
use swarf_fiveaxis::post::FeedMode;
use swarf_nc::Units;
use swarf_path::Cutting;
use swarf_tool::Cutter;
use swarf_toolpath::{Feeds, LinkingSpec};

pub(crate) mod file;
pub(crate) mod read;
mod validate;

use file::ToolFirst;
pub use file::{FeedsSpec, JobFile, ToolRef};
pub(crate) use validate::{check_arcs, output_file};

/// A planning job, as read and checked: the file's tables, its tool resolved
/// (from the library when it names one) and its feeds filled in.
#[derive(Debug, Clone, PartialEq)]
pub struct Job {
    /// Free-text name for reports.
    pub name: Option<String>,
    /// Part file (`.toml` patches, `.stl`/`.obj` mesh, `.step`/`.iges`), relative to
    /// the job file, or `builtin:NAME` for a shared part embedded in swarf.
    pub part: String,
    /// The faces of the part to machine (all when absent).
    pub faces: Option<Vec<FaceRef>>,
    /// How a STEP or IGES part is read.
    pub import: Import,
    /// The tool library the job's `tool` may name, relative to the job file.
    pub tools: Option<String>,
    /// The cutter.
    pub tool: Cutter,
    /// The library tool `tool` names, if it names one.
    pub library_tool: Option<swarf_tool::library::LibraryTool>,
    /// Strategy and its parameters.
    pub strategy: Strategy,
    /// Five-axis positioning of the strategy's CC paths (none: a vertical tool).
    pub positioning: Option<Positioning>,
    /// Feeds and speeds.
    pub feeds: Feeds,
    /// Linking between passes.
    pub linking: LinkingSpec,
    /// The stock the job cuts.
    pub stock: Stock,
    /// How high the material reaches, mm: the stock's top once the part is known
    /// ([`Job::on_stock`]; a sequence's operation: the in-process stock's).
    pub material_top: Option<f64>,
    /// Where the tool tip may go, once the part is known ([`Job::on_stock`]; a
    /// sequence's operation: over the in-process stock): the passes are cut to it.
    pub reach: Option<swarf_toolpath::reach::Reach>,
    /// What `swarf plan` does with the program: verify it on the stock and refuse
    /// it when unsafe (the default), write it labelled, or skip the check
    /// ([`crate::gate`]; a command-line choice, not a key of the job file).
    pub gate: crate::gate::Gate,
    /// Output files.
    pub output: Output,
    /// What a cleanup job cleans up after (`kind = "cleanup"` only).
    pub parent: Option<Parent>,
}

/// How a STEP or IGES part is read (`[import]`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Import {
    /// An entity the reader does not support: `"warn"` skips its face with a warning,
    /// `"refuse"` refuses the file.
    pub unsupported: UnsupportedChoice,
    /// Chordal tolerance for sampling trimming edges, mm.
    pub trim_chord: f64,
}

impl Default for Import {
    fn default() -> Self {
        Import {
            unsupported: UnsupportedChoice::Warn,
            trim_chord: swarf_io::CadOptions::default().trim_chord,
        }
    }
}

/// `import.unsupported`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum UnsupportedChoice {
    /// Skip the face with a warning.
    Warn,
    /// Refuse the file.
    Refuse,
}

impl Job {
    /// Whether the job's tool path is tilted: it has a five-axis positioning, or its
    /// strategy places the tool itself (drop-and-spin).
    pub fn tilted(&self) -> bool {
        self.positioning.is_some() || self.strategy.tilted()
    }

    /// How the job's part is read: its `[import]` table and `faces`.
    pub fn load_options(&self) -> LoadOptions {
        LoadOptions {
            cad: swarf_io::CadOptions {
                unsupported: match self.import.unsupported {
                    UnsupportedChoice::Warn => swarf_io::Unsupported::Warn,
                    UnsupportedChoice::Refuse => swarf_io::Unsupported::Refuse,
                },
                trim_chord: self.import.trim_chord,
            },
            faces: self.faces.clone(),
        }
    }

    /// What every strategy cuts with: the tool, feeds, linking and the material's
    /// top.
    pub fn cutting(&self) -> Cutting {
        Cutting {
            tool: self.tool,
            feeds: self.feeds,
            linking: self.linking,
            material_top: self.material_top,
        }
    }

    /// This job with its material's top and the tool's reach set from its stock
    /// over `model`, whose files are relative to `dir`.
    ///
    /// # Errors
    /// A mesh stock that cannot be read, a stock that does not hold the part, a
    /// floor above the part, a clearance plane below the stock's top.
    pub fn on_stock(&self, model: &Model, dir: &std::path::Path) -> crate::error::Result<Job> {
        let mesh = self.stock.mesh(dir)?;
        let [bottom, part_top] = model.z_range()?;
        let top = self.stock.top(part_top, mesh.as_ref())?;
        if let Some(c) = self.linking.clearance
            && c < top
        {
            bail!(
                "linking.clearance: {} mm is below the stock's top ({top:.3} mm): expected a \
                 clearance plane above the stock",
                swarf_geom::domain::show(c)
            );
        }
        let footprint = self.stock.footprint(&model.bounds(), mesh.as_ref());
        Ok(Job {
            material_top: Some((top * 1e3).ceil() / 1e3),
            reach: Some(swarf_toolpath::reach::Reach::around(
                self.stock.floor(bottom, part_top)?,
                footprint,
                self.tool.radius(),
            )),
            ..self.clone()
        })
    }

    /// The chordal (and gouge) tolerance of the strategy, mm.
    pub fn tolerance(&self) -> f64 {
        self.strategy.finish().tolerance
    }

    /// Parses and validates a job from TOML text; `source` names the file in errors,
    /// and a tool library (`tools`) is read relative to its directory.
    ///
    /// # Errors
    /// As [`Job::parse_in`].
    pub fn parse(text: &str, source: &str) -> Result<Job, AppError> {
        let dir = std::path::Path::new(source)
            .parent()
            .unwrap_or(std::path::Path::new(""));
        Job::parse_in(text, source, dir)
    }

    /// Parses and validates a job from TOML text; `source` names the file in errors,
    /// `dir` is where its tool library (`tools`) is relative to.
    ///
    /// # Errors
    /// [`AppError::Job`] with the file, line and field for malformed TOML, unknown
    /// keys, bad tools, and out-of-range parameters; a library that cannot be read
    /// (`tools`), a library key without a library or missing from it (`tool`, with
    /// the library's tools).
    pub fn parse_in(text: &str, source: &str, dir: &std::path::Path) -> Result<Job, AppError> {
        let err = |message: String| AppError::Job {
            file: source.to_string(),
            message,
        };
        read::from_text::<ToolFirst>(text).map_err(|e| err(e.in_file()))?;
        let file: JobFile = read::from_text(text).map_err(|e| err(e.in_file()))?;
        file.resolve(dir).map_err(|m| {
            err(if m.starts_with("tool: ") {
                read::at_key_line(text, "tool", m)
            } else {
                m
            })
        })
    }

    /// A job from a value in the job file's schema (a Python dict turned into TOML
    /// values); `source` names it in errors (`job dict`), `dir` is where its paths
    /// are relative to.
    ///
    /// # Errors
    /// As [`Job::parse_in`], naming the value's path (`strategy.scallop`) instead of
    /// a line.
    pub fn from_value(
        value: toml::Value,
        source: &str,
        dir: &std::path::Path,
    ) -> Result<Job, AppError> {
        let err = |message: String| AppError::Job {
            file: source.to_string(),
            message,
        };
        read::from_value::<ToolFirst>(value.clone()).map_err(|e| err(e.in_value()))?;
        let file: JobFile = read::from_value(value).map_err(|e| err(e.in_value()))?;
        file.resolve(dir).map_err(err)
    }
}

/// The parent of a cleanup job: a finishing job, or just the tool that finished.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Parent {
    /// The parent job file, relative to this job's file.
    #[serde(default)]
    pub job: Option<String>,
    /// A reference tool instead of a parent job.
    #[serde(default)]
    pub tool: Option<Cutter>,
}

/// Output files of a job, relative to the job file. Each is optional.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Output {
    /// RS274/NGC G-code.
    #[serde(default)]
    pub gcode: Option<String>,
    /// Drop-spin: the contact trajectories, a CSV row per pose.
    #[serde(default)]
    pub contacts: Option<String>,
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
    pub units: Units,
    /// The post the program is written for: a built-in post (`linuxcnc`, the default;
    /// `fanuc`, `mach3`, `grbl`, `heidenhain`) or a post file (`.toml`) relative to the
    /// job file ([`swarf_nc::post`]).
    #[serde(default)]
    pub post: Option<String>,
    /// The older name of `post`, for the built-in posts (`dialect = "fanuc"`).
    #[serde(default)]
    pub dialect: Option<String>,
    /// Machine for five-axis G-code: a machine file relative to the job file, or
    /// `builtin:NAME` for a machine shipped with swarf (`builtin:xyzac-trunnion`, ...).
    #[serde(default)]
    pub machine: Option<String>,
    /// Feeds of five-axis G-code: "inverse-time" (G93) or "units-per-minute" (G94).
    #[serde(default)]
    pub feed_mode: FeedMode,
    /// Spindle gauge line to tool tip, mm (machines with head axes).
    #[serde(default)]
    pub tool_length: Option<f64>,
    /// Write arcs (G2/G3, Heidenhain `C`) where the post has them: runs of feed
    /// moves on an arc or helix become one block (3-axis programs only).
    #[serde(default)]
    pub arcs: bool,
    /// Largest distance between an arc and the moves it replaces, mm (default
    /// [`swarf_nc::DEFAULT_ARC_TOLERANCE_MM`]); only with `arcs = true`.
    #[serde(default)]
    pub arc_tolerance: Option<f64>,
}

impl Output {
    /// The arc tolerance the program is written with: `None` without arcs.
    pub fn arc_tolerance_mm(&self) -> Option<f64> {
        arc_tolerance_mm(self.arcs, self.arc_tolerance)
    }

    /// The post this output names: `post`, else `dialect`, else `linuxcnc`.
    pub fn post_spec(&self) -> &str {
        self.post
            .as_deref()
            .or(self.dialect.as_deref())
            .unwrap_or("linuxcnc")
    }
}

/// The arc tolerance of an output with `arcs` and `arc_tolerance`, mm: `None`
/// without arcs.
pub(crate) fn arc_tolerance_mm(arcs: bool, arc_tolerance: Option<f64>) -> Option<f64> {
    arcs.then(|| arc_tolerance.unwrap_or(swarf_nc::DEFAULT_ARC_TOLERANCE_MM))
}

#[cfg(test)]
mod tests;
