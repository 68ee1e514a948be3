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
use crate::holder::library::{default_feeds, named_tool};
use crate::job::Job;
use crate::model::FaceRef;
use serde::Deserialize;
use std::path::Path;
use swarf_geom::domain::show;
use swarf_io::error::toml_message;
use swarf_tool::library::ToolLibrary;

pub use crate::holder::HolderSummary;
pub use report::{EngagementSummary, OperationReport, SequenceReport};
pub use run::plan_sequence;

/// A sequence job as read (module doc).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct SequenceRepr {
    #[serde(default)]
    name: Option<String>,
    part: String,
    #[serde(default)]
    faces: Option<Vec<FaceRef>>,
    #[serde(default)]
    import: Option<toml::Table>,
    #[serde(default)]
    tools: Option<String>,
    #[serde(default)]
    stock: Stock,
    operation: Vec<toml::Table>,
    #[serde(default)]
    output: SequenceOutput,
}

/// The stock a sequence starts from.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Stock {
    /// `box`, `offset` or `mesh`.
    pub kind: StockKind,
    /// Box: top, mm (default 1 mm above the part).
    pub top: Option<f64>,
    /// Box: XY margin round the part, mm.
    pub margin: f64,
    /// Offset: material above the design, mm.
    pub allowance: f64,
    /// Mesh: the stock's file (STL or OBJ), relative to the job file.
    pub file: Option<String>,
    /// Cell of the in-process stock, mm.
    pub cell: f64,
    /// Gouge and rest tolerance of the per-operation reports, mm.
    pub tol: f64,
}

impl Default for Stock {
    fn default() -> Self {
        Stock {
            kind: StockKind::Box,
            top: None,
            margin: 0.0,
            allowance: 1.0,
            file: None,
            cell: 0.25,
            tol: 0.01,
        }
    }
}

/// How the stock is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StockKind {
    /// A block over the part's XY extent.
    #[default]
    Box,
    /// The design raised by an allowance.
    Offset,
    /// A mesh's upper envelope.
    Mesh,
}

/// Outputs of a sequence.
#[derive(Debug, Clone, Default, Deserialize)]
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
        let repr: SequenceRepr = toml::from_str(text).map_err(|e| err(toml_message(text, &e)))?;
        check_stock(&repr.stock).map_err(err)?;
        crate::job::check_arcs(repr.output.arcs, repr.output.arc_tolerance).map_err(err)?;
        for (name, file) in [
            ("output.gcode", &repr.output.gcode),
            ("output.summary", &repr.output.summary),
        ] {
            if let Some(f) = file {
                crate::job::output_file(name, f).map_err(err)?;
            }
        }
        if repr.operation.is_empty() || repr.operation.len() > MAX_OPERATIONS {
            return Err(err(format!(
                "operation: expected 1 to {MAX_OPERATIONS} [[operation]] tables, found {}",
                repr.operation.len()
            )));
        }
        let library = match &repr.tools {
            Some(file) => {
                Some(ToolLibrary::read(&dir.join(file)).map_err(|e| err(format!("tools: {e}")))?)
            }
            None => None,
        };
        let mut operations = Vec::with_capacity(repr.operation.len());
        for (k, table) in repr.operation.iter().enumerate() {
            let op = operation(&repr, library.as_ref(), k, table, operations.last())
                .map_err(|m| err(format!("operation[{k}]: {m}")))?;
            operations.push(op);
        }
        Ok(Sequence {
            name: repr.name,
            part: repr.part,
            stock: repr.stock,
            operations,
            output: repr.output,
        })
    }
}

/// Operation `k` as a job: its own table with the sequence's part, faces and import,
/// its tool from the library when it names one.
fn operation(
    repr: &SequenceRepr,
    library: Option<&ToolLibrary>,
    k: usize,
    table: &toml::Table,
    prev: Option<&Operation>,
) -> Result<Operation, String> {
    let mut t = table.clone();
    let library_tool = named_tool(library, t.get("tool"))?.cloned();
    if let Some(lt) = &library_tool {
        let spec = toml::Value::String(lt.assembly.cutter.to_string());
        t.insert("tool".into(), spec);
    }
    let name = match t.remove("name") {
        Some(toml::Value::String(s)) => s,
        Some(v) => return Err(format!("name: expected text, found {v}")),
        None => format!("operation[{k}]"),
    };
    let number = match (t.remove("number"), &library_tool) {
        (Some(v), Some(lt)) => {
            return Err(format!(
                "number: {v} given for the library's tool T{} \"{}\": the library gives its \
                 number",
                lt.number, lt.name
            ));
        }
        (Some(toml::Value::Integer(n)), None) if (1..=99_999).contains(&n) => n as u32,
        (Some(v), None) => {
            return Err(format!(
                "number: expected a tool number from 1 to 99999, found {v}"
            ));
        }
        (None, Some(lt)) => lt.number,
        (None, None) => k as u32 + 1,
    };
    for key in [
        "part",
        "faces",
        "import",
        "output",
        "parent",
        "positioning",
        "tools",
    ] {
        if t.contains_key(key) {
            return Err(format!(
                "{key}: not an operation's key (the sequence gives part, faces, import, tools \
                 and output; operations are three-axis)"
            ));
        }
    }
    t.insert("part".into(), toml::Value::String(repr.part.clone()));
    // A cleanup cleans up after the operation before it (its tool is the reference).
    let prev_tool = prev.map(|p| toml::Value::String(p.job.tool.to_string()));
    let is_cleanup = t
        .get("strategy")
        .and_then(|s| s.get("kind"))
        .and_then(toml::Value::as_str)
        == Some("cleanup");
    if is_cleanup && k == 0 {
        return Err(
            "strategy.kind: a cleanup cannot be the first operation: it cleans up \
                    after the operation before it"
                .into(),
        );
    }
    if is_cleanup && let Some(tool) = prev_tool {
        let mut parent = toml::Table::new();
        parent.insert("tool".into(), tool);
        t.insert("parent".into(), toml::Value::Table(parent));
    }
    if let Some(faces) = &repr.faces {
        let v = toml::Value::try_from(faces).map_err(|e| e.to_string())?;
        t.insert("faces".into(), v);
    }
    if let Some(import) = &repr.import {
        t.insert("import".into(), toml::Value::Table(import.clone()));
    }
    let text = toml::to_string(&t).map_err(|e| e.to_string())?;
    // The table was written out again: a line number in a message would be of that
    // text, not of the file, so it is dropped.
    let mut job = Job::parse(&text, "").map_err(|e| match e {
        AppError::Job { message, .. } => without_line(&message).to_string(),
        other => other.to_string(),
    })?;
    if let Some(lt) = &library_tool {
        default_feeds(lt, table.get("feeds"), &mut job.feeds);
    }
    job.library_tool = library_tool;
    Ok(Operation { name, number, job })
}

/// `message` without a leading `line N: `.
fn without_line(message: &str) -> &str {
    message
        .strip_prefix("line ")
        .and_then(|rest| {
            let (n, tail) = rest.split_once(": ")?;
            n.chars().all(|c| c.is_ascii_digit()).then_some(tail)
        })
        .unwrap_or(message)
}

fn check_stock(s: &Stock) -> Result<(), String> {
    let cell_ok = s.cell.is_finite() && (0.01..=10.0).contains(&s.cell);
    if !cell_ok {
        return Err(format!(
            "stock.cell: {} mm: expected 0.01 to 10 mm",
            show(s.cell)
        ));
    }
    if !(s.tol.is_finite() && s.tol > 0.0 && s.tol <= 10.0) {
        return Err(format!(
            "stock.tol: {} mm: expected more than 0, at most 10 mm",
            show(s.tol)
        ));
    }
    if !(s.margin.is_finite() && (0.0..=1000.0).contains(&s.margin)) {
        return Err(format!(
            "stock.margin: {} mm: expected 0 to 1000 mm",
            show(s.margin)
        ));
    }
    if !(s.allowance.is_finite() && (0.0..=1000.0).contains(&s.allowance)) {
        return Err(format!(
            "stock.allowance: {} mm: expected 0 to 1000 mm",
            show(s.allowance)
        ));
    }
    if let Some(top) = s.top
        && !(top.is_finite() && top.abs() <= 1e6)
    {
        return Err(format!(
            "stock.top: {top} mm: expected a height within 1e6 mm"
        ));
    }
    if s.kind == StockKind::Mesh && s.file.is_none() {
        return Err("stock.file: a mesh stock needs its file (STL or OBJ)".into());
    }
    Ok(())
}
