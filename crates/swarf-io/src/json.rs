//! JSON output whose every number is finite. `serde_json` writes NaN and infinity as
//! `null`, which a reader takes for "absent": a report that says `"max_gouge": null`
//! after a computation went wrong looks like a clean part. [`to_pretty`] walks the
//! value first ([`check_finite`], a serializer that only looks at the numbers) and
//! refuses one that holds a non-finite number, naming its field.

use serde::Serialize;
use serde::ser;
use std::fmt::Display;
use thiserror::Error;

/// Why a value was not written as JSON.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum JsonError {
    /// A number that is NaN or infinite.
    #[error("{field}: {value} is not a finite number (refusing to write it as null)")]
    NonFinite {
        /// Where in the value (`deviation.gouge.worst`, `rows[3].time_s`).
        field: String,
        /// The number.
        value: f64,
    },
    /// The value cannot be serialized at all (a map key that is not text, ...).
    #[error("cannot write JSON: {0}")]
    Serialize(String),
}

impl ser::Error for JsonError {
    fn custom<T: Display>(msg: T) -> Self {
        JsonError::Serialize(msg.to_string())
    }
}

/// `value` as pretty-printed JSON with a final newline.
///
/// # Errors
/// [`JsonError::NonFinite`] naming the first non-finite number's field.
///
/// ```
/// #[derive(serde::Serialize)]
/// struct Report { worst: f64, cells: Vec<f64> }
/// let ok = Report { worst: 0.5, cells: vec![1.0] };
/// assert!(swarf_io::json::to_pretty(&ok).unwrap().ends_with("}\n"));
/// let bad = Report { worst: 0.5, cells: vec![1.0, f64::INFINITY] };
/// let e = swarf_io::json::to_pretty(&bad).unwrap_err();
/// assert_eq!(e.to_string(), "cells[1]: inf is not a finite number (refusing to write it as null)");
/// ```
pub fn to_pretty<T: Serialize + ?Sized>(value: &T) -> Result<String, JsonError> {
    check_finite(value)?;
    serde_json::to_string_pretty(value)
        .map(|s| s + "\n")
        .map_err(|e| JsonError::Serialize(e.to_string()))
}

/// Checks that every number in `value` is finite.
///
/// # Errors
/// [`JsonError::NonFinite`] naming the first one that is not.
pub fn check_finite<T: Serialize + ?Sized>(value: &T) -> Result<(), JsonError> {
    value.serialize(Finite {
        path: &mut Vec::new(),
    })
}

/// The serializer of [`check_finite`]: `path` is where it is in the value.
struct Finite<'a> {
    path: &'a mut Vec<String>,
}

impl Finite<'_> {
    fn number(self, value: f64) -> Result<(), JsonError> {
        if value.is_finite() {
            return Ok(());
        }
        let mut field = String::new();
        for p in self.path.iter() {
            if !field.is_empty() && !p.starts_with('[') {
                field.push('.');
            }
            field.push_str(p);
        }
        if field.is_empty() {
            field.push_str("value");
        }
        Err(JsonError::NonFinite { field, value })
    }

    fn nested(&mut self) -> Finite<'_> {
        Finite {
            path: &mut *self.path,
        }
    }

    /// Checks `value` at `step` below the current place.
    fn at<T: Serialize + ?Sized>(&mut self, step: String, value: &T) -> Result<(), JsonError> {
        self.path.push(step);
        let r = value.serialize(self.nested());
        self.path.pop();
        r
    }
}

/// A sequence, tuple, map or struct being checked.
struct Compound<'a> {
    inner: Finite<'a>,
    index: usize,
    key: Option<String>,
}

impl<'a> Compound<'a> {
    fn new(inner: Finite<'a>) -> Self {
        Compound {
            inner,
            index: 0,
            key: None,
        }
    }

    fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), JsonError> {
        let step = format!("[{}]", self.index);
        self.index += 1;
        self.inner.at(step, value)
    }
}

macro_rules! ignore {
    ($($name:ident: $t:ty),*) => {
        $(fn $name(self, _: $t) -> Result<(), JsonError> { Ok(()) })*
    };
}

impl<'a> ser::Serializer for Finite<'a> {
    type Ok = ();
    type Error = JsonError;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = Compound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    ignore!(serialize_bool: bool, serialize_i8: i8, serialize_i16: i16, serialize_i32: i32,
        serialize_i64: i64, serialize_i128: i128, serialize_u8: u8, serialize_u16: u16,
        serialize_u32: u32, serialize_u64: u64, serialize_u128: u128, serialize_char: char,
        serialize_str: &str, serialize_bytes: &[u8], serialize_unit_struct: &'static str);

    fn serialize_f32(self, v: f32) -> Result<(), JsonError> {
        self.number(f64::from(v))
    }
    fn serialize_f64(self, v: f64) -> Result<(), JsonError> {
        self.number(v)
    }
    fn serialize_none(self) -> Result<(), JsonError> {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), JsonError> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), JsonError> {
        Ok(())
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
    ) -> Result<(), JsonError> {
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<(), JsonError> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        mut self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), JsonError> {
        self.at(variant.to_string(), value)
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Compound<'a>, JsonError> {
        Ok(Compound::new(self))
    }
    fn serialize_tuple(self, _: usize) -> Result<Compound<'a>, JsonError> {
        Ok(Compound::new(self))
    }
    fn serialize_tuple_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, JsonError> {
        Ok(Compound::new(self))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, JsonError> {
        self.path.push(variant.to_string());
        Ok(Compound::new(self))
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Compound<'a>, JsonError> {
        Ok(Compound::new(self))
    }
    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, JsonError> {
        Ok(Compound::new(self))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, JsonError> {
        self.path.push(variant.to_string());
        Ok(Compound::new(self))
    }
}

impl ser::SerializeSeq for Compound<'_> {
    type Ok = ();
    type Error = JsonError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), JsonError> {
        self.element(value)
    }
    fn end(self) -> Result<(), JsonError> {
        Ok(())
    }
}

impl ser::SerializeTuple for Compound<'_> {
    type Ok = ();
    type Error = JsonError;
    fn serialize_element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), JsonError> {
        self.element(value)
    }
    fn end(self) -> Result<(), JsonError> {
        Ok(())
    }
}

impl ser::SerializeTupleStruct for Compound<'_> {
    type Ok = ();
    type Error = JsonError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), JsonError> {
        self.element(value)
    }
    fn end(self) -> Result<(), JsonError> {
        Ok(())
    }
}

impl ser::SerializeTupleVariant for Compound<'_> {
    type Ok = ();
    type Error = JsonError;
    fn serialize_field<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), JsonError> {
        self.element(value)
    }
    fn end(self) -> Result<(), JsonError> {
        self.inner.path.pop();
        Ok(())
    }
}

impl ser::SerializeMap for Compound<'_> {
    type Ok = ();
    type Error = JsonError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), JsonError> {
        self.key = Some(match serde_json::to_value(key) {
            Ok(serde_json::Value::String(s)) => s,
            Ok(other) => other.to_string(),
            Err(e) => return Err(JsonError::Serialize(e.to_string())),
        });
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), JsonError> {
        let key = self.key.take().unwrap_or_default();
        self.inner.at(key, value)
    }
    fn end(self) -> Result<(), JsonError> {
        Ok(())
    }
}

impl ser::SerializeStruct for Compound<'_> {
    type Ok = ();
    type Error = JsonError;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), JsonError> {
        self.inner.at(key.to_string(), value)
    }
    fn end(self) -> Result<(), JsonError> {
        Ok(())
    }
}

impl ser::SerializeStructVariant for Compound<'_> {
    type Ok = ();
    type Error = JsonError;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), JsonError> {
        self.inner.at(key.to_string(), value)
    }
    fn end(self) -> Result<(), JsonError> {
        self.inner.path.pop();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    #[derive(Serialize)]
    enum Shape {
        Circle { r: f64 },
        Pair(f64, f64),
        One(f64),
    }

    #[derive(Serialize)]
    struct Row {
        name: String,
        shapes: Vec<Shape>,
        by_key: BTreeMap<String, (u32, Option<f64>)>,
    }

    fn row(bad: usize) -> Row {
        let v = |k: usize| if k == bad { f64::NAN } else { 1.0 };
        Row {
            name: "a".into(),
            shapes: vec![
                Shape::Circle { r: v(0) },
                Shape::Pair(1.0, v(1)),
                Shape::One(v(2)),
            ],
            by_key: [
                ("x y".to_string(), (3, Some(v(3)))),
                ("z".to_string(), (4, None)),
            ]
            .into(),
        }
    }

    #[test]
    fn every_kind_of_place_is_named() {
        assert!(to_pretty(&row(99)).is_ok());
        let fields: Vec<String> = (0..4)
            .map(|k| match check_finite(&row(k)) {
                Err(JsonError::NonFinite { field, value }) if value.is_nan() => field,
                other => panic!("{other:?}"),
            })
            .collect();
        assert_eq!(
            fields,
            [
                "shapes[0].Circle.r",
                "shapes[1].Pair[1]",
                "shapes[2].One",
                "by_key.x y[1]"
            ]
        );
        let e = check_finite(&f64::NEG_INFINITY).unwrap_err();
        assert_eq!(
            e.to_string(),
            "value: -inf is not a finite number (refusing to write it as null)"
        );
        assert!(check_finite(&serde_json::json!({"a": [1.5, null]})).is_ok());
    }
}
