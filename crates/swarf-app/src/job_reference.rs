//! The job file reference (`docs/jobs.md`), written from the job schema: the typed
//! job ([`crate::job::JobFile`]), the strategies' parameter structs
//! ([`crate::strategy::Strategy`]) and the sequence file
//! ([`crate::sequence::SequenceFile`]), their doc comments, defaults, units and
//! domains as `schemars` reads them. A test holds the committed page to this
//! output.

use crate::job::JobFile;
use crate::sequence::SequenceFile;
use crate::strategy::Strategy;
use serde_json::Value;

/// The reference page, Markdown.
pub fn job_reference() -> String {
    let job = schema_of::<JobFile>();
    let seq = schema_of::<SequenceFile>();
    let mut page = String::from(
        "# Job files\n\n\
         Generated from swarf's job schema (`cargo test -p swarf-app job_reference` checks \
         it; `SWARF_WRITE_DOCS=1` with the same command rewrites it). Lengths are mm, \
         angles degrees, feeds mm/min; every path is relative to the job file.\n\n\
         A job names its part, its tool and its strategy; a sequence job lists \
         operations on one in-process stock. `swarf plan JOB.toml` runs either.\n\n",
    );
    page += "## The job\n\n";
    page += &table(&job, &job);
    for (name, title) in [
        ("feeds", "`[feeds]`"),
        ("linking", "`[linking]`"),
        ("output", "`[output]`"),
        ("import", "`[import]`"),
        ("parent", "`[parent]` (cleanup jobs)"),
    ] {
        page += &format!("\n### {title}\n\n");
        page += &table(resolve(&job, &job["properties"][name]), &job);
    }
    page += "\n### `positioning` (five-axis jobs)\n\n";
    page += &variants(
        resolve(&job, &job["properties"]["positioning"]),
        &job,
        "method",
    );
    page += "\n## Strategies (`[strategy]`, by `kind`)\n\n";
    page += &format!(
        "Kinds: {}. Each kind takes only its own fields; a field of another kind is \
         refused, naming the kinds that take it.\n\n",
        Strategy::KINDS
            .iter()
            .map(|k| format!("`{k}`"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    page += &variants(Strategy::schema(), Strategy::schema(), "kind");
    page += "\n## Sequence jobs\n\n";
    page += &table(&seq, &seq);
    for (name, title) in [
        ("stock", "`[stock]`"),
        ("operation", "`[[operation]]`"),
        ("output", "`[output]`"),
    ] {
        page += &format!("\n### {title}\n\n");
        let p = &seq["properties"][name];
        let p = if p["type"] == "array" { &p["items"] } else { p };
        page += &table(resolve(&seq, p), &seq);
    }
    page
}

/// The JSON schema of `T`.
fn schema_of<T: schemars::JsonSchema>() -> Value {
    let schema = schemars::generate::SchemaSettings::draft2020_12()
        .into_generator()
        .into_root_schema_for::<T>();
    serde_json::to_value(schema).unwrap_or_default()
}

/// `s` with a `$ref` (alone or in an `anyOf` with null) followed into `root`'s
/// definitions.
fn resolve<'a>(root: &'a Value, s: &'a Value) -> &'a Value {
    if let Some(r) = s["$ref"].as_str() {
        let name = r.rsplit('/').next().unwrap_or_default();
        return &root["$defs"][name];
    }
    if let Some(any) = s["anyOf"].as_array() {
        return any
            .iter()
            .find(|v| v["type"] != "null")
            .map_or(s, |v| resolve(root, v));
    }
    s
}

/// The `oneOf` variants of `s`, told apart by `tag`: a section each with its
/// description and its fields.
fn variants(s: &Value, root: &Value, tag: &str) -> String {
    let mut out = String::new();
    for v in s["oneOf"].as_array().into_iter().flatten() {
        let name = v["properties"][tag]["const"].as_str().unwrap_or("?");
        out += &format!("### `{tag} = \"{name}\"`\n\n");
        if let Some(d) = v["description"].as_str() {
            out += &format!("{}\n\n", one_line(d));
        }
        out += &table(v, root);
        out.push('\n');
    }
    out
}

/// The fields of the object schema `s` as a Markdown table.
fn table(s: &Value, root: &Value) -> String {
    let mut out = String::from(
        "| field | type | unit | default | domain | what |\n|---|---|---|---|---|---|\n",
    );
    let required: Vec<&str> = s["required"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(Value::as_str)
        .collect();
    let mut fields: Vec<(&String, &Value)> =
        s["properties"].as_object().into_iter().flatten().collect();
    fields.sort_by_key(|(name, _)| name.as_str());
    for (name, p) in fields {
        if p.get("const").is_some() {
            continue;
        }
        let default = match (&p["default"], required.contains(&name.as_str())) {
            (Value::Null, true) => "required".to_string(),
            (Value::Null, false) => "none".to_string(),
            (Value::Object(_), _) => "see below".to_string(),
            (d, _) => format!("`{d}`"),
        };
        out += &format!(
            "| `{name}` | {} | {} | {default} | {} | {} |\n",
            type_of(p, root),
            p["unit"].as_str().unwrap_or(""),
            p["domain"].as_str().unwrap_or(""),
            one_line(description(p, root)).replace('|', "\\|")
        );
    }
    out
}

/// The field's description, or its type's.
fn description<'a>(p: &'a Value, root: &'a Value) -> &'a str {
    p["description"]
        .as_str()
        .or_else(|| resolve(root, p)["description"].as_str())
        .unwrap_or("")
}

/// A field's type as a reader wants it: a number, text, a choice of names, a list.
fn type_of(p: &Value, root: &Value) -> String {
    let s = resolve(root, p);
    if let Some(choices) = s["oneOf"].as_array().or(s["enum"].as_array()) {
        let names: Vec<String> = choices
            .iter()
            .filter_map(|c| c["const"].as_str().or(c.as_str()))
            .map(|c| format!("`\"{c}\"`"))
            .collect();
        if !names.is_empty() {
            return names.join(", ");
        }
    }
    let base = |t: &Value| match t.as_str() {
        Some("number") => "number".to_string(),
        Some("integer") => "integer".to_string(),
        Some("string") => "text".to_string(),
        Some("boolean") => "true/false".to_string(),
        Some("object") => "table".to_string(),
        Some("array") => "list".to_string(),
        _ => String::new(),
    };
    match &s["type"] {
        Value::Array(ts) => ts
            .iter()
            .filter(|t| *t != "null")
            .map(base)
            .collect::<Vec<_>>()
            .join(" or "),
        Value::Null => "see below".into(),
        t => base(t),
    }
}

/// `text` with its line breaks and runs of spaces made single spaces, and its
/// rustdoc links (``[`name`]``) as plain code.
fn one_line(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace("[`", "`")
        .replace("`]", "`")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed page is this output: rewrite it with `SWARF_WRITE_DOCS=1`.
    #[test]
    fn job_reference_is_current() {
        let page = job_reference();
        for kind in Strategy::KINDS {
            assert!(page.contains(&format!("`kind = \"{kind}\"`")), "{kind}");
            for f in crate::strategy::fields_of(kind) {
                assert!(page.contains(&format!("| `{f}` |")), "{kind}.{f}");
            }
        }
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/jobs.md");
        if std::env::var_os("SWARF_WRITE_DOCS").is_some() {
            std::fs::write(&path, &page).unwrap();
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            committed == page,
            "docs/jobs.md is stale: run SWARF_WRITE_DOCS=1 cargo test -p swarf-app job_reference"
        );
    }
}
