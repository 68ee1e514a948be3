//! `swarf dsm`: the drop-and-spin method ([`swarf_fiveaxis::dsm`], paper 003) at one
//! footprint or along one reference line, as JSON: the edge at the station, the spin
//! zone, and per footprint the drop (pose, `P`, normal) and both spins (angle, pose,
//! `Q`, clearances). Lengths in mm, angles in degrees.

use crate::error::{AppError, Result, bail};
use crate::model::{Model, load_model};
use serde_json::{Value, json};
use swarf_fiveaxis::dsm::{Dsm, Spin, SpinSide, Station};
use swarf_geom::{Point3, Vec3};
use swarf_tool::{Cutter, Pose};

/// What `swarf dsm` is asked.
#[derive(Debug, Clone)]
pub struct DsmRequest {
    /// The part (a patch part: file or built-in name).
    pub part: String,
    /// The toroidal (or ball) cutter.
    pub tool: Cutter,
    /// The two faces (patch indices); the tool is dropped on the first.
    pub faces: [usize; 2],
    /// The edge's overall direction in XY, degrees from +X.
    pub along: f64,
    /// The station: position of the reference line along that direction, mm.
    pub station: f64,
    /// One footprint's offset from the edge toward the second face, mm; `None`: the
    /// reference line's zone with `footprints` footprints across it.
    pub offset: Option<f64>,
    /// Footprints across the zone on a reference line (its ends included), at least 2.
    pub footprints: usize,
}

fn point(p: &Point3) -> Value {
    json!([p.x, p.y, p.z])
}

fn vector(v: &Vec3) -> Value {
    json!([v.x, v.y, v.z])
}

fn pose(p: &Pose) -> Value {
    json!({ "cl": point(&p.cl), "axis": vector(&p.axis) })
}

fn spin_json(s: Option<Spin>) -> Value {
    s.map_or(Value::Null, |s| {
        json!({
            "angle_deg": s.angle.to_degrees(),
            "pose": pose(&s.pose),
            "q": point(&s.q),
            "q_uv": s.q_uv,
            "clearance_mm": s.clearance,
            "own_clearance_mm": s.own_clearance,
        })
    })
}

/// The drop and both spins at offset `w`, or the reason there are none.
fn footprint_json(dsm: &Dsm, st: &Station, w: f64) -> Value {
    let xy = dsm.footprint(st, 0, w);
    match dsm.drop_on(0, xy) {
        Err(e) => json!({ "offset_mm": w, "footprint": xy, "error": e.to_string() }),
        Ok(d) => json!({
            "offset_mm": w,
            "footprint": xy,
            "drop": { "pose": pose(&d.pose), "p": point(&d.p), "p_uv": d.p_uv, "normal": vector(&d.normal) },
            "spin_plus": spin_json(dsm.spin(&d, SpinSide::Plus)),
            "spin_minus": spin_json(dsm.spin(&d, SpinSide::Minus)),
        }),
    }
}

/// Runs the request (module doc).
///
/// # Errors
/// A part that is not a patch part or cannot be loaded; faces, direction or tool out
/// of their domains; no edge at the station; an empty or unbounded zone (on a line).
pub fn dsm_report(req: &DsmRequest) -> Result<Value> {
    let Model::Patches(part) = load_model(&req.part)? else {
        bail!(
            "{}: drop-and-spin needs a patch part (.toml), not a mesh",
            req.part
        );
    };
    if !req.station.is_finite() || !req.along.is_finite() {
        bail!("--station and --along: expected finite numbers");
    }
    let a = req.along.to_radians();
    let dsm = Dsm::new(
        &part,
        req.faces,
        &req.tool,
        Vec3::new(a.cos(), a.sin(), 0.0),
    )
    .map_err(|e| {
        AppError::Message(format!(
            "--faces {},{} --tool {} on {}: {e}",
            req.faces[0], req.faces[1], req.tool, part.name
        ))
    })?;
    let st = dsm
        .station(req.station)
        .map_err(|e| AppError::Message(format!("--station {}: {e}", req.station)))?;
    let (r, big) = dsm.insert();
    let mut out = json!({
        "part": part.name,
        "tool": req.tool.to_string(),
        "insert_radius_mm": r,
        "insert_centre_radius_mm": big,
        "faces": req.faces,
        "station": {
            "s_mm": st.s,
            "edge": point(&st.edge),
            "across": vector(&st.across),
            "tangent": vector(&st.tangent),
        },
    });
    match req.offset {
        Some(w) => {
            if !w.is_finite() {
                bail!("--offset: expected a finite number of mm");
            }
            out["footprint"] = footprint_json(&dsm, &st, w);
        }
        None => {
            if req.footprints < 2 {
                bail!(
                    "--footprints {}: expected at least 2 (the zone's ends)",
                    req.footprints
                );
            }
            let z = match dsm.zone(&st, 0) {
                Ok(z) => z,
                Err(e) => bail!("{e}{}", crate::drop_spin::fit_note(&dsm, st.s, 0)),
            };
            out["zone"] = json!({
                "t1_mm": z.t1,
                "t2_ball_mm": z.t2_ball,
                "t2_mm": z.t2,
                "binding": z.binding,
            });
            let n = req.footprints - 1;
            let line: Vec<Value> = (0..=n)
                .map(|i| footprint_json(&dsm, &st, z.t1 + (z.t2 - z.t1) * i as f64 / n as f64))
                .collect();
            out["footprints"] = Value::Array(line);
        }
    }
    Ok(out)
}
