//! The plan record: what a plan knows that a verification of its program needs,
//! written beside every program swarf writes (`part.ngc`, `part.cl`, `part.csv`
//! share `part.record.json`) and read back by `swarf verify` and `swarf view` for
//! G-code, APT CL and pose CSV alike. Its fields are the defaults of those commands
//! (flags given override them): the tools with their numbers, each operation's
//! planned scallop (the excess allowance) and tolerance, the machine and the post.
//!
//! The G-code header says the same for a reader (`(scallop limit 0.15 mm)`); with a
//! record beside the program the header is not read.
//!
//! The record is versioned ([`VERSION`]): a reader refuses a record of a version it
//! does not know, naming the file, rather than guess.

use crate::error::{AppError, Result};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use swarf_nc::Units;

/// What the record's `format` field says.
pub const FORMAT: &str = "swarf plan record";
/// The record's version.
pub const VERSION: u32 = 1;
/// The record's extension, after the program's stem.
pub const EXTENSION: &str = "record.json";

/// A plan record (module doc).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanRecord {
    /// [`FORMAT`].
    pub format: String,
    /// [`VERSION`].
    pub version: u32,
    /// The part, as the job names it.
    pub part: String,
    /// Units of the programs.
    pub units: Units,
    /// The programs the record is for (file names beside it).
    pub programs: Vec<String>,
    /// The tools, in the order the program uses them.
    pub tools: Vec<ToolRecord>,
    /// The operations, in order (one for a single job).
    pub operations: Vec<OperationRecord>,
    /// The machine of five-axis G-code, as the job names it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub machine: Option<String>,
    /// Spindle gauge line to tool tip, mm (machines with head axes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tool_length: Option<f64>,
    /// The post the G-code is written for.
    pub post: String,
}

/// A tool of the program.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToolRecord {
    /// T number.
    pub number: u32,
    /// The cutter, as a spec.
    pub cutter: String,
    /// The library tool's name, if the job named one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
}

/// An operation of the program: what it was planned for.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OperationRecord {
    /// Name (the job's, or the sequence operation's).
    pub name: String,
    /// The strategy's kind.
    pub strategy: String,
    /// T number of its tool.
    pub tool: u32,
    /// The scallop height it was planned for, mm (the material it leaves above the
    /// design by intent; for roughing, its allowance).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scallop: Option<f64>,
    /// Its chordal and gouge tolerance, mm.
    pub tolerance: f64,
}

impl PlanRecord {
    /// A record of `operations` with `tools` on `part`, for the program files
    /// `programs`.
    pub fn new(
        part: &str,
        units: Units,
        tools: Vec<ToolRecord>,
        operations: Vec<OperationRecord>,
        post: &str,
    ) -> PlanRecord {
        PlanRecord {
            format: FORMAT.into(),
            version: VERSION,
            part: part.into(),
            units,
            programs: Vec::new(),
            tools,
            operations,
            machine: None,
            tool_length: None,
            post: post.into(),
        }
    }

    /// The largest scallop any operation was planned for, mm.
    pub fn scallop(&self) -> Option<f64> {
        self.operations
            .iter()
            .filter_map(|o| o.scallop)
            .reduce(f64::max)
    }

    /// The smallest tolerance of the operations, mm.
    pub fn tolerance(&self) -> Option<f64> {
        self.operations.iter().map(|o| o.tolerance).reduce(f64::min)
    }

    /// The tools as specs, in program order.
    pub fn tool_specs(&self) -> Vec<String> {
        self.tools.iter().map(|t| t.cutter.clone()).collect()
    }

    /// Checks what the record holds: its format and version, finite figures.
    ///
    /// # Errors
    /// A message naming the field.
    fn check(&self) -> std::result::Result<(), String> {
        if self.format != FORMAT {
            return Err(format!(
                "format: expected {FORMAT:?}, found {:?}",
                self.format
            ));
        }
        if self.version != VERSION {
            return Err(format!(
                "version: {} is not a version this swarf reads (expected {VERSION})",
                self.version
            ));
        }
        for o in &self.operations {
            let ok = o.scallop.is_none_or(|h| h.is_finite() && h >= 0.0)
                && o.tolerance.is_finite()
                && o.tolerance > 0.0;
            if !ok {
                return Err(format!(
                    "operations: {:?}: expected a scallop of 0 or more and a positive tolerance",
                    o.name
                ));
            }
        }
        Ok(())
    }
}

/// The record of the program `program`: beside it, named by its stem
/// ([`EXTENSION`]).
pub fn record_path(program: &Path) -> PathBuf {
    program.with_extension(EXTENSION)
}

/// The record file name for the program output `rel` (relative to the outputs).
pub fn record_name(rel: &str) -> String {
    record_path(Path::new(rel)).display().to_string()
}

/// Reads the record beside `program`, if there is one.
///
/// # Errors
/// A record that cannot be read, is not JSON of this schema, or is of another
/// version, naming its file.
pub fn read_record(program: &Path) -> Result<Option<PlanRecord>> {
    let path = record_path(program);
    if !path.is_file() {
        return Ok(None);
    }
    let text = swarf_io::read_input_text(&path)?;
    let record: PlanRecord = serde_json::from_str(&text)
        .map_err(|e| AppError::Message(format!("{}: {e}", path.display())))?;
    record
        .check()
        .map_err(|m| AppError::Message(format!("{}: {m}", path.display())))?;
    Ok(Some(record))
}

/// The records beside `programs` (those that have one).
///
/// # Errors
/// As [`read_record`].
pub fn read_records(programs: &[PathBuf]) -> Result<Vec<PlanRecord>> {
    let mut out = Vec::new();
    for p in programs {
        if let Some(r) = read_record(p)? {
            out.push(r);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record() -> PlanRecord {
        PlanRecord::new(
            "builtin:wave",
            Units::Mm,
            vec![ToolRecord {
                number: 1,
                cutter: "ball:d=8".into(),
                name: None,
            }],
            vec![OperationRecord {
                name: "wave".into(),
                strategy: "raster".into(),
                tool: 1,
                scallop: Some(0.15),
                tolerance: 0.01,
            }],
            "linuxcnc",
        )
    }

    #[test]
    fn records_read_back_and_refuse_other_versions() {
        let dir = std::env::temp_dir().join(format!("swarf-record-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let program = dir.join("a.cl");
        assert!(read_record(&program).unwrap().is_none());
        let r = record();
        std::fs::write(record_path(&program), serde_json::to_string(&r).unwrap()).unwrap();
        assert_eq!(read_record(&program).unwrap(), Some(r.clone()));
        assert_eq!((r.scallop(), r.tolerance()), (Some(0.15), Some(0.01)));
        let future = PlanRecord { version: 99, ..r };
        std::fs::write(
            record_path(&program),
            serde_json::to_string(&future).unwrap(),
        )
        .unwrap();
        let e = read_record(&program).unwrap_err().to_string();
        assert!(
            e.contains("a.record.json") && e.contains("version: 99"),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!(record_name("out/part.ngc"), "out/part.record.json");
    }
}
