//! The fixed-format ASCII file (IGES 5.3 ch. 2): 80-column records whose column 73
//! names the section (S start, G global, D directory, P parameter, T terminate) and
//! columns 74-80 number the record within it. The Global section sets the parameter
//! and record delimiters (`,` and `;` unless its first two fields say otherwise) and
//! the length unit; each directory entry is two records of ten 8-column fields.

use super::params::{Tok, tokenize};
use crate::error::{At, IoError};
use swarf_geom::units::MM_PER_INCH;

/// One directory entry (IGES 5.3 sec. 2.2.4.4), with what the reader needs.
#[derive(Debug, Clone)]
pub(crate) struct Entry {
    /// Entity type number (field 1).
    pub ty: i64,
    /// First parameter record, 1-based sequence number in P (field 2).
    pub param: usize,
    /// Transformation matrix DE pointer, 0 for none (field 7).
    pub transform: usize,
    /// Status number (field 9): digits 3-4 are the subordinate switch.
    pub status: String,
    /// Parameter record count (field 14).
    pub param_lines: usize,
    /// Form number (field 15).
    pub form: i64,
    /// Entity label and subscript (fields 18, 19), when not blank.
    pub label: Option<String>,
}

impl Entry {
    /// Whether the entity stands alone or only belongs to a group (subordinate
    /// switch 00 or 02), not physically part of another entity (01, 03).
    pub fn independent(&self) -> bool {
        !matches!(self.status.get(2..4).map(str::trim), Some("01" | "03"))
    }
}

/// The file split into its sections.
pub(crate) struct Records<'a> {
    /// Parameter records: data columns 1-64 and the file line number.
    pub params: Vec<(&'a str, usize)>,
    /// Directory entries, in order (DE pointer `2k + 1` is entry `k`).
    pub entries: Vec<Entry>,
    /// File line of each directory entry's first record.
    pub entry_lines: Vec<usize>,
    /// mm per file length unit, including the model-space scale.
    pub mm_per_unit: f64,
    /// The unit as written (`mm`, `inch`...).
    pub unit: String,
    /// The file's minimum intended resolution (Global field 19), mm.
    pub resolution_mm: f64,
    /// Parameter and record delimiters.
    pub delims: (char, char),
}

/// Splits `text` into sections and reads the Global section and the directory.
pub(crate) fn split<'a>(text: &'a str, file: &str) -> Result<Records<'a>, IoError> {
    let mut sections: [Vec<(&str, usize)>; 5] = Default::default();
    let mut last = 0;
    for (k, raw) in text.lines().enumerate() {
        let line = raw.trim_end_matches('\r');
        if line.trim().is_empty() {
            continue;
        }
        let at = At::Line(k + 1);
        let letter = line.get(72..73).unwrap_or("");
        let sec = match letter {
            "S" => 0,
            "G" => 1,
            "D" => 2,
            "P" => 3,
            "T" => 4,
            _ if sections.iter().all(Vec::is_empty) => {
                return Err(IoError::format(
                    file,
                    at,
                    "not an IGES file: expected 80-column records with S, G, D, P or T in \
                     column 73 (fixed ASCII form)",
                ));
            }
            _ => {
                return Err(IoError::format(
                    file,
                    at,
                    format!("expected S, G, D, P or T in column 73, found {letter:?}"),
                ));
            }
        };
        if sec < last {
            return Err(IoError::format(
                file,
                at,
                format!("section {letter} after a later section; expected the order S G D P T"),
            ));
        }
        last = sec;
        sections[sec].push((line, k + 1));
    }
    let [_, global, dir, params, term] = sections;
    if global.is_empty() || dir.is_empty() || params.is_empty() {
        return Err(IoError::format(
            file,
            At::File,
            "not an IGES file: expected Global (G), Directory (D) and Parameter (P) sections",
        ));
    }
    check_terminate(&term, [global.len(), dir.len(), params.len()], file)?;
    let (delims, mm_per_unit, unit, resolution) = global_section(&global, file)?;
    let (entries, entry_lines) = directory(&dir, file)?;
    let params = params
        .iter()
        .map(|(l, n)| (l.get(..64).unwrap_or(l), *n))
        .collect();
    Ok(Records {
        params,
        entries,
        entry_lines,
        mm_per_unit,
        unit,
        resolution_mm: resolution * mm_per_unit,
        delims,
    })
}

/// The T record's counts of G, D and P records match the file.
fn check_terminate(term: &[(&str, usize)], counts: [usize; 3], file: &str) -> Result<(), IoError> {
    let Some((t, line)) = term.first() else {
        return Ok(());
    };
    for (k, (name, n)) in ["G", "D", "P"].iter().zip(counts).enumerate() {
        let field = t.get(8 * (k + 1)..8 * (k + 2)).unwrap_or("");
        let count = field.get(1..).unwrap_or("").trim().parse::<usize>().ok();
        if count != Some(n) {
            return Err(IoError::format(
                file,
                At::Line(*line),
                format!(
                    "terminate record: {name} count {:?}, but the file has {n} {name} records",
                    field.trim()
                ),
            ));
        }
    }
    Ok(())
}

/// Delimiters, mm per unit, unit name and resolution (file units) from the Global
/// section (sec. 2.2.4.3).
fn global_section(
    lines: &[(&str, usize)],
    file: &str,
) -> Result<((char, char), f64, String, f64), IoError> {
    let text: String = lines
        .iter()
        .map(|(l, _)| l.get(..72).unwrap_or(l))
        .collect();
    let line = lines[0].1;
    let bad = |m: String| IoError::field(file, At::Line(line), "global section", m);
    let (pd, rest) = delimiter(&text, ',', None)
        .ok_or_else(|| bad("bad parameter delimiter (field 1)".into()))?;
    let (rd, _) = delimiter(rest, ';', Some(pd))
        .ok_or_else(|| bad("bad record delimiter (field 2)".into()))?;
    let toks = tokenize(&text, pd, rd).map_err(&bad)?;
    let real = |k: usize, default: f64| -> Result<f64, IoError> {
        match toks.get(k - 1) {
            None | Some(Tok::Empty) => Ok(default),
            Some(Tok::Num(s)) => s
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(format!("field {k}: expected a number, found {s:?}"))),
            Some(Tok::Str(s)) => Err(bad(format!(
                "field {k}: expected a number, found string {s:?}"
            ))),
        }
    };
    let scale = real(13, 1.0)?;
    if scale <= 0.0 {
        return Err(bad(format!(
            "field 13 (model space scale): expected > 0, found {scale}"
        )));
    }
    let flag = real(14, 1.0)?;
    let name = match toks.get(14) {
        Some(Tok::Str(s)) => s.trim().to_string(),
        _ => String::new(),
    };
    let (mm, unit) = unit_of(flag, &name).ok_or_else(|| {
        bad(format!(
            "fields 14-15 (units): flag {flag} name {name:?}: expected flag 1 (inch), 2 (mm), \
             4 (ft), 5 (mile), 6 (m), 7 (km), 8 (mil), 9 (micron), 10 (cm), 11 (microinch) or \
             3 with a known name"
        ))
    })?;
    let resolution = real(19, 0.0)?.abs();
    Ok(((pd, rd), mm / scale, unit.to_string(), resolution))
}

/// mm per unit and its name for the Global unit flag (and name for flag 3).
fn unit_of(flag: f64, name: &str) -> Option<(f64, &'static str)> {
    let by_flag = match flag as i64 {
        1 => (MM_PER_INCH, "inch"),
        2 => (1.0, "mm"),
        4 => (12.0 * MM_PER_INCH, "ft"),
        5 => (63_360.0 * MM_PER_INCH, "mile"),
        6 => (1000.0, "m"),
        7 => (1e6, "km"),
        8 => (1e-3 * MM_PER_INCH, "mil"),
        9 => (1e-3, "micron"),
        10 => (10.0, "cm"),
        11 => (1e-6 * MM_PER_INCH, "microinch"),
        3 => match name.to_ascii_uppercase().as_str() {
            "IN" | "INCH" => (MM_PER_INCH, "inch"),
            "MM" => (1.0, "mm"),
            "M" => (1000.0, "m"),
            "CM" => (10.0, "cm"),
            "FT" => (12.0 * MM_PER_INCH, "ft"),
            _ => return None,
        },
        _ => return None,
    };
    (flag.fract() == 0.0).then_some(by_flag)
}

/// One of the first two Global fields: `1Hc` then the delimiter, or empty (default).
/// Returns the delimiter and the text after it.
fn delimiter(s: &str, default: char, pd: Option<char>) -> Option<(char, &str)> {
    let sep = pd.unwrap_or(default);
    let s = s.trim_start();
    if let Some(rest) = s.strip_prefix("1H") {
        let mut it = rest.chars();
        let c = it.next()?;
        let after = it.as_str();
        let sep = pd.unwrap_or(c);
        let after = after.trim_start();
        let after = after
            .strip_prefix(sep)
            .or_else(|| (pd.is_some()).then_some(after))?;
        return Some((c, after));
    }
    if let Some(rest) = s.strip_prefix(sep) {
        return Some((default, rest));
    }
    (pd.is_some() && s.starts_with(';')).then_some((default, s))
}

/// The directory entries (sec. 2.2.4.4).
fn directory(lines: &[(&str, usize)], file: &str) -> Result<(Vec<Entry>, Vec<usize>), IoError> {
    if !lines.len().is_multiple_of(2) {
        return Err(IoError::format(
            file,
            At::Line(lines[lines.len() - 1].1),
            format!("{} directory records; expected two per entity", lines.len()),
        ));
    }
    let mut out = Vec::with_capacity(lines.len() / 2);
    let mut at = Vec::with_capacity(lines.len() / 2);
    for pair in lines.chunks(2) {
        let ((a, la), (b, lb)) = (pair[0], pair[1]);
        let field = |l: &str, k: usize| l.get(8 * k..8 * k + 8).unwrap_or("").trim().to_string();
        let int = |l: &str, line: usize, k: usize, name: &str| -> Result<i64, IoError> {
            let f = field(l, k);
            if f.is_empty() {
                return Ok(0);
            }
            f.parse::<i64>().map_err(|_| {
                IoError::field(
                    file,
                    At::Line(line),
                    format!(
                        "directory field {} ({name})",
                        k + 1 + if line == lb { 9 } else { 0 }
                    ),
                    format!("expected an integer, found {f:?}"),
                )
            })
        };
        let ptr = |v: i64| usize::try_from(v).unwrap_or(0);
        let ty = int(a, la, 0, "entity type")?;
        let ty2 = int(b, lb, 0, "entity type")?;
        if ty != ty2 {
            return Err(IoError::format(
                file,
                At::Line(lb),
                format!(
                    "directory entry: entity type {ty2} on its second record, {ty} on its first"
                ),
            ));
        }
        let label = field(b, 7);
        let sub = int(b, lb, 8, "entity subscript")?;
        let label = (!label.is_empty()).then(|| {
            if sub != 0 {
                format!("{label}({sub})")
            } else {
                label
            }
        });
        out.push(Entry {
            ty,
            param: ptr(int(a, la, 1, "parameter data")?),
            transform: ptr(int(a, la, 6, "transformation matrix")?),
            status: a.get(64..72).unwrap_or("").to_string(),
            param_lines: ptr(int(b, lb, 3, "parameter line count")?),
            form: int(b, lb, 4, "form number")?,
            label,
        });
        at.push(la);
    }
    Ok((out, at))
}
