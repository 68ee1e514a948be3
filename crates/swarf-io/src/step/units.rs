//! The file's length and plane-angle units (ISO 10303-41 `si_unit`,
//! `conversion_based_unit`), from the `GLOBAL_UNIT_ASSIGNED_CONTEXT` of the geometric
//! context: everything is converted to mm and radians on reading.

use super::graph::{Ent, Graph};
use super::parser::Value;
use crate::error::IoError;

/// Conversion factors of the file's units.
#[derive(Debug, Clone, PartialEq)]
pub struct Units {
    /// mm per file length unit.
    pub mm: f64,
    /// Radians per file angle unit.
    pub rad: f64,
    /// The length unit's name for reports (`mm`, `inch`, `m`...).
    pub name: String,
}

impl Default for Units {
    fn default() -> Self {
        Units {
            mm: 1.0,
            rad: 1.0,
            name: "mm".into(),
        }
    }
}

/// Most `conversion_based_unit` links followed (they may refer to one another).
const MAX_UNIT_CHAIN: usize = 8;

fn si_prefix(p: &Value) -> f64 {
    match p {
        Value::Enum(e) => match e.as_str() {
            "MILLI" => 1e-3,
            "CENTI" => 1e-2,
            "DECI" => 1e-1,
            "KILO" => 1e3,
            "MICRO" => 1e-6,
            "NANO" => 1e-9,
            _ => 1.0,
        },
        _ => 1.0,
    }
}

/// The factor of unit `#id` to SI (metre or radian) and its name.
fn factor(g: &Graph<'_>, id: u64, from: &Ent<'_>, depth: usize) -> Result<(f64, String), IoError> {
    let parts = g.parts(id, Some(from))?;
    if depth > MAX_UNIT_CHAIN {
        return Err(parts[0].err("unit conversions nest too deep (cyclic?)"));
    }
    if let Some(si) = parts.iter().find(|e| e.name == "SI_UNIT") {
        let pre = si.args.first().map_or(1.0, si_prefix);
        let name = match (si.args.first(), si.args.get(1)) {
            (Some(Value::Enum(p)), Some(Value::Enum(n))) if p == "MILLI" && n == "METRE" => {
                "mm".into()
            }
            (Some(Value::Enum(p)), Some(Value::Enum(n))) => {
                format!("{}{}", p.to_lowercase(), n.to_lowercase())
            }
            (_, Some(Value::Enum(n))) if n == "METRE" => "m".into(),
            (_, Some(Value::Enum(n))) => n.to_lowercase(),
            _ => "?".into(),
        };
        return Ok((pre, name));
    }
    if let Some(cb) = parts.iter().find(|e| e.name == "CONVERSION_BASED_UNIT") {
        let name = cb.string(0)?.to_lowercase();
        let m = g.parts(cb.refr(1)?, Some(cb))?;
        let m = m
            .iter()
            .find(|e| e.name.ends_with("MEASURE_WITH_UNIT"))
            .ok_or_else(|| cb.err("argument 2: expected a MEASURE_WITH_UNIT"))?;
        let v = m.num(0)?;
        let (f, _) = factor(g, m.refr(1)?, m, depth + 1)?;
        return Ok((v * f, name));
    }
    Err(parts[0].err("expected an SI_UNIT or a CONVERSION_BASED_UNIT"))
}

/// The units of the file: the first `GLOBAL_UNIT_ASSIGNED_CONTEXT`'s length and
/// angle units; mm and radians where the file says nothing.
///
/// # Errors
/// A unit entity that cannot be read.
pub fn units(g: &Graph<'_>) -> Result<Units, IoError> {
    let mut out = Units::default();
    for id in &g.ex.order {
        let parts = g.parts(*id, None)?;
        let Some(ctx) = parts
            .iter()
            .find(|e| e.name == "GLOBAL_UNIT_ASSIGNED_CONTEXT")
        else {
            continue;
        };
        for u in ctx.refs(0)? {
            let up = g.parts(u, Some(ctx))?;
            if up.iter().any(|e| e.name == "LENGTH_UNIT") {
                let (f, name) = factor(g, u, ctx, 0)?;
                out.mm = f * 1000.0;
                out.name = name;
            } else if up.iter().any(|e| e.name == "PLANE_ANGLE_UNIT") {
                out.rad = factor(g, u, ctx, 0)?.0;
            }
        }
        if !(out.mm.is_finite() && out.mm > 0.0 && out.rad.is_finite() && out.rad > 0.0) {
            return Err(ctx.err("expected positive finite unit conversion factors"));
        }
        return Ok(out);
    }
    Ok(out)
}
