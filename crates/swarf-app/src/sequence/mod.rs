//! Sequence jobs: operations in order on one in-process stock, from stock to part
//! (thesis 002 §4.1: the stock B, operations P1 ... Pn each turning the in-process
//! model IOPM(i-1) into IOPM(i), the rest the last IOPM less the design).
//!
//! ```toml
//! name = "fillet pocket, stock to part"
//! part = "builtin:fillet-pocket"
//!
//! tools = "../tooling/library.toml"   # optional: operations may name its tools
//!
//! [stock]
//! kind = "box"          # "box" (top, margin), "offset" (allowance) or "mesh" (file)
//! top = 21              # box top, mm (default 1 mm above the part)
//! cell = 0.25           # in-process stock cell, mm
//!
//! [[operation]]         # a job's tool, strategy, feeds and linking tables
//! name = "rough"
//! tool = "flat:d=10"
//! number = 1            # T word (default: the operation's place, from 1)
//! strategy = { kind = "roughing", allowance = 0.5, step_down = 4 }
//!
//! [[operation]]
//! name = "finish"
//! tool = "ball:d=12"
//! strategy = { kind = "raster", scallop = 0.01 }
//!
//! [[operation]]
//! name = "cleanup"
//! tool = "ball:d=4"
//! strategy = { kind = "cleanup", scallop = 0.01 }   # rest from the stock
//!
//! [output]
//! gcode = "pocket.ngc"  # one program, a tool change per operation
//! summary = "pocket.json"
//! post = "fanuc"        # linuxcnc (default), fanuc, mach3, grbl, heidenhain, a file
//! arcs = true           # arcs and helices as G2/G3 (Heidenhain CC/C), as a job's
//! arc_tolerance = 0.01  # mm, the default
//! ```
//!
//! With a tool library, an operation's `tool` may be a library tool's number or
//! name: its cutter, T number and default feeds come from the library, and its
//! shank and holder at the library's stick-out are checked against the part at
//! every pose of the operation's program ([`crate::holder`]); a collision stops
//! the job, naming the operation, where it collides and the shortest stick-out
//! that clears.
//!
//! Each operation is a job of its own ([`crate::job`]: the same tables, checked
//! the same way, errors naming `operation[k]`), on the sequence's part. Roughing
//! takes its material from the in-process stock, so a second roughing is rest
//! roughing; a cleanup takes its rest from the in-process stock (the `stock` source:
//! stock minus design), with the operation before it as the reference tool. Every
//! operation is simulated on the stock as soon as it is planned, and reported: its
//! time, the engagement of roughing measured on the stock ([`swarf_sim::engagement`]),
//! gouge and rest after it.

mod report;
mod run;

use crate::error::AppError;
use crate::job::read::{Key, Located};
use crate::job::{FeedsSpec, Import, Job, Output, Parent, ToolRef};
use crate::model::FaceRef;
use crate::stock::Stock;
use crate::strategy::Strategy;
use schemars::JsonSchema;
use serde::Deserialize;
use std::path::Path;
use swarf_tool::library::ToolLibrary;
use swarf_toolpath::LinkingSpec;

pub use crate::holder::HolderSummary;
pub use report::{EngagementSummary, OperationReport, SequenceReport};
pub use run::plan_sequence;

/// A sequence job as its file states it (module doc).
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SequenceFile {
    /// Free-text name for reports.
    #[serde(default)]
    pub name: Option<String>,
    /// The part, as a job names it.
    pub part: String,
    /// The faces of the part to machine (all when absent).
    #[serde(default)]
    pub faces: Option<Vec<FaceRef>>,
    /// How a STEP or IGES part is read.
    #[serde(default)]
    pub import: Import,
    /// The tool library the operations' `tool` may name, relative to the job file.
    #[serde(default)]
    pub tools: Option<String>,
    /// The stock.
    #[serde(default)]
    pub stock: Stock,
    /// The operations, in order.
    pub operation: Vec<OperationFile>,
    /// Outputs.
    #[serde(default)]
    pub output: SequenceOutput,
}

/// One `[[operation]]` table: a job's tool, strategy, feeds and linking.
#[derive(Debug, Clone, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OperationFile {
    /// Name (default `operation[k]`).
    #[serde(default)]
    pub name: Option<String>,
    /// T word, 1 to 99999 (default: the operation's place, from 1; a library tool's
    /// own number).
    #[serde(default)]
    pub number: Option<i64>,
    /// The cutter, or a library tool's T number or name.
    pub tool: ToolRef,
    /// Strategy and its parameters.
    pub strategy: Strategy,
    /// Feeds and speeds.
    #[serde(default)]
    pub feeds: FeedsSpec,
    /// Linking between passes.
    #[serde(default)]
    pub linking: LinkingSpec,
}

/// The keys of a job that a sequence gives, not its operations.
const SEQUENCE_KEYS: [&str; 8] = [
    "part",
    "stock",
    "faces",
    "import",
    "output",
    "parent",
    "positioning",
    "tools",
];

/// Outputs of a sequence.
#[derive(Debug, Clone, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SequenceOutput {
    /// The one program, a tool change per operation.
    #[serde(default)]
    pub gcode: Option<String>,
    /// JSON summary with every operation's report.
    #[serde(default)]
    pub summary: Option<String>,
    /// The post: a built-in name (`linuxcnc`, `fanuc`, `mach3`, `grbl`,
    /// `heidenhain`) or a post file relative to the job file (default `linuxcnc`).
    #[serde(default)]
    pub post: Option<String>,
    /// Output units: "mm" or "inch".
    #[serde(default)]
    pub units: swarf_nc::Units,
    /// Write arcs where the post has them (as a job's `output.arcs`).
    #[serde(default)]
    pub arcs: bool,
    /// Arc tolerance, mm (as a job's `output.arc_tolerance`).
    #[serde(default)]
    pub arc_tolerance: Option<f64>,
}

impl SequenceOutput {
    /// The arc tolerance the program is written with: `None` without arcs.
    pub fn arc_tolerance_mm(&self) -> Option<f64> {
        crate::job::arc_tolerance_mm(self.arcs, self.arc_tolerance)
    }
}

/// One operation: its job and its tool number.
#[derive(Debug, Clone)]
pub struct Operation {
    /// Name (`operation[k]` when not given).
    pub name: String,
    /// T number.
    pub number: u32,
    /// The operation as a job on the sequence's part (with the library tool it
    /// names, whose shank, holder and stick-out are checked).
    pub job: Job,
}

/// A parsed sequence job.
#[derive(Debug, Clone)]
pub struct Sequence {
    /// Name.
    pub name: Option<String>,
    /// The part, as a job names it.
    pub part: String,
    /// The stock.
    pub stock: Stock,
    /// Operations in order.
    pub operations: Vec<Operation>,
    /// What `swarf plan` does with an unsafe program ([`crate::gate`]; every
    /// operation is simulated on the in-process stock whatever this says).
    pub gate: crate::gate::Gate,
    /// Outputs.
    pub output: SequenceOutput,
}

/// Most operations in one sequence.
pub const MAX_OPERATIONS: usize = 64;

impl Sequence {
    /// Whether `text` is a sequence job (it has `[[operation]]` tables).
    pub fn is_sequence(text: &str) -> bool {
        toml::from_str::<toml::Table>(text).is_ok_and(|t| t.contains_key("operation"))
    }

    /// Parses and checks a sequence job; `source` names the file in errors, `dir`
    /// is where its paths (the tool library) are relative to.
    ///
    /// # Errors
    /// [`AppError::Job`] naming the file, and `operation[k]` and its field, for
    /// malformed TOML, unknown keys, a bad stock, a tool the library lacks, and
    /// every error a job can have; a library that cannot be read.
    pub fn parse(text: &str, source: &str, dir: &Path) -> Result<Sequence, AppError> {
        let err = |message: String| AppError::Job {
            file: source.to_string(),
            message,
        };
        let file: SequenceFile =
            crate::job::read::from_text(text).map_err(|e| err(misplaced(e).in_file()))?;
        file.resolve(dir).map_err(err)
    }

    /// A sequence from a value in the sequence file's schema (a Python dict turned
    /// into TOML values); `source` names it in errors.
    ///
    /// # Errors
    /// As [`Sequence::parse`], naming the value's path instead of a line.
    pub fn from_value(value: toml::Value, source: &str, dir: &Path) -> Result<Sequence, AppError> {
        let err = |message: String| AppError::Job {
            file: source.to_string(),
            message,
        };
        let file: SequenceFile =
            crate::job::read::from_value(value).map_err(|e| err(misplaced(e).in_value()))?;
        file.resolve(dir).map_err(err)
    }
}

/// An error about a job's key given in an operation, said so.
fn misplaced(mut e: Located) -> Located {
    if let [Key::Name(op), Key::Index(_), Key::Name(key)] = e.path.as_slice()
        && op == "operation"
        && SEQUENCE_KEYS.contains(&key.as_str())
        && e.message.starts_with("unknown field")
    {
        e.message = format!(
            "{key}: not an operation's key (the sequence gives part, faces, import, stock, \
             tools and output; operations are three-axis)"
        );
        e.path.pop();
    }
    e
}

impl SequenceFile {
    /// The sequence this file states, its library read relative to `dir`, checked.
    ///
    /// # Errors
    /// A bad stock or output, a library that cannot be read, and every error of an
    /// operation, as `operation[k]: field: message`.
    pub fn resolve(self, dir: &Path) -> Result<Sequence, String> {
        self.stock.check()?;
        crate::job::check_arcs(self.output.arcs, self.output.arc_tolerance)?;
        for (name, file) in [
            ("output.gcode", &self.output.gcode),
            ("output.summary", &self.output.summary),
        ] {
            if let Some(f) = file {
                crate::job::output_file(name, f)?;
            }
        }
        if self.operation.is_empty() || self.operation.len() > MAX_OPERATIONS {
            return Err(format!(
                "operation: expected 1 to {MAX_OPERATIONS} [[operation]] tables, found {}",
                self.operation.len()
            ));
        }
        let library = crate::job::file::read_library(self.tools.as_deref(), dir)?;
        let mut operations: Vec<Operation> = Vec::with_capacity(self.operation.len());
        for (k, op) in self.operation.iter().enumerate() {
            let op = self
                .operation_job(library.as_ref(), k, op, operations.last())
                .map_err(|m| format!("operation[{k}]: {m}"))?;
            operations.push(op);
        }
        Ok(Sequence {
            name: self.name,
            part: self.part,
            stock: self.stock,
            operations,
            gate: crate::gate::Gate::default(),
            output: self.output,
        })
    }

    /// Operation `k` as a job on the sequence's part, faces and import, its tool
    /// from the library when it names one; a cleanup cleans up after the operation
    /// before it (its tool is the reference).
    fn operation_job(
        &self,
        library: Option<&ToolLibrary>,
        k: usize,
        op: &OperationFile,
        prev: Option<&Operation>,
    ) -> Result<Operation, String> {
        let (tool, library_tool) = op.tool.resolve(library)?;
        let number = match (op.number, &library_tool) {
            (Some(v), Some(lt)) => {
                return Err(format!(
                    "number: {v} given for the library's tool T{} \"{}\": the library gives its \
                     number",
                    lt.number, lt.name
                ));
            }
            (Some(n), None) if (1..=99_999).contains(&n) => n as u32,
            (Some(v), None) => {
                return Err(format!(
                    "number: expected a tool number from 1 to 99999, found {v}"
                ));
            }
            (None, Some(lt)) => lt.number,
            (None, None) => k as u32 + 1,
        };
        let parent = match (&op.strategy, prev) {
            (Strategy::Cleanup(_), None) => {
                return Err(
                    "strategy.kind: a cleanup cannot be the first operation: it cleans \
                            up after the operation before it"
                        .into(),
                );
            }
            (Strategy::Cleanup(_), Some(p)) => Some(Parent {
                job: None,
                tool: Some(p.job.tool),
            }),
            _ => None,
        };
        let job = Job {
            name: None,
            part: self.part.clone(),
            faces: self.faces.clone(),
            import: self.import,
            tools: None,
            tool,
            feeds: op.feeds.resolve(library_tool.as_ref()),
            library_tool,
            strategy: op.strategy.clone(),
            positioning: None,
            linking: op.linking,
            stock: self.stock.clone(),
            material_top: None,
            reach: None,
            gate: crate::gate::Gate::default(),
            output: Output::default(),
            parent,
        };
        job.validate()?;
        Ok(Operation {
            name: op.name.clone().unwrap_or_else(|| format!("operation[{k}]")),
            number,
            job,
        })
    }
}
