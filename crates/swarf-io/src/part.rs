//! Part files: TOML holding one or more tensor-product patches (format in
//! `parts/README.md`).
//!
//! The document is parsed into `toml`'s spanned tree ([`toml::de::DeTable`]) and
//! walked by hand rather than deserialised with serde: every value keeps its byte
//! span, so each error names the line of the exact value at fault (down to one
//! control point or knot) and the field path (`patch[1].knots_u[4]`), and unknown
//! keys are rejected with a suggestion (typo protection). Patches are validated by
//! [`Patch::new`], whose `field` names are mapped back to spans.
//!
//! Units: `units = "inch"` multiplies the control points by 25.4; knots and weights
//! are dimensionless. Everything returned is in mm.

use crate::error::{At, IoError, excerpt, line_of};
use std::ops::Range;
use std::path::Path;
use swarf_geom::domain::COORDINATE;
use swarf_geom::units::MM_PER_INCH;
use swarf_geom::{GeomError, Part, Patch, Point3};
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// Keys of the top-level table.
const TOP_KEYS: [&str; 3] = ["name", "units", "patch"];
/// Keys of a `[[patch]]` table.
const PATCH_KEYS: [&str; 5] = ["degree", "points", "knots_u", "knots_v", "weights"];
/// Longest excerpt of the source quoted in a message, characters.
const EXCERPT: usize = 40;

/// Reads a part file.
///
/// # Units
/// The returned part is in mm whatever the file's `units`.
///
/// # Errors
/// [`IoError::Io`] when the file cannot be read; otherwise as [`parse_part`].
pub fn read_part(path: &Path) -> Result<Part, IoError> {
    let bytes = crate::input::read_input(path)?;
    let file = path.display().to_string();
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        IoError::format(&file, At::Line(line), "not UTF-8 text; a part file is TOML")
    })?;
    parse_part(text, &file)
}

/// Parses the text of a part file; `source` names it in errors.
///
/// # Units
/// The returned part is in mm whatever the file's `units`.
///
/// # Errors
/// [`IoError::Format`] for malformed TOML, [`IoError::Field`] for a missing, unknown
/// or ill-typed key and for a patch that [`Patch::new`] rejects (wrong point count,
/// decreasing or unclamped knots, weights <= 0, NaN...), each with the line.
///
/// # Example
/// ```
/// let text = "name = \"flat\"\nunits = \"inch\"\n[[patch]]\ndegree = [1, 1]\n\
///             points = [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 0]]\n";
/// let part = swarf_io::parse_part(text, "flat.toml").unwrap();
/// assert_eq!(part.patches[0].point(1, 1).x, 25.4);
/// let e = swarf_io::parse_part(&text.replace("units", "unit"), "flat.toml").unwrap_err();
/// assert_eq!(e.to_string(), "flat.toml: line 2: unit: unknown key; did you mean `units`?");
/// ```
pub fn parse_part(text: &str, source: &str) -> Result<Part, IoError> {
    let doc = Doc { text, file: source };
    let root = DeTable::parse(text).map_err(|e| {
        let at = e
            .span()
            .map_or(At::File, |s| At::Line(line_of(text, s.start)));
        IoError::format(
            source,
            at,
            format!("invalid TOML: {}", e.message().trim().replace('\n', "; ")),
        )
    })?;
    let top = root.get_ref();
    doc.check_keys(top, "", &TOP_KEYS)?;
    let name = doc.string(
        doc.require(top, None, "", "name", "name = \"...\"")?,
        "name",
    )?;
    let units = doc.require(top, None, "", "units", "units = \"mm\" or \"inch\"")?;
    let scale = match doc.string(units, "units")?.as_str() {
        "mm" => 1.0,
        "inch" => MM_PER_INCH,
        _ => {
            let found = doc.found(units);
            return Err(doc.err(
                units,
                "units",
                format!("expected \"mm\" or \"inch\", found {found}"),
            ));
        }
    };
    let list = doc.require(top, None, "", "patch", "one or more [[patch]] tables")?;
    let tables = match list.get_ref() {
        DeValue::Array(a) if !a.is_empty() => a,
        _ => {
            let found = doc.found(list);
            return Err(doc.err(
                list,
                "patch",
                format!("expected one or more [[patch]] tables, found {found}"),
            ));
        }
    };
    let patches = tables
        .iter()
        .enumerate()
        .map(|(k, t)| doc.patch(k, t, scale))
        .collect::<Result<_, _>>()?;
    Ok(Part::new(name, patches))
}

/// The source text and file name, for errors.
struct Doc<'a> {
    text: &'a str,
    file: &'a str,
}

type Value<'i> = Spanned<DeValue<'i>>;

impl Doc<'_> {
    fn at(&self, span: &Range<usize>) -> At {
        At::Line(line_of(self.text, span.start))
    }

    fn err<T>(
        &self,
        v: &Spanned<T>,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> IoError {
        IoError::field(self.file, self.at(&v.span()), field, message)
    }

    /// The source text of `v`, quoted and shortened.
    fn found<T>(&self, v: &Spanned<T>) -> String {
        format!(
            "`{}`",
            excerpt(self.text.get(v.span()).unwrap_or(""), EXCERPT)
        )
    }

    /// Rejects the first key of `table` (in file order) that is not in `allowed`.
    fn check_keys(
        &self,
        table: &DeTable<'_>,
        prefix: &str,
        allowed: &[&str],
    ) -> Result<(), IoError> {
        let unknown = table
            .keys()
            .filter(|k| !allowed.contains(&&**k.get_ref()))
            .min_by_key(|k| k.span().start);
        let Some(key) = unknown else { return Ok(()) };
        let name: &str = key.get_ref();
        let hint = match allowed.iter().min_by_key(|a| edit_distance(a, name)) {
            Some(best) if edit_distance(best, name) <= 2 => format!("did you mean `{best}`?"),
            _ => format!("expected one of {}", allowed.join(", ")),
        };
        Err(self.err(
            key,
            format!("{prefix}{name}"),
            format!("unknown key; {hint}"),
        ))
    }

    /// The value of `key`, or an error at the table's line (`table` span) or file.
    fn require<'t, 'i>(
        &self,
        table: &'t DeTable<'i>,
        table_span: Option<Range<usize>>,
        prefix: &str,
        key: &str,
        expected: &str,
    ) -> Result<&'t Value<'i>, IoError> {
        table.get(key).ok_or_else(|| {
            let at = table_span.map_or(At::File, |s| self.at(&s));
            IoError::field(
                self.file,
                at,
                format!("{prefix}{key}"),
                format!("missing; expected {expected}"),
            )
        })
    }

    fn string(&self, v: &Value<'_>, field: &str) -> Result<String, IoError> {
        match v.get_ref() {
            DeValue::String(s) => Ok(s.to_string()),
            _ => Err(self.err(
                v,
                field,
                format!("expected a string, found {}", self.found(v)),
            )),
        }
    }

    fn number(&self, v: &Value<'_>, field: &str) -> Result<f64, IoError> {
        let parsed = match v.get_ref() {
            DeValue::Integer(i) => i64::from_str_radix(i.as_str(), i.radix())
                .ok()
                .map(|i| i as f64),
            DeValue::Float(f) => f.as_str().parse::<f64>().ok(),
            _ => None,
        };
        parsed.ok_or_else(|| {
            self.err(
                v,
                field,
                format!("expected a number, found {}", self.found(v)),
            )
        })
    }

    fn numbers(&self, v: &Value<'_>, field: &str) -> Result<Vec<f64>, IoError> {
        match v.get_ref() {
            DeValue::Array(a) => a
                .iter()
                .enumerate()
                .map(|(i, x)| self.number(x, &format!("{field}[{i}]")))
                .collect(),
            _ => Err(self.err(
                v,
                field,
                format!("expected an array of numbers, found {}", self.found(v)),
            )),
        }
    }

    fn point(&self, v: &Value<'_>, field: &str) -> Result<Point3, IoError> {
        let bad = || {
            self.err(
                v,
                field,
                format!("expected [x, y, z], three numbers, found {}", self.found(v)),
            )
        };
        let DeValue::Array(a) = v.get_ref() else {
            return Err(bad());
        };
        if a.len() != 3 {
            return Err(bad());
        }
        let c = [0, 1, 2].map(|k| self.number(&a[k], field));
        let [x, y, z] = c;
        Ok(Point3::new(x?, y?, z?))
    }

    fn degree(&self, v: &Value<'_>, field: &str) -> Result<[usize; 2], IoError> {
        let bad = || {
            self.err(
                v,
                field,
                format!(
                    "expected [degree_u, degree_v], two integers >= 1, found {}",
                    self.found(v)
                ),
            )
        };
        let DeValue::Array(a) = v.get_ref() else {
            return Err(bad());
        };
        let d: Vec<usize> = a
            .iter()
            .filter_map(|x| match x.get_ref() {
                DeValue::Integer(i) => usize::from_str_radix(i.as_str(), i.radix()).ok(),
                _ => None,
            })
            .filter(|&d| d >= 1)
            .collect();
        match (a.len(), d.as_slice()) {
            (2, &[u, v]) => Ok([u, v]),
            _ => Err(bad()),
        }
    }

    /// Builds `[[patch]]` number `k`, scaling its points by `scale`.
    fn patch(&self, k: usize, value: &Value<'_>, scale: f64) -> Result<Patch, IoError> {
        let prefix = format!("patch[{k}].");
        let DeValue::Table(t) = value.get_ref() else {
            return Err(self.err(
                value,
                format!("patch[{k}]"),
                format!("expected a [[patch]] table, found {}", self.found(value)),
            ));
        };
        self.check_keys(t, &prefix, &PATCH_KEYS)?;
        let span = Some(value.span());
        let dv = self.require(
            t,
            span.clone(),
            &prefix,
            "degree",
            "degree = [degree_u, degree_v]",
        )?;
        let degree = self.degree(dv, &format!("{prefix}degree"))?;
        let pv = self.require(t, span, &prefix, "points", "points = [[x, y, z], ...]")?;
        let DeValue::Array(pa) = pv.get_ref() else {
            return Err(self.err(
                pv,
                format!("{prefix}points"),
                format!("expected an array of [x, y, z], found {}", self.found(pv)),
            ));
        };
        let points = pa
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let field = format!("{prefix}points[{i}]");
                let q = self.point(p, &field)? * scale;
                // NaN and infinity are Patch::new's to report; a finite coordinate
                // beyond the domain is refused here, before any work is sized by it.
                for &c in q.iter().filter(|c| c.is_finite()) {
                    COORDINATE
                        .check(c)
                        .map_err(|m| self.err(p, field.as_str(), m))?;
                }
                Ok(q)
            })
            .collect::<Result<Vec<_>, IoError>>()?;
        for (dir, d) in ["u", "v"].iter().zip(degree) {
            if d >= points.len() {
                let msg = format!(
                    "degree_{dir} = {d} needs more than {d} control points, found {} in all",
                    points.len()
                );
                return Err(self.err(dv, format!("{prefix}degree"), msg));
            }
        }
        let list = |key: &str| {
            t.get(key)
                .map(|v| self.numbers(v, &format!("{prefix}{key}")))
                .transpose()
        };
        let knots = [list("knots_u")?, list("knots_v")?];
        let weights = list("weights")?;
        Patch::new(degree, points, knots, weights).map_err(|e| self.patch_error(e, k, value, t))
    }

    /// Prefixes a [`Patch::new`] error with the patch and the line of its field.
    fn patch_error(&self, e: GeomError, k: usize, value: &Value<'_>, t: &DeTable<'_>) -> IoError {
        let GeomError::InvalidPatch { field, message } = e else {
            return self.err(value, format!("patch[{k}]"), e.to_string());
        };
        let (name, index) = match field.split_once('[') {
            Some((n, rest)) => (n, rest.trim_end_matches(']').parse::<usize>().ok()),
            None => (field.as_str(), None),
        };
        let span = match (t.get(name), index) {
            (Some(v), Some(i)) => match v.get_ref() {
                DeValue::Array(a) => a.get(i).map_or(v.span(), |x| x.span()),
                _ => v.span(),
            },
            (Some(v), None) => v.span(),
            (None, _) => value.span(),
        };
        IoError::field(
            self.file,
            self.at(&span),
            format!("patch[{k}].{field}"),
            message,
        )
    }
}

/// Levenshtein distance, for "did you mean" hints.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (diag + usize::from(ca != *cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            diag = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const HEAD: &str = "name = \"t\"\nunits = \"mm\"\n\n[[patch]]\ndegree = [1, 1]\n";
    const POINTS: &str =
        "points = [\n  [0, 0, 0],\n  [0, 1, 0],\n  [1, 0, 0],\n  [1, 1, 0.5],\n]\n";

    fn err(text: &str) -> String {
        match parse_part(text, "t.toml") {
            Ok(_) => panic!("parsed: {text}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn minimal_part_and_inch_scaling() {
        let part = parse_part(&format!("{HEAD}{POINTS}"), "t.toml").unwrap();
        assert_eq!(part.name, "t");
        assert_eq!(part.patches[0].point(1, 1), Point3::new(1.0, 1.0, 0.5));
        let inch = format!("{HEAD}{POINTS}").replace("\"mm\"", "\"inch\"");
        let part = parse_part(&inch, "t.toml").unwrap();
        assert_eq!(part.patches[0].point(1, 1), Point3::new(25.4, 25.4, 12.7));
        let floats = format!("{HEAD}{POINTS}").replace("0.5", "5_0.0e-2");
        assert_eq!(
            parse_part(&floats, "t.toml").unwrap().patches[0]
                .point(1, 1)
                .z,
            0.5
        );
    }

    #[test]
    fn malformed_toml_names_line() {
        let e = err("name = \"t\"\nunits = \"mm\"\npatch = [\n  {degree = [1, 1],,}\n]\n");
        assert!(e.starts_with("t.toml: line 4: invalid TOML: "), "{e}");
        assert!(!e.contains('\n'), "{e}");
        let e = err("name = \"t\"\nname = \"u\"\n");
        assert!(e.starts_with("t.toml: line 2: invalid TOML: "), "{e}");
    }

    #[test]
    fn units_and_top_level_keys() {
        let e = err(&format!("{HEAD}{POINTS}").replace("\"mm\"", "\"cm\""));
        assert_eq!(
            e,
            "t.toml: line 2: units: expected \"mm\" or \"inch\", found `\"cm\"`"
        );
        let e = err(&format!("{HEAD}{POINTS}").replace("units = \"mm\"\n", ""));
        assert_eq!(
            e,
            "t.toml: units: missing; expected units = \"mm\" or \"inch\""
        );
        let e = err("name = \"t\"\nunits = \"mm\"\n");
        assert!(
            e.contains("patch: missing; expected one or more [[patch]]"),
            "{e}"
        );
        let e = err("name = \"t\"\nunits = \"mm\"\npatch = []\n");
        assert!(
            e.starts_with("t.toml: line 3: patch: expected one or more"),
            "{e}"
        );
        let e = err(&format!("{HEAD}{POINTS}").replace("name = \"t\"", "name = 5"));
        assert_eq!(e, "t.toml: line 1: name: expected a string, found `5`");
        let e = err(&format!("colour = 1\n{HEAD}{POINTS}"));
        assert_eq!(
            e,
            "t.toml: line 1: colour: unknown key; expected one of name, units, patch"
        );
    }

    #[test]
    fn patch_keys_degree_and_points() {
        let e = err(&format!("{HEAD}{POINTS}knots = [0, 1]\n"));
        assert_eq!(
            e,
            "t.toml: line 12: patch[0].knots: unknown key; did you mean `knots_u`?"
        );
        for (bad, want) in [
            ("[1]", "[1]"),
            ("[0, 1]", "[0, 1]"),
            ("[1, -1]", "[1, -1]"),
            ("\"1\"", "\"1\""),
        ] {
            let e = err(&format!("{HEAD}{POINTS}").replace("[1, 1]\n", &format!("{bad}\n")));
            assert_eq!(
                e,
                format!(
                    "t.toml: line 5: patch[0].degree: expected [degree_u, degree_v], two integers >= 1, found `{want}`"
                )
            );
        }
        let e = err(&format!("{HEAD}{POINTS}").replace("[1, 0, 0]", "[1, 0]"));
        assert_eq!(
            e,
            "t.toml: line 9: patch[0].points[2]: expected [x, y, z], three numbers, found `[1, 0]`"
        );
        let e = err(&format!("{HEAD}{POINTS}").replace("[1, 0, 0]", "[1, true, 0]"));
        assert_eq!(
            e,
            "t.toml: line 9: patch[0].points[2]: expected a number, found `true`"
        );
        let e = err(&format!("{HEAD}{POINTS}").replace("  [1, 0, 0],\n", ""));
        assert!(
            e.starts_with("t.toml: line 6: patch[0].points: expected 4 control points"),
            "{e}"
        );
        let e = err(&format!("{HEAD}{POINTS}").replace("[1, 1]\n", "[4000000000, 1]\n"));
        assert!(
            e.starts_with("t.toml: line 5: patch[0].degree: degree_u = 4000000000 needs more"),
            "{e}"
        );
        let e = err(&format!("{HEAD}degree = [2, 2]\n{POINTS}").replace("degree = [1, 1]\n", ""));
        assert!(
            e.contains("patch[0].points: expected 9 control points"),
            "{e}"
        );
        let e = err(&HEAD.replace("degree", "weights = [1, 1, 1, 1]\ndegree"));
        assert!(
            e.starts_with("t.toml: line 4: patch[0].points: missing"),
            "{e}"
        );
    }

    #[test]
    fn nan_points_knots_and_weights_name_the_element_line() {
        let e = err(&format!("{HEAD}{POINTS}").replace("[0, 1, 0]", "[0, 1, nan]"));
        assert_eq!(
            e,
            "t.toml: line 8: patch[0].points[1]: expected three finite coordinates"
        );
        let knots = "knots_u = [0, 0, 0.5,\n  0.25, 1, 1]\n";
        let six = "points = [[0,0,0],[0,1,0],[1,0,0],[1,1,0],[2,0,0],[2,1,0],[3,0,0],[3,1,0]]\n";
        let e = err(&format!("{HEAD}{six}{knots}"));
        assert_eq!(
            e,
            "t.toml: line 8: patch[0].knots_u[3]: knots must not decrease, found 0.25 after 0.5"
        );
        let e = err(&format!("{HEAD}{six}knots_u = [0, 0.1, 0.5, 0.7, 1, 1]\n"));
        assert!(
            e.starts_with("t.toml: line 7: patch[0].knots_u: expected a clamped knot vector"),
            "{e}"
        );
        let e = err(&format!("{HEAD}{POINTS}weights = [1, -2, 1, 1]\n"));
        assert_eq!(
            e,
            "t.toml: line 12: patch[0].weights[1]: expected a finite weight > 0, found -2"
        );
        let e = err(&format!("{HEAD}{POINTS}weights = [1, 1]\n"));
        assert!(
            e.starts_with("t.toml: line 12: patch[0].weights: expected 4 weights"),
            "{e}"
        );
        let second = POINTS.replace("[0, 0, 0]", "[0, 0, inf]");
        let e = err(&format!(
            "{HEAD}{POINTS}[[patch]]\ndegree = [1, 1]\n{second}"
        ));
        assert_eq!(
            e,
            "t.toml: line 15: patch[1].points[0]: expected three finite coordinates"
        );
    }

    #[test]
    fn a_patch_below_the_smallest_extent_names_its_line() {
        let tiny = "points = [[0,0,0],[0,1e-200,0],[1e-200,0,0],[1e-200,1e-200,0]]\n";
        let e = err(&format!("{HEAD}{POINTS}[[patch]]\ndegree = [1, 1]\n{tiny}"));
        assert_eq!(
            e,
            "t.toml: line 14: patch[1].points: expected control points spanning at least \
             1e-6 mm (the longest side of their box; smaller patches have no computable \
             normal or curvature), found 1.0e-200 mm"
        );
        let small = POINTS.replace("0.5", "0").replace('1', "4e-8");
        let inch = format!("{HEAD}{small}").replace("\"mm\"", "\"inch\"");
        assert!(
            parse_part(&inch, "t.toml").is_ok(),
            "4e-8 inch is 1.016e-6 mm"
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn random_text_never_panics(text in "\\PC{0,200}") {
            let _ = parse_part(&text, "r.toml");
        }

        /// Valid documents with one span replaced by random TOML-ish text.
        #[test]
        fn mutated_parts_never_panic(at in 0usize..200, len in 0usize..6, insert in "[-\\[\\]0-9a-z.,=\" \n]{0,8}") {
            let base = format!("{HEAD}{POINTS}knots_v = [0, 0, 1, 1]\nweights = [1, 2, 1, 1]\n");
            let start = at.min(base.len());
            let end = (start + len).min(base.len());
            let text = format!("{}{}{}", &base[..start], insert, &base[end..]);
            if let Err(e) = parse_part(&text, "m.toml") {
                prop_assert!(e.to_string().starts_with("m.toml"));
            }
        }
    }
}
