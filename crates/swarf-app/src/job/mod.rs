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

use crate::error::AppError;
use crate::model::{FaceRef, LoadOptions};
use serde::{Deserialize, Serialize};
use swarf_fiveaxis::positioning::Positioning;
use swarf_fiveaxis::post::FeedMode;
use swarf_io::error::toml_message;
use swarf_nc::Units;
use swarf_path::params::{StartSide, StrategyKind};
use swarf_rest::{Pattern, RegionParams};
use swarf_tool::Cutter;
use swarf_toolpath::{Feeds, LinkingSpec};

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
    /// The faces of the part to machine, by index (as `swarf inspect` lists them) or
    /// by name (STEP and IGES names); all faces when absent.
    #[serde(default)]
    pub faces: Option<Vec<FaceRef>>,
    /// How a STEP or IGES part is read.
    #[serde(default)]
    pub import: Import,
    /// The tool library the job's `tool` may name (a file relative to the job file):
    /// a T number or name gives the cutter, the T number and default feeds, and the
    /// shank and holder are checked at every pose of the plan.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tools: Option<String>,
    /// The cutter.
    pub tool: Cutter,
    /// The library tool `tool` names (set by [`Job::parse_in`]).
    #[serde(skip)]
    pub library_tool: Option<swarf_tool::library::LibraryTool>,
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
    pub linking: LinkingSpec,
    /// Output files.
    #[serde(default)]
    pub output: Output,
    /// What a cleanup job cleans up after (`kind = "cleanup"` only).
    #[serde(default)]
    pub parent: Option<Parent>,
}

/// How a STEP or IGES part is read (`[import]`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum UnsupportedChoice {
    /// Skip the face with a warning.
    Warn,
    /// Refuse the file.
    Refuse,
}

impl Job {
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
}

/// The parent of a cleanup job: a finishing job, or just the tool that finished.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Parent {
    /// The parent job file, relative to this job's file.
    #[serde(default)]
    pub job: Option<String>,
    /// A reference tool instead of a parent job.
    #[serde(default)]
    pub tool: Option<Cutter>,
}

/// Where a cleanup job takes its rest from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RestSource {
    /// Crease scans of the part with the parent's tool (any parent).
    #[default]
    Reference,
    /// The double contacts the parent raster job records while it is planned.
    Contacts,
    /// The dexel stock after the parent job's program, minus the design.
    Stock,
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
    /// Feed direction along a parameter (`u` or `v`: iso-parametric, iso-scallop),
    /// or the milling direction (`climb` or `conventional`: waterline,
    /// steep-shallow).
    #[serde(default)]
    pub direction: Option<Direction>,
    /// Feed direction in the XY plane, degrees from +X (iso-planar, raster; the
    /// edge's overall direction for drop-spin).
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
    /// Raster: ramp angle limit, degrees in `(0, 90)` (passes climb and descend no
    /// steeper; the rest it leaves is ramp rest for a cleanup job).
    #[serde(default)]
    pub max_ramp: Option<f64>,
    /// Waterline, steep-shallow: the scallop limit holds on walls this steep and
    /// steeper with the base level spacing; steep-shallow: walls this steep are
    /// steep. Degrees in `(0, 90)`.
    #[serde(default)]
    pub steep_angle: Option<f64>,
    /// Waterline: adaptive levels stop at walls this flat; steep-shallow: areas this
    /// flat are horizontal. Degrees in `(0, steep_angle)`.
    #[serde(default)]
    pub flat_angle: Option<f64>,
    /// Waterline: fixed level spacing, mm (no adaptive levels).
    #[serde(default)]
    pub level_step: Option<f64>,
    /// Waterline: add levels where walls flatten.
    #[serde(default = "default_true")]
    pub adaptive: bool,
    /// Waterline: drop-field grid step, mm (default: a quarter of the tool radius).
    #[serde(default)]
    pub sampling: Option<f64>,
    /// Raster: steepest slope across the passes on which `scallop` must hold,
    /// degrees in `(0, 90)`: the stepover then keeps the scallop within it on every
    /// plane sloping up to this angle (default: a level floor).
    #[serde(default)]
    pub max_slope: Option<f64>,
    /// Cleanup: the cut pattern (`flow-cut` or `follow-pocket`).
    #[serde(default)]
    pub pattern: Pattern,
    /// Cleanup, flow-cut: parallel passes on each side of the pencil pass.
    /// Drop-spin: passes across the spin zone (or `stepover`).
    #[serde(default)]
    pub passes: usize,
    /// Cleanup: where the rest comes from.
    #[serde(default)]
    pub source: RestSource,
    /// Cleanup: rest thinner than this is left, mm (default: the tolerance plus the
    /// scallop height).
    #[serde(default)]
    pub threshold: Option<f64>,
    /// Cleanup: regions closer than this are merged, mm.
    #[serde(default = "default_merge")]
    pub merge: f64,
    /// Cleanup: outward offset of the regions, mm.
    #[serde(default = "default_overlap")]
    pub overlap: f64,
    /// Cleanup: regions with a smaller raw area are dropped, mm².
    #[serde(default = "default_min_area")]
    pub min_area: f64,
    /// Cleanup: concave corners of the boundaries are rounded to at least this
    /// radius, mm.
    #[serde(default = "default_smoothness")]
    pub smoothness: f64,
    /// Cleanup: intermediate tools, largest first, each cleaning up after the one
    /// before it (the parent's tool first); the job's tool cleans up last.
    #[serde(default)]
    pub chain: Vec<Cutter>,
    /// Cleanup: the rest to clean up (default `["valley", "ramp"]`).
    #[serde(default = "default_restmaterial")]
    pub restmaterial: Vec<RestMaterial>,
    /// Drop-spin: the two faces (patch indices), dropped on the first and spun onto
    /// the second (default `[0, 1]`).
    #[serde(default)]
    pub faces: Option<[usize; 2]>,
    /// Drop-spin: spacing of the stations along the edge, mm (default: half the
    /// tool radius).
    #[serde(default)]
    pub step: Option<f64>,
    /// Drop-spin: which side of the tool cuts the second face.
    #[serde(default)]
    pub spin: SpinChoice,
    /// Drop-spin: the whole zone, or only its snug limit.
    #[serde(default)]
    pub zone: ZoneChoice,
    /// Drop-spin: the faces dropped on (the bands of the valley).
    #[serde(default)]
    pub bands: BandChoice,
    /// Roughing: material left on the part, mm (default 0.5).
    #[serde(default)]
    pub allowance: Option<f64>,
    /// Roughing: largest depth of one level, mm (default 2).
    #[serde(default)]
    pub step_down: Option<f64>,
    /// Roughing: largest radial engagement on straight stretches, degrees (default
    /// 60); sets the stepover.
    #[serde(default)]
    pub max_engagement: Option<f64>,
    /// Roughing: ramp angle of the entries, degrees (default 3).
    #[serde(default)]
    pub ramp_angle: Option<f64>,
    /// Roughing: top of the box stock, mm (default 1 mm above the part); the box
    /// covers the part's XY extent.
    #[serde(default)]
    pub stock_top: Option<f64>,
}

/// The bands of drop-spin passes: which faces the tool is dropped on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BandChoice {
    /// Dropped on the first face, spun onto the second: the second face's band.
    First,
    /// Dropped on the second, spun onto the first.
    Second,
    /// Both, the first's passes first: the whole valley.
    #[default]
    Both,
}

impl BandChoice {
    /// The faces dropped on (0 for the first), in cutting order.
    pub fn faces(self) -> Vec<usize> {
        match self {
            BandChoice::First => vec![0],
            BandChoice::Second => vec![1],
            BandChoice::Both => vec![0, 1],
        }
    }
}

/// The cutting side of drop-spin passes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SpinChoice {
    /// The second contact ahead of the axis along the feed.
    #[default]
    Leading,
    /// Behind it.
    Trailing,
    /// Both, leading passes first.
    Both,
}

/// Which passes of the spin zone a drop-spin job cuts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ZoneChoice {
    /// Passes across the zone, the last at its limit.
    #[default]
    Full,
    /// The one pass at the zone's limit, nearest the edge on the second face.
    Snug,
}

/// A kind of rest a cleanup job cleans up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RestMaterial {
    /// Valleys the parent's tool touched on two sides at once (regions from the
    /// source; regions found on the stock count as valley and ramp rest).
    Valley,
    /// Where the parent's ramp limit held its tool above the part (regions).
    Ramp,
    /// Walls whose slope across a parent raster's passes leaves a scallop above the
    /// threshold, cleaned up by Z-levels ([`swarf_rest::steep`]).
    Steep,
}

fn default_restmaterial() -> Vec<RestMaterial> {
    vec![RestMaterial::Valley, RestMaterial::Ramp]
}

/// A feed direction along a parameter, or a milling direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// Passes along u (iso-parametric, iso-scallop).
    U,
    /// Passes along v (iso-parametric, iso-scallop).
    V,
    /// Climb milling: the material on the right of travel (waterline).
    Climb,
    /// Conventional milling: the material on the left (waterline).
    Conventional,
}

fn default_merge() -> f64 {
    RegionParams::default().merge
}

fn default_overlap() -> f64 {
    RegionParams::default().overlap
}

fn default_min_area() -> f64 {
    RegionParams::default().min_area
}

fn default_smoothness() -> f64 {
    RegionParams::default().smoothness
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

impl Job {
    /// Parses and validates a job from TOML text naming no library tool; `source`
    /// names the file in errors.
    fn parse_plain(text: &str, source: &str) -> Result<Job, AppError> {
        let job: Job = toml::from_str(text).map_err(|e| AppError::Job {
            file: source.to_string(),
            message: toml_message(text, &e),
        })?;
        job.validate().map_err(|message| AppError::Job {
            file: source.to_string(),
            message,
        })?;
        Ok(job)
    }
}

mod params;
mod tools;
mod validate;
pub use validate::MAX_DROP_SPIN_PASSES;
pub(crate) use validate::check_arcs;

/// The arc tolerance of an output with `arcs` and `arc_tolerance`, mm: `None`
/// without arcs.
pub(crate) fn arc_tolerance_mm(arcs: bool, arc_tolerance: Option<f64>) -> Option<f64> {
    arcs.then(|| arc_tolerance.unwrap_or(swarf_nc::DEFAULT_ARC_TOLERANCE_MM))
}
pub(crate) use validate::output_file;

#[cfg(test)]
mod tests;
