//! Parsing a job that may name a tool of a library (module doc of [`super`]): the
//! library is read relative to the job file, the `tool` value a library key names
//! is replaced in the text by the tool's cutter spec (on its own line, so every
//! later error keeps its line), and the library's feeds fill what `[feeds]` leaves
//! out ([`crate::holder::library`], shared with sequence jobs).

use super::Job;
use crate::error::AppError;
use crate::holder::library::{default_feeds, library_key, named_tool};
use serde::Deserialize;
use std::path::Path;
use swarf_io::error::{line_of, toml_message};
use swarf_tool::library::ToolLibrary;

/// The keys of a job that concern a library tool (the rest is ignored here).
#[derive(Deserialize)]
struct LibraryKeys {
    #[serde(default)]
    tools: Option<String>,
    #[serde(default)]
    tool: Option<toml::Spanned<toml::Value>>,
    #[serde(default)]
    feeds: Option<toml::Value>,
}

impl Job {
    /// Parses and validates a job from TOML text; `source` names the file in errors,
    /// and a tool library (`tools`) is read relative to its directory.
    ///
    /// # Errors
    /// As [`Job::parse_in`].
    pub fn parse(text: &str, source: &str) -> Result<Job, AppError> {
        let dir = Path::new(source).parent().unwrap_or(Path::new(""));
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
    pub fn parse_in(text: &str, source: &str, dir: &Path) -> Result<Job, AppError> {
        let err = |message: String| AppError::Job {
            file: source.to_string(),
            message,
        };
        let keys: LibraryKeys = toml::from_str(text).map_err(|e| err(toml_message(text, &e)))?;
        let library = match &keys.tools {
            Some(file) => {
                Some(ToolLibrary::read(&dir.join(file)).map_err(|e| err(format!("tools: {e}")))?)
            }
            None => None,
        };
        let Some(tool) = keys
            .tool
            .as_ref()
            .filter(|t| library_key(Some(t.get_ref())).is_some())
        else {
            return Job::parse_plain(text, source);
        };
        let span = tool.span();
        let line = line_of(text, span.start);
        let Some(lt) = named_tool(library.as_ref(), Some(tool.get_ref()))
            .map_err(|m| err(format!("line {line}: {m}")))?
        else {
            return Job::parse_plain(text, source);
        };
        let spec = toml::Value::String(lt.assembly.cutter.to_string());
        let spliced = format!("{}{spec}{}", &text[..span.start], &text[span.end..]);
        let mut job = Job::parse_plain(&spliced, source)?;
        default_feeds(lt, keys.feeds.as_ref(), &mut job.feeds);
        job.library_tool = Some(lt.clone());
        Ok(job)
    }
}
