//! The tool library: a TOML file of tools, each a cutter with its flute length,
//! shank, holder, stick-out and default feeds, found by number or name.
//!
//! ```toml
//! [[tool]]
//! number = 3                      # the T number, >= 1, unique
//! name = "ball6-long"             # unique, not all digits
//! cutter = "ball:d=6"             # a spec string or a table, as in jobs
//! flute_length = 12               # mm; sets the cutter's length
//! stick_out = 30                  # mm, tool tip to holder face
//! shank = [                       # from the top of the flutes up
//!   { d0 = 5, d1 = 6, length = 8 },   # a cone
//!   { d = 6, length = 40 },           # a cylinder
//! ]
//! holder = [                      # from the holder face up
//!   { d0 = 20, d1 = 32, length = 20 },
//!   { d = 63, length = 30 },
//! ]
//! feed = 1200                     # optional defaults: mm/min, rev/min
//! spindle = 12000
//! plunge = 300
//! ```
//!
//! The cutter's own `length` (its flute length) may be left out, or given equal to
//! `flute_length`; without `flute_length` it is the cutter's. The stick-out must lie
//! between the flute length (a tool is not held by its flutes) and the tool's
//! overall length (flutes and shank). Every error names the file, the tool (index,
//! line, name) and the field ([`ToolError::Library`]). `tools/library.toml` in the
//! repository is an example.

use crate::cutter::Cutter;
use crate::error::ToolError;
use crate::holder::{Assembly, StackSegment};
use serde::Deserialize;
use swarf_geom::domain::{self, Domain};
use toml::Spanned;

/// Lengths this close count as equal when comparing a cutter's length with
/// `flute_length`, mm.
pub const LENGTH_MATCH: f64 = 1e-9;

/// One tool of the library.
#[derive(Debug, Clone, PartialEq)]
pub struct LibraryTool {
    /// The T number.
    pub number: u32,
    /// The name.
    pub name: String,
    /// The cutter with its flutes, shank, holder and stick-out.
    pub assembly: Assembly,
    /// Default cutting feed, mm/min.
    pub feed: Option<f64>,
    /// Default spindle speed, rev/min.
    pub spindle: Option<f64>,
    /// Default plunge feed, mm/min.
    pub plunge: Option<f64>,
}

/// A tool library read from TOML ([`crate::library`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ToolLibrary {
    source: String,
    tools: Vec<LibraryTool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLibrary {
    #[serde(default)]
    tool: Vec<Spanned<RawTool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTool {
    number: Option<u32>,
    name: Option<String>,
    cutter: Option<Cutter>,
    flute_length: Option<f64>,
    stick_out: Option<f64>,
    #[serde(default)]
    shank: Vec<RawSegment>,
    #[serde(default)]
    holder: Vec<RawSegment>,
    feed: Option<f64>,
    spindle: Option<f64>,
    plunge: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSegment {
    d: Option<f64>,
    d0: Option<f64>,
    d1: Option<f64>,
    length: Option<f64>,
}

/// Where an entry is, for messages: `line 12: tool[2] "ball6"`.
struct Place<'a> {
    file: &'a str,
    line: usize,
    index: usize,
    name: Option<&'a str>,
}

impl Place<'_> {
    fn err(&self, field: &str, message: impl Into<String>) -> ToolError {
        let name = self.name.map(|n| format!(" \"{n}\"")).unwrap_or_default();
        ToolError::Library {
            file: self.file.to_string(),
            place: format!("line {}: tool[{}]{name}: {field}", self.line, self.index),
            message: message.into(),
        }
    }

    fn check(&self, field: &str, value: f64, domain: Domain) -> Result<f64, ToolError> {
        domain.check(value).map_err(|m| self.err(field, m))
    }

    fn required<T>(&self, field: &str, value: Option<T>, what: &str) -> Result<T, ToolError> {
        value.ok_or_else(|| self.err(field, format!("missing (expected {what})")))
    }
}

impl RawSegment {
    fn build(&self, place: &Place, field: &str) -> Result<StackSegment, ToolError> {
        let dia = |k: &str, v: f64| place.check(&format!("{field}.{k}"), v, domain::TOOL_DIAMETER);
        let length = place.required(
            &format!("{field}.length"),
            self.length,
            "the segment's height, mm",
        )?;
        let length = place.check(&format!("{field}.length"), length, domain::TOOL_LENGTH)?;
        let seg = match (self.d, self.d0, self.d1) {
            (Some(d), None, None) => StackSegment::Cylinder {
                d: dia("d", d)?,
                length,
            },
            (None, Some(d0), Some(d1)) => StackSegment::Cone {
                d0: dia("d0", d0)?,
                d1: dia("d1", d1)?,
                length,
            },
            _ => {
                return Err(place.err(
                    field,
                    "expected `{ d, length }` (a cylinder) or `{ d0, d1, length }` (a cone)",
                ));
            }
        };
        seg.as_cutter()
            .map_err(|e| place.err(field, e.to_string()))?;
        Ok(seg)
    }
}

impl RawTool {
    fn build(self, place: &Place) -> Result<LibraryTool, ToolError> {
        let number = place.required("number", self.number, "the T number, >= 1")?;
        if number == 0 {
            return Err(place.err("number", "must be >= 1 (T0 is no tool), got 0"));
        }
        let name = place.required("name", self.name, "a unique name")?;
        if name.trim().is_empty() || name.trim().parse::<u32>().is_ok() {
            return Err(place.err(
                "name",
                format!("expected a name that is not empty and not a number, got \"{name}\""),
            ));
        }
        let cutter = place.required("cutter", self.cutter, "a spec such as \"ball:d=6\"")?;
        let cutter = flute_length(cutter, self.flute_length, place)?;
        let segments = |list: &[RawSegment], field: &str| {
            if list.is_empty() {
                return Err(place.err(field, "expected at least one `{ d, length }` segment"));
            }
            list.iter()
                .enumerate()
                .map(|(k, s)| s.build(place, &format!("{field}[{k}]")))
                .collect::<Result<Vec<_>, _>>()
        };
        let shank = segments(&self.shank, "shank")?;
        let holder = segments(&self.holder, "holder")?;
        let stick_out =
            place.required("stick_out", self.stick_out, "mm from tip to holder face")?;
        let stick_out = place.check("stick_out", stick_out, domain::TOOL_LENGTH)?;
        let assembly = Assembly {
            cutter,
            shank,
            holder,
            stick_out,
        };
        let (lo, hi) = (cutter.length(), assembly.tool_length());
        if !(lo..=hi).contains(&stick_out) {
            return Err(place.err(
                "stick_out",
                format!(
                    "expected between the flute length {lo} and the tool's length {hi} \
                     (flutes and shank), got {stick_out}"
                ),
            ));
        }
        let rate = |f: &str, v: Option<f64>| v.map(|v| place.check(f, v, domain::RATE)).transpose();
        Ok(LibraryTool {
            number,
            name,
            assembly,
            feed: rate("feed", self.feed)?,
            spindle: rate("spindle", self.spindle)?,
            plunge: rate("plunge", self.plunge)?,
        })
    }
}

/// The cutter with its length set to `flute_length` (module doc).
fn flute_length(cutter: Cutter, given: Option<f64>, place: &Place) -> Result<Cutter, ToolError> {
    let Some(fl) = given else {
        return Ok(cutter);
    };
    let fl = place.check("flute_length", fl, domain::TOOL_LENGTH)?;
    let default = cutter
        .with_length(None)
        .map_err(|e| place.err("cutter", e.to_string()))?;
    let own = cutter.length();
    if (own - default.length()).abs() > LENGTH_MATCH && (own - fl).abs() > LENGTH_MATCH {
        return Err(place.err(
            "flute_length",
            format!("{fl} disagrees with the cutter's own length {own}: give one, or both equal"),
        ));
    }
    cutter
        .with_length(Some(fl))
        .map_err(|e| place.err("flute_length", e.to_string()))
}

impl ToolLibrary {
    /// Parses and validates a library from TOML `text`; `source` names the file in
    /// errors.
    ///
    /// # Errors
    /// [`ToolError::Library`] naming the file, line, tool and field: malformed TOML,
    /// unknown keys, missing or out-of-range fields, bad segments, duplicate numbers
    /// or names.
    ///
    /// # Example
    /// ```
    /// let lib = swarf_tool::library::ToolLibrary::parse(
    ///     "[[tool]]\nnumber = 1\nname = \"f6\"\ncutter = \"flat:d=6\"\nflute_length = 15\n\
    ///      stick_out = 25\nshank = [{ d = 6, length = 45 }]\nholder = [{ d = 25, length = 40 }]\n",
    ///     "tools.toml",
    /// )
    /// .unwrap();
    /// assert_eq!(lib.get("1").unwrap().name, "f6");
    /// assert!(lib.get("T9").is_err());
    /// ```
    pub fn parse(text: &str, source: &str) -> Result<ToolLibrary, ToolError> {
        let raw: RawLibrary = toml::from_str(text).map_err(|e| ToolError::Library {
            file: source.to_string(),
            place: "TOML".into(),
            message: swarf_geom::domain::at_line(text, e.span().map(|s| s.start), e.message()),
        })?;
        let mut tools: Vec<LibraryTool> = Vec::with_capacity(raw.tool.len());
        for (index, spanned) in raw.tool.into_iter().enumerate() {
            let rest = text.get(spanned.span().start..).unwrap_or_default();
            let start = text.len() - rest.trim_start().len();
            let line = swarf_geom::domain::line_of(text, start);
            let entry = spanned.into_inner();
            let name = entry.name.clone();
            let place = Place {
                file: source,
                line,
                index,
                name: name.as_deref(),
            };
            let tool = entry.build(&place)?;
            if let Some(o) = tools.iter().find(|o| o.number == tool.number) {
                let m = format!("{} is already the number of \"{}\"", tool.number, o.name);
                return Err(place.err("number", m));
            }
            if tools.iter().any(|o| o.name == tool.name) {
                return Err(place.err("name", "another tool already has this name"));
            }
            tools.push(tool);
        }
        Ok(ToolLibrary {
            source: source.to_string(),
            tools,
        })
    }

    /// Reads and parses the library file at `path`.
    ///
    /// # Errors
    /// [`ToolError::Library`] when the file cannot be read, and as
    /// [`ToolLibrary::parse`].
    pub fn read(path: &std::path::Path) -> Result<ToolLibrary, ToolError> {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| ToolError::Library {
            file: file.clone(),
            place: "reading".into(),
            message: e.to_string(),
        })?;
        ToolLibrary::parse(&text, &file)
    }

    /// The tools, in file order.
    pub fn tools(&self) -> &[LibraryTool] {
        &self.tools
    }

    /// The tool with T number or name `key` (a key that parses as a number is a
    /// number; names are never all digits).
    ///
    /// # Errors
    /// [`ToolError::UnknownTool`] listing the tools the library has.
    pub fn get(&self, key: &str) -> Result<&LibraryTool, ToolError> {
        let key = key.trim();
        let found = match key.parse::<u32>() {
            Ok(n) => self.tools.iter().find(|t| t.number == n),
            Err(_) => self.tools.iter().find(|t| t.name == key),
        };
        found.ok_or_else(|| ToolError::UnknownTool {
            file: self.source.clone(),
            wanted: key.to_string(),
            known: if self.tools.is_empty() {
                "no tools".into()
            } else {
                self.tools
                    .iter()
                    .map(|t| format!("{} \"{}\"", t.number, t.name))
                    .collect::<Vec<_>>()
                    .join(", ")
            },
        })
    }
}

#[cfg(test)]
mod tests;
