//! What the strategy tables hold, read off their schema (the parameter structs'
//! serde and doc comments, through `schemars`): the fields of each kind, the kinds
//! that take a field, and the messages for a table that names an unknown kind or a
//! field its kind does not take.

use super::{Kind, Strategy, StrategySchema};
use std::sync::OnceLock;

/// The schema of every kind's table, as JSON.
pub(crate) fn strategy_schema() -> &'static serde_json::Value {
    static SCHEMA: OnceLock<serde_json::Value> = OnceLock::new();
    SCHEMA.get_or_init(|| {
        let schema = schemars::generate::SchemaSettings::draft2020_12()
            .into_generator()
            .into_root_schema_for::<StrategySchema>();
        serde_json::to_value(schema).unwrap_or_default()
    })
}

/// Each kind's table schema (its `kind` constant and properties), in the order of
/// [`Strategy::KINDS`].
pub(crate) fn kind_schemas() -> Vec<(&'static str, &'static serde_json::Value)> {
    let variants = strategy_schema()["oneOf"].as_array();
    Strategy::KINDS
        .iter()
        .map(|&kind| {
            let schema = variants
                .into_iter()
                .flatten()
                .find(|v| v["properties"]["kind"]["const"] == kind)
                .unwrap_or(&serde_json::Value::Null);
            (kind, schema)
        })
        .collect()
}

/// The fields a `kind`'s table takes besides `kind`, sorted.
pub fn fields_of(kind: &str) -> Vec<String> {
    kind_schemas()
        .into_iter()
        .filter(|(k, _)| *k == kind)
        .flat_map(|(_, s)| s["properties"].as_object().into_iter().flatten())
        .map(|(name, _)| name.clone())
        .filter(|name| name != "kind")
        .collect()
}

/// The kinds whose tables take `field`, in the order of [`Strategy::KINDS`].
pub fn kinds_taking(field: &str) -> Vec<&'static str> {
    Strategy::KINDS
        .iter()
        .copied()
        .filter(|kind| fields_of(kind).iter().any(|f| f == field))
        .collect()
}

/// Every kind, quoted, for a message.
pub(super) fn kind_list() -> String {
    quoted(Strategy::KINDS)
}

fn quoted(names: &[&str]) -> String {
    names
        .iter()
        .map(|k| format!("`{k}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The message for an unknown `kind`.
pub(super) fn unknown_kind(kind: &str) -> String {
    format!(
        "kind: unknown variant `{}`, expected one of {}",
        swarf_geom::domain::excerpt(kind, 40),
        kind_list()
    )
}

/// The message for `field`, which `kind`'s table does not take: the fields it takes
/// and the kinds that do take it.
pub(super) fn misplaced(kind: &str, field: &str) -> String {
    let takes = fields_of(kind);
    let takes: Vec<&str> = takes.iter().map(String::as_str).collect();
    let others = kinds_taking(field);
    let elsewhere = if others.is_empty() {
        "no strategy takes it".to_string()
    } else {
        format!("it is a field of {}", quoted(&others))
    };
    format!(
        "{field}: unknown field `{field}` for kind `{kind}` ({elsewhere}); `{kind}` takes {}",
        quoted(&takes)
    )
}

/// The parameters of `K` read from `table` (without `kind`).
///
/// # Errors
/// The first bad field as `field: message` (its path inside the table); a field
/// the kind does not take as [`misplaced`].
pub(super) fn decode<K: Kind>(table: toml::Table) -> Result<K::Params, String> {
    serde_path_to_error::deserialize::<_, K::Params>(toml::Value::Table(table)).map_err(|e| {
        let message = e.inner().message().trim().to_string();
        let path = e.path().to_string();
        match unknown_field_name(&message) {
            Some(field) if path == "." => misplaced(K::KIND, field),
            _ if path == "." => message,
            _ => format!("{path}: {message}"),
        }
    })
}

/// The field a serde "unknown field `x`" message names.
pub(crate) fn unknown_field_name(message: &str) -> Option<&str> {
    let rest = message.strip_prefix("unknown field `")?;
    rest.split('`').next()
}
