//! Reading a typed job (or sequence) from TOML text or from a value (a Python
//! dict), with errors that name the place: a file's line and the field's path
//! (`strategy.scallop`, `operation[2]`), or the dict's path.
//!
//! serde gives the path of the value an error is about ([`serde_path_to_error`]);
//! toml the byte span of what it was reading. A strategy table is read whole before
//! its fields are ([`crate::strategy`]), so its errors name their field inside the
//! table (`scallop: ...`) and come with the table's span: the field is joined to
//! the path, and its own line found in the document's spans ([`DeTable`]).

use serde::de::DeserializeOwned;
use serde_path_to_error::Segment;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// Where an error is, and what it says.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Located {
    /// The keys and indices down to the value, a strategy's own field included.
    pub path: Vec<Key>,
    /// The message, without the place.
    pub message: String,
    /// The 1-based line, when read from text.
    pub line: Option<usize>,
}

/// A step of a path: a table key or an array index.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Key {
    /// A table's key.
    Name(String),
    /// An array's element.
    Index(usize),
}

impl Located {
    /// The error as a file's reader says it: `line N: `, the array element it is in
    /// (`operation[2]`), the strategy field (`strategy.scallop`), then the message;
    /// a field elsewhere is named by the message and the line.
    pub(crate) fn in_file(&self) -> String {
        let strategy = self
            .path
            .iter()
            .position(|k| *k == Key::Name("strategy".into()));
        let head = &self.path[..strategy.unwrap_or(self.path.len())];
        let element = head
            .iter()
            .rposition(|k| matches!(k, Key::Index(_)))
            .map(|i| dotted(&head[..=i]));
        let mut parts: Vec<String> = self.line.map(|l| format!("line {l}")).into_iter().collect();
        parts.extend(element);
        parts.extend(strategy.map(|s| dotted(&self.path[s..])));
        parts.push(self.message.clone());
        parts.join(": ")
    }

    /// The error as a dict's reader says it: the whole path, then the message.
    pub(crate) fn in_value(&self) -> String {
        if self.path.is_empty() {
            self.message.clone()
        } else {
            format!("{}: {}", dotted(&self.path), self.message)
        }
    }
}

/// `path` as a job names it: `operation[2].strategy.scallop`.
pub(crate) fn dotted(path: &[Key]) -> String {
    let mut s = String::new();
    for k in path {
        match k {
            Key::Name(n) if s.is_empty() => s += n,
            Key::Name(n) => {
                s.push('.');
                s += n;
            }
            Key::Index(i) => s += &format!("[{i}]"),
        }
    }
    s
}

/// Reads `T` from TOML `text`.
///
/// # Errors
/// Malformed TOML, or a value `T` refuses, [`Located`].
pub(crate) fn from_text<T: DeserializeOwned>(text: &str) -> Result<T, Located> {
    let de = toml::de::Deserializer::parse(text).map_err(|e| Located {
        path: Vec::new(),
        message: e.message().trim().to_string(),
        line: e.span().map(|s| swarf_geom::domain::line_of(text, s.start)),
    })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let span = e.inner().span();
        let mut located = locate(e.path(), e.inner().message());
        let doc = DeTable::parse(text).ok();
        let at = doc
            .as_ref()
            .and_then(|d| key_span(d.get_ref(), &located.path))
            .or(span.map(|s| s.start));
        located.line = at.map(|a| swarf_geom::domain::line_of(text, a));
        located
    })
}

/// Reads `T` from a TOML value (a dict turned into TOML values).
///
/// # Errors
/// A value `T` refuses, [`Located`] without a line.
pub(crate) fn from_value<T: DeserializeOwned>(value: toml::Value) -> Result<T, Located> {
    serde_path_to_error::deserialize(value).map_err(|e| locate(e.path(), e.inner().message()))
}

/// The place and message of an error at `path` saying `message` (module doc).
fn locate(path: &serde_path_to_error::Path, message: &str) -> Located {
    let mut keys: Vec<Key> = path
        .iter()
        .filter_map(|s| match s {
            Segment::Map { key } => Some(Key::Name(key.clone())),
            Segment::Seq { index } => Some(Key::Index(*index)),
            Segment::Enum { .. } | Segment::Unknown => None,
        })
        .collect();
    let mut message = message.trim().to_string();
    let in_strategy = matches!(keys.last(), Some(Key::Name(n)) if n == "strategy");
    if in_strategy
        && let Some((field, rest)) = message.split_once(": ")
        && is_field_path(field)
    {
        // Further lines name further fields of the table: placed as the first.
        let table = dotted(&keys);
        let mut lines = rest.split('\n');
        let mut placed = lines.next().unwrap_or_default().to_string();
        for line in lines {
            placed += &format!("; {table}.{line}");
        }
        keys.extend(field_keys(field));
        message = placed;
    }
    Located {
        path: keys,
        message,
        line: None,
    }
}

/// Whether `s` reads as a path of field names and indices (`scallop`, `a.b`,
/// `chain[1]`).
fn is_field_path(s: &str) -> bool {
    !s.is_empty()
        && s.split('.').all(|p| {
            !p.is_empty()
                && p.chars()
                    .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '[' | ']'))
        })
}

/// The keys of a field path (`chain[1].d`: `chain`, 1, `d`).
fn field_keys(path: &str) -> Vec<Key> {
    let mut keys = Vec::new();
    for part in path.split('.') {
        let mut pieces = part.split('[');
        if let Some(name) = pieces.next().filter(|n| !n.is_empty()) {
            keys.push(Key::Name(name.to_string()));
        }
        for index in pieces {
            if let Ok(i) = index.trim_end_matches(']').parse() {
                keys.push(Key::Index(i));
            }
        }
    }
    keys
}

/// `message`, about the top-level `key` of the document `text`, with the key's line
/// in front (`line 4: tool: ...`) when the key is there.
pub(crate) fn at_key_line(text: &str, key: &str, message: String) -> String {
    let at = DeTable::parse(text)
        .ok()
        .and_then(|d| key_span(d.get_ref(), &[Key::Name(key.to_string())]));
    match at {
        Some(a) => format!("line {}: {message}", swarf_geom::domain::line_of(text, a)),
        None => message,
    }
}

/// The byte offset of the deepest key of `path` found in `doc`.
fn key_span(doc: &DeTable<'_>, path: &[Key]) -> Option<usize> {
    let mut table = doc;
    let mut array: Option<&[Spanned<DeValue<'_>>]> = None;
    let mut found = None;
    for k in path {
        let value = match (k, array) {
            (Key::Index(i), Some(items)) => items.get(*i)?,
            (Key::Name(n), None) => {
                let (key, value) = table.iter().find(|(key, _)| key.get_ref() == n)?;
                found = Some(key.span().start);
                value
            }
            _ => return found,
        };
        array = None;
        match value.get_ref() {
            DeValue::Table(t) => table = t,
            DeValue::Array(a) => {
                array = Some(&a[..]);
                found = Some(value.span().start).or(found);
            }
            _ => return found,
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Doc {
        a: f64,
        #[serde(default)]
        op: Vec<Op>,
    }

    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Op {
        b: f64,
    }

    #[test]
    fn errors_name_their_path_and_line() {
        let e = from_text::<Doc>("a = 1\n[[op]]\nb = 2\n[[op]]\nb = \"x\"\n").unwrap_err();
        assert_eq!(dotted(&e.path), "op[1].b");
        assert_eq!(e.line, Some(5));
        let e = from_text::<Doc>("a = 1\n[[op]]\nc = 2\n").unwrap_err();
        assert_eq!(dotted(&e.path), "op[0].c");
        assert!(e.message.starts_with("unknown field `c`"), "{}", e.message);
        assert_eq!(e.line, Some(3));
        let e = from_value::<Doc>(toml::from_str("a = \"s\"").unwrap()).unwrap_err();
        assert_eq!((dotted(&e.path), e.line), ("a".to_string(), None));
    }
}
