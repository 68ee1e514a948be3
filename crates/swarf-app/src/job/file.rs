//! A job as its file states it ([`JobFile`]), and its resolution into a [`Job`]:
//! the tool a library key names (the library read relative to the job file), and
//! the feeds the job leaves out taken from the library tool, then the defaults
//! ([`crate::holder::library`], shared with sequence jobs).

use super::{Import, Job, Output, Parent};
use crate::holder::library::named_tool;
use crate::model::FaceRef;
use crate::stock::Stock;
use crate::strategy::Strategy;
use schemars::JsonSchema;
use serde::{Deserialize, Deserializer};
use std::path::Path;
use swarf_fiveaxis::positioning::Positioning;
use swarf_tool::Cutter;
use swarf_tool::library::{LibraryTool, ToolLibrary};
use swarf_toolpath::{Feeds, LinkingSpec};

/// The tool of a job file alone, read before the rest: the strategy's domains
/// depend on it (a stepover below the diameter), so a bad tool is the error to
/// report, whatever else the file holds.
#[derive(Deserialize)]
pub(super) struct ToolFirst {
    /// As [`JobFile::tool`]: only its errors are wanted.
    #[serde(default, rename = "tool")]
    _tool: Option<ToolRef>,
}

/// A job file (module doc of [`crate::job`]).
#[derive(Debug, Clone, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JobFile {
    /// Free-text name for reports.
    #[serde(default)]
    pub name: Option<String>,
    /// Part file (`.toml` patches, `.stl`/`.obj` mesh, `.step`/`.iges`), relative to
    /// the job file, or `builtin:NAME` for a shared part embedded in swarf.
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
    #[serde(default)]
    pub tools: Option<String>,
    /// The cutter, or a library tool's T number or name.
    pub tool: ToolRef,
    /// Strategy and its parameters.
    pub strategy: Strategy,
    /// Five-axis positioning of the strategy's CC paths (none: a vertical tool).
    #[serde(default)]
    pub positioning: Option<Positioning>,
    /// Feeds and speeds (a library tool's where left out, then the defaults).
    #[serde(default)]
    pub feeds: FeedsSpec,
    /// Linking between passes.
    #[serde(default)]
    pub linking: LinkingSpec,
    /// The stock the job cuts (default: a box 1 mm above the part; a five-axis
    /// job's: the design raised by 1 mm).
    #[serde(default)]
    pub stock: Option<Stock>,
    /// Output files.
    #[serde(default)]
    pub output: Output,
    /// What a cleanup job cleans up after (`kind = "cleanup"` only).
    #[serde(default)]
    pub parent: Option<Parent>,
}

/// A job's or an operation's `tool`: a cutter (a spec with a `:`, or a table), or a
/// library tool's T number or name.
#[derive(Debug, Clone, PartialEq)]
pub enum ToolRef {
    /// A cutter.
    Cutter(Cutter),
    /// A library key: a T number or a name.
    Library(String),
}

impl<'de> Deserialize<'de> for ToolRef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let value = toml::Value::deserialize(d)?;
        match value {
            toml::Value::Integer(n) => Ok(ToolRef::Library(n.to_string())),
            toml::Value::String(s) if !s.contains(':') => Ok(ToolRef::Library(s)),
            other => Cutter::deserialize(other)
                .map(ToolRef::Cutter)
                .map_err(|e| D::Error::custom(e.message().trim())),
        }
    }
}

impl JsonSchema for ToolRef {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "ToolRef".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "description": "A cutter spec (`ball:d=8`) or table ({ shape = \"bull\", d = 10, r = 2 }), or a library tool's T number or name",
            "type": ["string", "object", "integer"]
        })
    }
}

impl ToolRef {
    /// The cutter and the library tool this names.
    ///
    /// # Errors
    /// A library key without a library, or one the library lacks (`tool: ...`).
    pub fn resolve(
        &self,
        library: Option<&ToolLibrary>,
    ) -> Result<(Cutter, Option<LibraryTool>), String> {
        match self {
            ToolRef::Cutter(c) => Ok((*c, None)),
            ToolRef::Library(key) => {
                let lt = named_tool(library, key)?;
                Ok((lt.assembly.cutter, Some(lt.clone())))
            }
        }
    }
}

/// Feeds as a job gives them: each left out is the library tool's, then the default.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct FeedsSpec {
    /// Cutting feed, mm/min (default 300).
    #[schemars(extend("unit" = "mm/min"))]
    pub feed: Option<f64>,
    /// Feed for the approach into the material, mm/min (default 100).
    #[schemars(extend("unit" = "mm/min"))]
    pub plunge: Option<f64>,
    /// Rapid traverse rate of the machine, mm/min, for the time estimate (default
    /// 5000).
    #[schemars(extend("unit" = "mm/min"))]
    pub rapid: Option<f64>,
    /// Spindle speed, rev/min, clockwise (default 1500).
    #[schemars(extend("unit" = "rev/min"))]
    pub spindle: Option<f64>,
}

impl FeedsSpec {
    /// The feeds: those given, else `tool`'s (a library tool's feed, spindle and
    /// plunge), else the defaults.
    pub fn resolve(&self, tool: Option<&LibraryTool>) -> Feeds {
        let d = Feeds::default();
        let from_tool = |f: fn(&LibraryTool) -> Option<f64>| tool.and_then(f);
        Feeds {
            feed: self.feed.or(from_tool(|t| t.feed)).unwrap_or(d.feed),
            plunge: self.plunge.or(from_tool(|t| t.plunge)).unwrap_or(d.plunge),
            rapid: self.rapid.unwrap_or(d.rapid),
            spindle: self
                .spindle
                .or(from_tool(|t| t.spindle))
                .unwrap_or(d.spindle),
        }
    }
}

/// The library a job's `tools` names, read relative to `dir`.
///
/// # Errors
/// A library that cannot be read, as `tools: ...`.
pub(crate) fn read_library(tools: Option<&str>, dir: &Path) -> Result<Option<ToolLibrary>, String> {
    tools
        .map(|file| ToolLibrary::read(&dir.join(file)).map_err(|e| format!("tools: {e}")))
        .transpose()
}

impl JobFile {
    /// The job this file states, its library read relative to `dir`, checked.
    ///
    /// # Errors
    /// The library, the tool it names, and every check of [`Job`]'s fields, as
    /// `field: message`.
    pub fn resolve(self, dir: &Path) -> Result<Job, String> {
        if let Some(stock) = &self.stock {
            stock.check()?;
        }
        let stock_given = self.stock.is_some();
        let library = read_library(self.tools.as_deref(), dir)?;
        let (tool, library_tool) = self.tool.resolve(library.as_ref())?;
        let mut job = Job {
            name: self.name,
            part: self.part,
            faces: self.faces,
            import: self.import,
            tools: self.tools,
            tool,
            feeds: self.feeds.resolve(library_tool.as_ref()),
            library_tool,
            strategy: self.strategy,
            positioning: self.positioning,
            linking: self.linking,
            stock: self.stock.unwrap_or_default(),
            material_top: None,
            reach: None,
            gate: crate::gate::Gate::default(),
            output: self.output,
            parent: self.parent,
        };
        if !stock_given && job.tilted() {
            job.stock = Stock::near_net();
        }
        job.validate()?;
        Ok(job)
    }
}
