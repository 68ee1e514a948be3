//! What the strategy tables hold, read off their schema (the parameter structs'
//! serde and doc comments, through `schemars`): the fields of each kind, the kinds
//! that take a field, and the messages for a table that names an unknown kind or a
//! field its kind does not take.

use super::{Kind, Strategy};

/// The JSON schema of the strategy enum `S` (a `oneOf` per kind).
pub(crate) fn generate<S: schemars::JsonSchema>() -> serde_json::Value {
    let schema = schemars::generate::SchemaSettings::draft2020_12()
        .into_generator()
        .into_root_schema_for::<S>();
    serde_json::to_value(schema).unwrap_or_default()
}

/// The table schema of `kind` in `schema` (its `kind` constant and properties).
pub(crate) fn kind_schema<'a>(schema: &'a serde_json::Value, kind: &str) -> &'a serde_json::Value {
    schema["oneOf"]
        .as_array()
        .into_iter()
        .flatten()
        .find(|v| v["properties"]["kind"]["const"] == kind)
        .unwrap_or(&serde_json::Value::Null)
}

/// The fields `kind`'s table takes in `schema`, besides `kind`, sorted.
fn fields_in(schema: &serde_json::Value, kind: &str) -> Vec<String> {
    kind_schema(schema, kind)["properties"]
        .as_object()
        .into_iter()
        .flatten()
        .map(|(name, _)| name.clone())
        .filter(|name| name != "kind")
        .collect()
}

/// The fields a strategy `kind`'s table takes besides `kind`, sorted.
pub fn fields_of(kind: &str) -> Vec<String> {
    fields_in(Strategy::schema(), kind)
}

/// The strategy kinds whose tables take `field`, in the order of
/// [`Strategy::KINDS`].
pub fn kinds_taking(field: &str) -> Vec<&'static str> {
    taking(Strategy::schema(), Strategy::KINDS, field)
}

fn taking<'a>(schema: &serde_json::Value, kinds: &[&'a str], field: &str) -> Vec<&'a str> {
    kinds
        .iter()
        .copied()
        .filter(|kind| fields_in(schema, kind).iter().any(|f| f == field))
        .collect()
}

fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|k| format!("`{k}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `table`'s `kind` and the rest of it.
///
/// # Errors
/// No kind, or one that is not text, as `kind: ...`.
pub(crate) fn split_kind(
    mut table: toml::Table,
    kinds: &[&str],
) -> Result<(String, toml::Table), String> {
    match table.remove("kind") {
        Some(toml::Value::String(k)) => Ok((k, table)),
        Some(v) => Err(format!(
            "kind: expected one of {}, found {v}",
            quoted(kinds)
        )),
        None => Err("missing field `kind`".into()),
    }
}

/// The message for an unknown `kind`.
pub(crate) fn unknown_kind(kind: &str, kinds: &[&str]) -> String {
    format!(
        "kind: unknown variant `{}`, expected one of {}",
        swarf_geom::domain::excerpt(kind, 40),
        quoted(kinds)
    )
}

/// The message for the `fields` `kind`'s table does not take, a line each (`field:
/// message`): the kinds that do take it, and the fields `kind` takes.
fn misplaced(schema: &serde_json::Value, kinds: &[&str], kind: &str, fields: &[&str]) -> String {
    let takes = fields_in(schema, kind);
    let takes: Vec<&str> = takes.iter().map(String::as_str).collect();
    let lines: Vec<String> = fields
        .iter()
        .map(|field| {
            let others = taking(schema, kinds, field);
            let elsewhere = if others.is_empty() {
                "no strategy takes it".to_string()
            } else {
                format!("it is a field of {}", quoted(&others))
            };
            format!("{field}: unknown field `{field}` for kind `{kind}` ({elsewhere})")
        })
        .collect();
    format!("{}; `{kind}` takes {}", lines.join("\n"), quoted(&takes))
}

/// The parameters of `K` read from `table` (without `kind`); `schema` is the
/// strategies' schema, for a misplaced field's message.
///
/// # Errors
/// The first bad field as `field: message` (its path inside the table); a field
/// the kind does not take, with the kinds that do.
pub(crate) fn decode<K: Kind>(
    table: toml::Table,
    schema: &serde_json::Value,
) -> Result<K::Params, String> {
    let takes = fields_in(schema, K::KIND);
    let unknown: Vec<&str> = table
        .keys()
        .map(String::as_str)
        .filter(|k| !takes.iter().any(|t| t == k))
        .collect();
    if !unknown.is_empty() {
        let kinds: Vec<&str> = schema["oneOf"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|v| v["properties"]["kind"]["const"].as_str())
            .collect();
        return Err(misplaced(schema, &kinds, K::KIND, &unknown));
    }
    serde_path_to_error::deserialize::<_, K::Params>(toml::Value::Table(table)).map_err(|e| {
        let message = e.inner().message().trim().to_string();
        let path = e.path().to_string();
        if path == "." {
            message
        } else {
            format!("{path}: {message}")
        }
    })
}
