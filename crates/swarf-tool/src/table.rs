//! Cutters in config files: a spec string or a table with the same keys.
//!
//! `tool = "bull:d=10,r=2"` and
//! `[tool] shape = "bull", d = 10, r = 2, length = 40` read the same; both go through
//! the spec's field validation ([`crate::spec`]), so errors read the same. A cutter
//! serialises as its canonical spec string.

use crate::cutter::Cutter;
use crate::error::ToolError;
use crate::spec::{Fields, Shape};
use serde::Deserialize;
use std::collections::BTreeMap;

/// What a cutter deserialises from before validation.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum CutterRepr {
    /// `"ball:d=8"`.
    Spec(String),
    /// `{ shape = "ball", d = 8 }`.
    Table(BTreeMap<String, Scalar>),
}

/// A table value: a number, or text (the shape, or a number written as a string).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum Scalar {
    /// A number.
    Number(f64),
    /// Text.
    Text(String),
}

impl TryFrom<CutterRepr> for Cutter {
    type Error = ToolError;

    fn try_from(repr: CutterRepr) -> Result<Cutter, ToolError> {
        let table = match repr {
            CutterRepr::Spec(s) => return s.parse(),
            CutterRepr::Table(table) => table,
        };
        let is_shape = |k: &str| k.trim().eq_ignore_ascii_case("shape");
        let shape = match table.iter().find(|(k, _)| is_shape(k)) {
            Some((_, Scalar::Text(s))) => Shape::parse(s)?,
            _ => return Err(ToolError::MissingShape),
        };
        let mut fields = Fields::new(shape);
        for (key, value) in table.iter().filter(|(k, _)| !is_shape(k)) {
            match value {
                Scalar::Number(x) => fields.set_number(key, *x)?,
                Scalar::Text(t) => fields.set_text(key, t)?,
            }
        }
        fields.build()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Serialize;

    #[derive(Debug, Serialize, Deserialize, PartialEq)]
    struct Job {
        tool: Cutter,
    }

    #[test]
    fn toml_string_and_table_read_the_same() {
        let a: Job = toml::from_str("tool = \"bull:d=10,r=2,length=40\"").unwrap();
        let b: Job =
            toml::from_str("[tool]\nshape = \"bull\"\nd = 10\nr = 2\nlength = 40\n").unwrap();
        assert_eq!(a, b);
        assert_eq!(a.tool, Cutter::bull(10.0, 2.0, Some(40.0)).unwrap());
        let c: Job =
            toml::from_str("tool = { shape = \"Cone\", d = 6.0, angle = \"90\" }").unwrap();
        assert_eq!(c.tool.to_string(), "cone:d=6,angle=90");
    }

    #[test]
    fn serialises_as_the_spec_string() {
        let job = Job {
            tool: "taperball:d=6,angle=10,tip=1".parse().unwrap(),
        };
        let text = toml::to_string(&job).unwrap();
        assert_eq!(text.trim(), "tool = \"taperball:d=6,angle=10,tip=1\"");
        let back: Job = toml::from_str(&text).unwrap();
        assert_eq!(back, job);
        let json = serde_json::to_string(&job).unwrap();
        assert_eq!(json, r#"{"tool":"taperball:d=6,angle=10,tip=1"}"#);
        assert_eq!(serde_json::from_str::<Job>(&json).unwrap(), job);
    }

    #[test]
    fn table_errors_read_like_spec_errors() {
        let err = |text: &str| toml::from_str::<Job>(text).unwrap_err().to_string();
        let e = err("[tool]\nshape = \"bull\"\nd = 10\nr = 6\n");
        assert!(e.contains("`r` must be <= 5 (d/2), got 6"), "{e}");
        let e = err("[tool]\nshape = \"ball\"\nd = 8\nq = 1\n");
        assert!(e.contains("unknown key `q`"), "{e}");
        let e = err("[tool]\nd = 8\n");
        assert!(e.contains("expected `shape"), "{e}");
        let e = err("[tool]\nshape = \"drill\"\nd = 8\n");
        assert!(e.contains("unknown tool shape `drill`"), "{e}");
        let e = err("[tool]\nshape = \"cone\"\nd = 8\n");
        assert!(e.contains("missing `angle`"), "{e}");
        let e = err("[tool]\nshape = \"ball\"\nd = \"eight\"\n");
        assert!(e.contains("`d`: expected a number, got `eight`"), "{e}");
        let e = err("tool = \"ball:d=-8\"");
        assert!(e.contains("`d` must be > 0, got -8"), "{e}");
        let e = err("[tool]\nshape = \"ball\"\nd = 8\nD = 9\n");
        assert!(e.contains("duplicate key `d`"), "{e}");
    }
}
