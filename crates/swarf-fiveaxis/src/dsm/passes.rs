//! Passes along the common edge (module doc of [`crate::dsm`]): one pass per zone
//! fraction, a pose per station.
//!
//! A pass keeps its fraction `f` of each station's zone, `w = T1 + f (T2 - T1)`, so
//! it follows the zone's width along the edge instead of coming out ragged where the
//! zone narrows; `f = 1` is the snug pass (the insert's ball or the binding part
//! touching at the limit). Each pose is the drop at that footprint spun to the side
//! the pass asked for: *leading* where the second contact `Q` lies ahead of the tool
//! axis along the feed (the edge's tangent), *trailing* where it lies behind; the
//! side is chosen at every station, so the pass stays on one root branch. A station
//! that gives no pose (an empty zone, a drop off a face, no spin) is reported with
//! its reason and the pass is split there; consecutive poses whose axes turn more
//! than `max_turn` per mm of travel are reported too.

use super::{Dsm, Spin, SpinSide, Station, Zone};
use crate::error::FiveAxisError;
use serde::Serialize;
use swarf_toolpath::{Contact, Pass, PathPoint};

/// Which side of the tool cuts the second face.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// `Q` ahead of the axis along the feed.
    Leading,
    /// `Q` behind the axis.
    Trailing,
}

/// Parameters of drop-and-spin passes.
#[derive(Debug, Clone, PartialEq)]
pub struct PassParams {
    /// Stations along the edge direction, mm, in cutting order.
    pub stations: Vec<f64>,
    /// Zone fractions of the passes, each in `[0, 1]`.
    pub fractions: Vec<f64>,
    /// The cutting sides: every fraction is cut with each, in this order.
    pub sides: Vec<Side>,
    /// The face dropped on (0 or 1).
    pub face: usize,
    /// Largest axis turn per mm of travel before a pair of poses is reported,
    /// radians per mm.
    pub max_turn: f64,
}

/// One pose of a pass with its contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgePose {
    /// Station, mm.
    pub station: f64,
    /// Offset from the edge, mm.
    pub offset: f64,
    /// The spun pose and its contacts.
    pub spin: Spin,
    /// First contact `P`.
    pub p: swarf_geom::Point3,
}

/// Something a pass could not do at a station.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StationIssue {
    /// Station, mm.
    pub station: f64,
    /// Zone fraction of the pass.
    pub fraction: f64,
    /// Why.
    pub reason: String,
}

/// Drop-and-spin passes and what went wrong on the way.
#[derive(Debug, Clone, Default)]
pub struct EdgePasses {
    /// The passes as tool paths (split where a station gives no pose).
    pub passes: Vec<Pass>,
    /// Every pose with its contacts, pass by pass.
    pub poses: Vec<Vec<EdgePose>>,
    /// Stations without a pose, and axis turns above the limit.
    pub issues: Vec<StationIssue>,
    /// The zone at each station (`None` where it could not be found).
    pub zones: Vec<(f64, Option<Zone>)>,
}

impl Dsm {
    /// The pose of fraction `f` at `station` to `side`, or the reason there is none.
    fn edge_pose(
        &self,
        st: &Station,
        zone: &Zone,
        f: f64,
        (side, k): (Side, usize),
    ) -> Result<EdgePose, String> {
        let w = zone.t1 + f * (zone.t2 - zone.t1);
        let drop = self
            .drop_on(k, self.footprint(st, k, w))
            .map_err(|e| e.to_string())?;
        let ahead = |s: &Spin| (s.q - s.pose.cl).dot(&st.tangent);
        let spins: Vec<Spin> = [SpinSide::Plus, SpinSide::Minus]
            .into_iter()
            .filter_map(|side| self.spin(&drop, side))
            .collect();
        let chosen = spins
            .into_iter()
            .filter(|s| s.own_clearance >= -super::CONTACT_TOL)
            .max_by(|a, b| {
                let (x, y) = (ahead(a), ahead(b));
                match side {
                    Side::Leading => x.total_cmp(&y),
                    Side::Trailing => y.total_cmp(&x),
                }
            })
            .ok_or_else(|| format!("no spin at offset {w:.6} clears both faces"))?;
        Ok(EdgePose {
            station: st.s,
            offset: w,
            spin: chosen,
            p: drop.p,
        })
    }

    /// Drop-and-spin passes (module doc).
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] on `stations` (fewer than two, not finite),
    /// `fractions` (none, or outside `[0, 1]`), `sides` (none), `face` (not 0 or 1) or `max_turn`
    /// (not above 0).
    pub fn passes(&self, params: &PassParams) -> Result<EdgePasses, FiveAxisError> {
        validate(params)?;
        let mut out = EdgePasses::default();
        let stations: Vec<(Option<Station>, Option<Zone>, Option<String>)> = params
            .stations
            .iter()
            .map(|&s| {
                match self
                    .station(s)
                    .and_then(|st| self.zone(&st, params.face).map(|z| (st, z)))
                {
                    Ok((st, z)) => (Some(st), Some(z), None),
                    Err(e) => (None, None, Some(e.to_string())),
                }
            })
            .collect();
        out.zones = params
            .stations
            .iter()
            .zip(&stations)
            .map(|(&s, x)| (s, x.1))
            .collect();
        let runs = params
            .sides
            .iter()
            .flat_map(|&side| params.fractions.iter().map(move |&f| (side, f)));
        for (side, f) in runs {
            let mut run: Vec<EdgePose> = Vec::new();
            let mut runs: Vec<Vec<EdgePose>> = Vec::new();
            for (&s, (st, zone, why)) in params.stations.iter().zip(&stations) {
                let pose = match (st, zone) {
                    (Some(st), Some(z)) => self.edge_pose(st, z, f, (side, params.face)),
                    _ => Err(why.clone().unwrap_or_default()),
                };
                match pose {
                    Ok(p) => {
                        if let Some(prev) = run.last() {
                            let travel = (p.spin.pose.cl - prev.spin.pose.cl).norm().max(1e-12);
                            let turn = prev.spin.pose.axis.angle(&p.spin.pose.axis);
                            if turn / travel > params.max_turn {
                                out.issues.push(StationIssue {
                                    station: s,
                                    fraction: f,
                                    reason: format!(
                                        "the axis turns {:.3} degrees over {travel:.4} mm, above the limit",
                                        turn.to_degrees()
                                    ),
                                });
                            }
                        }
                        run.push(p);
                    }
                    Err(reason) => {
                        out.issues.push(StationIssue {
                            station: s,
                            fraction: f,
                            reason,
                        });
                        if !run.is_empty() {
                            runs.push(std::mem::take(&mut run));
                        }
                    }
                }
            }
            if !run.is_empty() {
                runs.push(run);
            }
            for run in runs.into_iter().filter(|r| r.len() > 1) {
                out.passes.push(self.pass_of(&run, params.face));
                out.poses.push(run);
            }
        }
        Ok(out)
    }

    /// The tool path pass of `run`, contacts on the second face.
    fn pass_of(&self, run: &[EdgePose], k: usize) -> Pass {
        let other = 1 - k;
        let points = run
            .iter()
            .map(|e| {
                let s = &e.spin;
                let normal = self
                    .face(other)
                    .patch()
                    .derivs(s.q_uv[0], s.q_uv[1])
                    .normal()
                    .map_or(swarf_geom::Vec3::z(), |n| if n.z < 0.0 { -n } else { n });
                PathPoint {
                    pose: s.pose,
                    contact: Some(Contact {
                        point: s.q,
                        normal,
                        face: other,
                        uv: s.q_uv,
                    }),
                    lifted: 0.0,
                }
            })
            .collect();
        Pass {
            points,
            ..Pass::default()
        }
    }
}

fn validate(p: &PassParams) -> Result<(), FiveAxisError> {
    let bad = |field: &str, m: String| Err(FiveAxisError::parameter(field, m));
    if p.stations.len() < 2 || p.stations.iter().any(|s| !s.is_finite()) {
        return bad(
            "stations",
            format!(
                "{} stations: expected two or more finite positions",
                p.stations.len()
            ),
        );
    }
    if p.fractions.is_empty() || p.fractions.iter().any(|f| !(0.0..=1.0).contains(f)) {
        return bad(
            "fractions",
            format!(
                "{:?}: expected one or more zone fractions in [0, 1]",
                p.fractions
            ),
        );
    }
    if p.sides.is_empty() {
        return bad("sides", "expected one or more cutting sides".to_string());
    }
    if p.face > 1 {
        return bad("face", format!("{}: expected 0 or 1", p.face));
    }
    if p.max_turn.is_nan() || p.max_turn <= 0.0 {
        return bad(
            "max_turn",
            format!("{}: expected a turn rate above 0", p.max_turn),
        );
    }
    Ok(())
}
