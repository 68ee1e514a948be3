//! Posts as data: a post description file (TOML) says how a control wants its
//! program written, and the one block writer ([`crate::block::BlockWriter`]) writes
//! every post from it. Five posts are built in (`crates/swarf-nc/posts/*.toml`):
//! `linuxcnc`, `fanuc`, `mach3` (Mach3 and Mach4), `grbl` and `heidenhain`
//! (conversational); a user post is a file of the same form.
//!
//! A post holds only what differs between controls, as literal words and short
//! templates with named placeholders (`{number}`, `{units}`, `{feed_mode}`, `{tool}`,
//! `{speed}`), not a template language:
//!
//! - `name`, `reader` (the swarf reader of its programs: `linuxcnc`, `fanuc` or
//!   `heidenhain`), `inverse_time` (G93 available), `rotary_axes` (A/B/C available);
//! - `[program]`: `header` and `footer` lines (not numbered: `%`, `O{number}`),
//!   `begin` and `end` blocks (numbered: `BEGIN PGM {number} {units}`, `M5`, `M30`),
//!   `number_digits` (zero padding of `{number}`) and `number_range` (checked when a
//!   line uses `{number}`);
//! - `[comment]`: `open`, `close`, `upper_case`;
//! - `[numbers]` (optional): block numbers `prefix` (`N`, or empty for Heidenhain),
//!   `start`, `step`;
//! - `[words]`: decimals of lengths in mm and in inches, of angles (degrees), of feeds
//!   and of inverse-time feeds; `plus_sign` (`X+10`); `trailing_point` (`X10.`, for
//!   controls that read `X10` as ten increments);
//! - `[motion]`: the `rapid` and `linear` words, `modal` (written only when the motion
//!   changes), `rapid_suffix` (Heidenhain's `FMAX`, which holds for its block only);
//! - `[modal]`: the safe modal `line`, the words of the units (`mm`, `inch`) and feed
//!   modes (`per_minute`, `inverse_time`);
//! - `[tool]`: the `change` blocks (none: the control has no tool change, and a
//!   program of more than one tool is refused), the `length_offset` blocks written
//!   after every change (none where the change sets the length, as Heidenhain's
//!   `TOOL CALL` does; five-axis programs on head machines carry the length in their
//!   kinematics instead), `spindle_on`;
//! - `[arc]` (optional; a post without it never gets arcs): the `cw` and `ccw`
//!   words (`G2`, `G3`; Heidenhain `C`), the `center` form: `"ij"` (incremental
//!   `I J` from the start), `"r"` (an `R` word: `max_sweep` must stay below 180) or
//!   `"cc"` (a `center_block` word, `CC X.. Y..`, then the arc block), the
//!   `cw_suffix` and `ccw_suffix` words (Heidenhain `DR-`, `DR+`), `helical` (Z may
//!   change along an arc), `max_sweep` (degrees per block, below 360) and `setup`
//!   blocks written after the safe modal line in programs with arcs (`G91.1`).
//!
//! A program the post cannot express (inverse-time feed or rotary axes where it has
//! none) is refused before anything is written ([`Post::check`]).

use crate::block::FeedMode;
use crate::error::NcError;
use crate::number::Units;
use serde::Deserialize;
use std::path::Path;
use swarf_io::Source;

/// The built-in posts, by name: the text of `crates/swarf-nc/posts/NAME.toml`.
pub const BUILTIN_POSTS: [(&str, &str); 5] = [
    ("linuxcnc", include_str!("../posts/linuxcnc.toml")),
    ("fanuc", include_str!("../posts/fanuc.toml")),
    ("mach3", include_str!("../posts/mach3.toml")),
    ("grbl", include_str!("../posts/grbl.toml")),
    ("heidenhain", include_str!("../posts/heidenhain.toml")),
];

/// The reader that reads a post's programs back.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Language {
    /// RS274/NGC as LinuxCNC reads it (grbl and Mach3 write subsets of it).
    #[default]
    Linuxcnc,
    /// Fanuc macro B.
    Fanuc,
    /// Heidenhain conversational ([`crate::read::heidenhain`]).
    Heidenhain,
}

impl Language {
    /// The language called `name` (`linuxcnc`, `fanuc`, `heidenhain`).
    pub fn named(name: &str) -> Option<Language> {
        match name {
            "linuxcnc" => Some(Language::Linuxcnc),
            "fanuc" => Some(Language::Fanuc),
            "heidenhain" => Some(Language::Heidenhain),
            _ => None,
        }
    }
}

/// Program frame (module doc).
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub(crate) struct Frame {
    pub(crate) header: Vec<String>,
    pub(crate) begin: Vec<String>,
    pub(crate) end: Vec<String>,
    pub(crate) footer: Vec<String>,
    pub(crate) number_digits: usize,
    pub(crate) number_range: Option<[u32; 2]>,
}

/// Comment style (module doc).
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub(crate) struct Comment {
    pub(crate) open: String,
    pub(crate) close: String,
    pub(crate) upper_case: bool,
}

/// Block numbers (module doc).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Numbers {
    pub(crate) prefix: String,
    pub(crate) start: u64,
    pub(crate) step: u64,
}

/// Word format (module doc).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub(crate) struct Words {
    pub(crate) mm_decimals: usize,
    pub(crate) inch_decimals: usize,
    pub(crate) angle_decimals: usize,
    pub(crate) feed_decimals: usize,
    pub(crate) inverse_time_decimals: usize,
    pub(crate) plus_sign: bool,
    pub(crate) trailing_point: bool,
}

impl Default for Words {
    fn default() -> Self {
        Words {
            mm_decimals: 4,
            inch_decimals: 5,
            angle_decimals: 4,
            feed_decimals: 3,
            inverse_time_decimals: 4,
            plus_sign: false,
            trailing_point: true,
        }
    }
}

/// Motion words (module doc).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct MotionWords {
    pub(crate) rapid: String,
    pub(crate) linear: String,
    #[serde(default = "yes")]
    pub(crate) modal: bool,
    #[serde(default)]
    pub(crate) rapid_suffix: String,
}

/// Modal words (module doc).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Modal {
    #[serde(default)]
    pub(crate) line: String,
    pub(crate) mm: String,
    pub(crate) inch: String,
    #[serde(default)]
    pub(crate) per_minute: String,
    #[serde(default)]
    pub(crate) inverse_time: String,
}

/// Tool change and spindle (module doc).
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub(crate) struct ToolWords {
    pub(crate) change: Vec<String>,
    pub(crate) length_offset: Vec<String>,
    pub(crate) spindle_on: Vec<String>,
}

/// How a post writes an arc's centre (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum CenterForm {
    /// Incremental `I J` from the start.
    Ij,
    /// An `R` word (the radius; at most half a turn).
    R,
    /// A centre block (`CC X.. Y..`) before the arc block.
    Cc,
}

/// Arc words (module doc).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ArcWords {
    pub(crate) cw: String,
    pub(crate) ccw: String,
    pub(crate) center: CenterForm,
    #[serde(default)]
    pub(crate) center_block: String,
    #[serde(default)]
    pub(crate) cw_suffix: String,
    #[serde(default)]
    pub(crate) ccw_suffix: String,
    #[serde(default = "yes")]
    pub(crate) helical: bool,
    #[serde(default = "half_turn")]
    pub(crate) max_sweep: f64,
    #[serde(default)]
    pub(crate) setup: Vec<String>,
}

fn half_turn() -> f64 {
    180.0
}

fn yes() -> bool {
    true
}

/// A validated post description (module doc).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Post {
    name: String,
    reader: Language,
    inverse_time: bool,
    rotary_axes: bool,
    #[serde(default)]
    pub(crate) program: Frame,
    #[serde(default)]
    pub(crate) comment: Comment,
    #[serde(default)]
    pub(crate) numbers: Option<Numbers>,
    #[serde(default)]
    pub(crate) words: Words,
    pub(crate) motion: MotionWords,
    pub(crate) modal: Modal,
    #[serde(default)]
    pub(crate) tool: ToolWords,
    #[serde(default)]
    pub(crate) arc: Option<ArcWords>,
}

impl Post {
    /// Parses and validates a post description; `source` names it in errors.
    ///
    /// # Errors
    /// [`NcError::Post`] naming the file, the line (TOML errors) and the field: an
    /// unknown key, a missing field, a placeholder the field does not take, more
    /// than 12 decimals, a block number step of 0.
    pub fn parse(text: &str, source: &str) -> Result<Post, NcError> {
        let err = |field: &str, message: String| NcError::Post {
            file: source.to_string(),
            field: field.to_string(),
            message,
        };
        let post: Post = toml::from_str(text)
            .map_err(|e| err("toml", swarf_io::error::toml_message(text, &e)))?;
        post.validate().map_err(|(f, m)| err(&f, m))?;
        Ok(post)
    }

    /// The built-in post `name` (one of [`BUILTIN_POSTS`]).
    ///
    /// # Errors
    /// [`NcError::Post`] for an unknown name, listing the built-in names.
    pub fn builtin(name: &str) -> Result<Post, NcError> {
        let Some((_, text)) = BUILTIN_POSTS.iter().find(|(n, _)| *n == name) else {
            let names: Vec<_> = BUILTIN_POSTS.iter().map(|(n, _)| *n).collect();
            return Err(NcError::Post {
                file: name.to_string(),
                field: "post".into(),
                message: format!(
                    "no built-in post of that name (built in: {})",
                    names.join(", ")
                ),
            });
        };
        Post::parse(text, &format!("{name}.toml (built in)"))
    }

    /// The post `spec` names: a built-in name (`builtin:NAME`, or the bare name when
    /// it does not end in `.toml`), or a post file (`.toml`), relative to `dir` unless
    /// absolute.
    ///
    /// # Errors
    /// As [`Post::builtin`] and [`Post::parse`]; a file that cannot be read.
    pub fn load(spec: &str, dir: &Path) -> Result<Post, NcError> {
        let path = match Source::parse(spec, dir) {
            Source::Builtin(name) => return Post::builtin(name),
            Source::File(_) if !spec.ends_with(".toml") => return Post::builtin(spec),
            Source::File(path) => path,
        };
        let text = swarf_io::read_input_text(&path).map_err(|e| NcError::Post {
            file: path.display().to_string(),
            field: "post".into(),
            message: format!("cannot read the post file: {e}"),
        })?;
        Post::parse(&text, &path.display().to_string())
    }

    /// The built-in LinuxCNC post, the default of every writer.
    pub fn linuxcnc() -> Post {
        match Post::builtin("linuxcnc") {
            Ok(p) => p,
            Err(e) => unreachable!("the built-in LinuxCNC post parses (a unit test checks): {e}"),
        }
    }

    /// The post's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The reader of the post's programs.
    pub fn reader(&self) -> Language {
        self.reader
    }

    /// Whether the post writes rotary axis words.
    pub fn has_rotary_axes(&self) -> bool {
        self.rotary_axes
    }

    /// Whether the post writes inverse-time feeds (G93).
    pub fn has_inverse_time(&self) -> bool {
        self.inverse_time
    }

    /// The arcs the post writes, for fitting within `tolerance` (mm): `None` when
    /// the post has no `[arc]` table.
    pub fn arc_fit(&self, tolerance: f64) -> Option<crate::arc_fit::ArcFitOptions> {
        self.arc.as_ref().map(|a| crate::arc_fit::ArcFitOptions {
            tolerance,
            helical: a.helical,
            max_sweep: a.max_sweep.to_radians(),
        })
    }

    /// Checks that the post can express a program: program number `number`, feeds
    /// `feed_mode`, rotary axes when `rotary`; `operation` names the program for the
    /// error (e.g. "five-axis program").
    ///
    /// # Errors
    /// [`NcError::Unsupported`] naming the post, the field and the operation;
    /// [`NcError::InvalidOption`] for a program number outside `number_range`.
    pub fn check(
        &self,
        operation: &str,
        number: u32,
        feed_mode: FeedMode,
        rotary: bool,
    ) -> Result<(), NcError> {
        let unsupported = |field: &'static str, what: &str| NcError::Unsupported {
            post: self.name.clone(),
            field,
            message: format!("{operation}: {what}"),
        };
        if rotary && !self.rotary_axes {
            return Err(unsupported(
                "rotary_axes",
                "the control has no rotary axes (A/B/C)",
            ));
        }
        if feed_mode == FeedMode::InverseTime && !self.inverse_time {
            return Err(unsupported(
                "inverse_time",
                "the control has no inverse-time feed (G93); use feed_mode = \"units-per-minute\"",
            ));
        }
        let frame = &self.program;
        let numbered = [&frame.header, &frame.begin, &frame.end, &frame.footer]
            .iter()
            .any(|l| l.iter().any(|s| s.contains("{number}")));
        if let (true, Some([lo, hi])) = (numbered, frame.number_range)
            && !(lo..=hi).contains(&number)
        {
            return Err(NcError::InvalidOption {
                field: "program_number",
                message: format!("post {}: expected {lo}..={hi}, found {number}", self.name),
            });
        }
        Ok(())
    }

    /// Refuses a program of more than one tool (`tools`: the T number of each
    /// section, in order) on a post without tool change blocks.
    ///
    /// # Errors
    /// [`NcError::Unsupported`] naming the post, `tool.change` and the tools.
    pub fn check_tools(
        &self,
        operation: &str,
        tools: impl IntoIterator<Item = u32>,
    ) -> Result<(), NcError> {
        let mut distinct: Vec<u32> = Vec::new();
        for t in tools {
            if !distinct.contains(&t) {
                distinct.push(t);
            }
        }
        if distinct.len() < 2 || !self.tool.change.is_empty() {
            return Ok(());
        }
        let list: Vec<String> = distinct.iter().map(|t| format!("T{t}")).collect();
        Err(NcError::Unsupported {
            post: self.name.clone(),
            field: "tool.change",
            message: format!(
                "{operation} with {} tools ({}): the control has no tool change; write one \
                 program per tool",
                distinct.len(),
                list.join(", ")
            ),
        })
    }

    /// The units word of `units`.
    pub(crate) fn units_word(&self, units: Units) -> &str {
        match units {
            Units::Mm => &self.modal.mm,
            Units::Inch => &self.modal.inch,
        }
    }

    /// Decimals of lengths written in `units`.
    pub(crate) fn length_decimals(&self, units: Units) -> usize {
        match units {
            Units::Mm => self.words.mm_decimals,
            Units::Inch => self.words.inch_decimals,
        }
    }

    fn validate(&self) -> Result<(), (String, String)> {
        let frame = ["{number}", "{units}"];
        let tool = ["{tool}", "{speed}"];
        let lists: [(&str, &[String], &[&str]); 8] = [
            ("program.header", &self.program.header, &frame),
            ("program.begin", &self.program.begin, &frame),
            ("program.end", &self.program.end, &frame),
            ("program.footer", &self.program.footer, &frame),
            ("tool.change", &self.tool.change, &tool),
            ("tool.length_offset", &self.tool.length_offset, &tool),
            ("tool.spindle_on", &self.tool.spindle_on, &["{speed}"]),
            (
                "modal.line",
                std::slice::from_ref(&self.modal.line),
                &["{units}", "{feed_mode}"],
            ),
        ];
        for (field, lines, allowed) in lists {
            for (k, line) in lines.iter().enumerate() {
                check_template(line, allowed).map_err(|m| (format!("{field}[{k}]"), m))?;
            }
        }
        let w = &self.words;
        for (field, d) in [
            ("words.mm_decimals", w.mm_decimals),
            ("words.inch_decimals", w.inch_decimals),
            ("words.angle_decimals", w.angle_decimals),
            ("words.feed_decimals", w.feed_decimals),
            ("words.inverse_time_decimals", w.inverse_time_decimals),
        ] {
            if d > 12 {
                return Err((field.into(), format!("expected 0..=12 decimals, found {d}")));
            }
        }
        if let Some(a) = &self.arc {
            validate_arc(a)?;
        }
        if self.numbers.as_ref().is_some_and(|n| n.step == 0) {
            return Err(("numbers.step".into(), "expected a step > 0".into()));
        }
        if self.motion.rapid.is_empty() || self.motion.linear.is_empty() {
            return Err(("motion".into(), "expected rapid and linear words".into()));
        }
        if self.inverse_time && self.modal.inverse_time.is_empty() {
            return Err((
                "modal.inverse_time".into(),
                "inverse_time = true needs the word that selects it (G93)".into(),
            ));
        }
        if !self.modal.line.is_empty() && self.modal.per_minute.is_empty() {
            return Err((
                "modal.per_minute".into(),
                "a modal line needs the word of feeds per minute (G94)".into(),
            ));
        }
        Ok(())
    }
}

fn validate_arc(a: &ArcWords) -> Result<(), (String, String)> {
    if a.cw.is_empty() || a.ccw.is_empty() {
        return Err(("arc".into(), "expected cw and ccw words".into()));
    }
    let most = if a.center == CenterForm::R {
        180.0
    } else {
        360.0
    };
    if !(a.max_sweep >= 1.0 && a.max_sweep < most) {
        return Err((
            "arc.max_sweep".into(),
            format!(
                "expected 1 <= degrees < {most} (R arcs are ambiguous from a half turn), found {}",
                a.max_sweep
            ),
        ));
    }
    if (a.center == CenterForm::Cc) == a.center_block.is_empty() {
        return Err((
            "arc.center_block".into(),
            "expected a centre block word (CC) exactly when center = \"cc\"".into(),
        ));
    }
    for (k, line) in a.setup.iter().enumerate() {
        check_template(line, &[]).map_err(|m| (format!("arc.setup[{k}]"), m))?;
    }
    Ok(())
}

/// Checks that `template` uses only the placeholders `allowed`, and has no stray
/// brace.
fn check_template(template: &str, allowed: &[&str]) -> Result<(), String> {
    let mut rest = template;
    while let Some(open) = rest.find(['{', '}']) {
        let tail = &rest[open..];
        let Some(close) = tail.find('}').filter(|_| tail.starts_with('{')) else {
            return Err(format!("stray brace in {template:?}"));
        };
        let name = &tail[..=close];
        if !allowed.contains(&name) {
            return Err(format!(
                "unknown placeholder {name} (this field takes {})",
                allowed.join(", ")
            ));
        }
        rest = &tail[close + 1..];
    }
    Ok(())
}

/// `template` with each placeholder of `values` (`("{tool}", "3")`) replaced.
pub(crate) fn render(template: &str, values: &[(&str, &str)]) -> String {
    values
        .iter()
        .fold(template.to_string(), |s, (k, v)| s.replace(k, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_posts_parse() {
        for (name, _) in BUILTIN_POSTS {
            let p = Post::builtin(name).unwrap();
            assert_eq!(p.name(), name);
            let arcs = p.arc_fit(0.01).unwrap();
            assert_eq!(arcs.helical, name != "heidenhain", "{name}");
        }
        let e = Post::builtin("sinumerik").unwrap_err().to_string();
        assert!(e.contains("built in: linuxcnc, fanuc"), "{e}");
    }

    #[test]
    fn bad_posts_name_the_field() {
        let text = BUILTIN_POSTS[0].1.replace("T{tool} M6", "T{tol} M6");
        let e = Post::parse(&text, "my.toml").unwrap_err().to_string();
        assert!(
            e.starts_with("my.toml: tool.change[0]: unknown placeholder {tol}"),
            "{e}"
        );
        let text = BUILTIN_POSTS[0]
            .1
            .replace("mm_decimals = 4", "mm_decimals = 40");
        let e = Post::parse(&text, "my.toml").unwrap_err().to_string();
        assert!(e.starts_with("my.toml: words.mm_decimals"), "{e}");
        let text = BUILTIN_POSTS[0]
            .1
            .replace("[motion]", "[motion]\nspeed = 3");
        let e = Post::parse(&text, "my.toml").unwrap_err().to_string();
        assert!(e.contains("line ") && e.contains("speed"), "{e}");
        let text = format!(
            "{}\n[arc]\ncw = \"G2\"\nccw = \"G3\"\ncenter = \"r\"\n",
            BUILTIN_POSTS[0].1.split("[arc]").next().unwrap()
        );
        let e = Post::parse(&text, "my.toml").unwrap_err().to_string();
        assert!(
            e.starts_with("my.toml: arc.max_sweep: expected 1 <= degrees < 180"),
            "{e}"
        );
        let text = text.replace("\"r\"", "\"cc\"");
        let e = Post::parse(&text, "my.toml").unwrap_err().to_string();
        assert!(e.starts_with("my.toml: arc.center_block"), "{e}");
        assert!(check_template("G{x", &["{x}"]).is_err());
        assert!(check_template("a}b", &["{x}"]).is_err());
    }
}
