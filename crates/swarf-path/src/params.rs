//! What every strategy shares: the job's [`Cutting`] (its tool, feeds and linking,
//! from the job's own tables), the [`Finish`] part that every strategy table
//! flattens in (tolerance, zigzag), and the side and direction choices. Each
//! strategy's own parameters are defined beside it ([`crate::strategy`]), with
//! serde for the job file (lengths mm, angles degrees there, radians here) and a
//! `validate` that names its own field (`scallop`, not `scallop`: the
//! application adds the table and the place).

use crate::error::PathError;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_geom::domain::{COORDINATE, Domain, SCALLOP, STEP, TOLERANCE, show};
use swarf_geom::units::shown_degrees;
use swarf_tool::Cutter;
use swarf_toolpath::{Feeds, Linking, LinkingSpec};

/// What every strategy cuts with: the job's tool, feeds and linking, and how high
/// the material it cuts reaches.
#[derive(Debug, Clone, PartialEq)]
pub struct Cutting {
    /// The cutter.
    pub tool: Cutter,
    /// Feeds and speeds.
    pub feeds: Feeds,
    /// Clearance plane and approach.
    pub linking: LinkingSpec,
    /// The stock's top, mm (`None`: no material above the path's highest point).
    pub material_top: Option<f64>,
}

impl Cutting {
    /// `tool` with default feeds and linking, no stock above the path.
    pub fn new(tool: Cutter) -> Cutting {
        Cutting {
            tool,
            feeds: Feeds::default(),
            linking: LinkingSpec::default(),
            material_top: None,
        }
    }

    /// The linking of a path whose highest CL point is at `top_z` (mm), above this
    /// cutting's material ([`LinkingSpec::for_top`]).
    pub fn linking_for(&self, top_z: f64) -> Linking {
        self.linking.for_top(top_z, self.material_top)
    }
}

/// The part of every strategy's table that every strategy takes: the chordal
/// tolerance along its passes and whether consecutive passes alternate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default)]
pub struct Finish {
    /// Chordal tolerance along a pass (and gouge tolerance), mm.
    #[schemars(extend("unit" = "mm", "domain" = TOLERANCE.to_string()))]
    pub tolerance: f64,
    /// Alternate the cutting direction of consecutive passes.
    pub zigzag: bool,
}

impl Default for Finish {
    /// A tolerance of 0.01 mm, zigzag passes.
    fn default() -> Self {
        Finish {
            tolerance: 0.01,
            zigzag: true,
        }
    }
}

impl Finish {
    /// Checks the tolerance.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] on `tolerance` outside [`TOLERANCE`].
    pub fn validate(&self) -> Result<(), PathError> {
        in_domain("tolerance", Some(self.tolerance), TOLERANCE)
    }
}

/// Which parameter a pass follows (iso-parametric) or which boundary the first pass
/// starts on (iso-scallop).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ParamDir {
    /// Passes run along u (v constant on each pass).
    #[default]
    U,
    /// Passes run along v (u constant on each pass).
    V,
}

impl std::str::FromStr for ParamDir {
    type Err = String;

    /// `u` or `v`; a milling direction (`climb`, `conventional`) is named as one.
    fn from_str(s: &str) -> Result<ParamDir, String> {
        match s {
            "u" => Ok(ParamDir::U),
            "v" => Ok(ParamDir::V),
            "climb" | "conventional" => Err(format!(
                "\"{s}\" is a milling direction (waterline, steep-shallow, steep cleanup); this strategy takes \"u\" or \"v\""
            )),
            other => Err(format!(
                "unknown variant `{}`, expected `u` or `v`",
                swarf_geom::domain::excerpt(other, 40)
            )),
        }
    }
}

impl<'de> Deserialize<'de> for ParamDir {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<ParamDir, D::Error> {
        String::deserialize(d)?
            .parse()
            .map_err(serde::de::Error::custom)
    }
}

/// Which end of the side-step range the first pass is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum StartSide {
    /// Start at the low end (smallest v, or the lowest drive plane offset).
    #[default]
    Min,
    /// Start at the high end.
    Max,
}

/// `v`, when given, in `domain`; the error names `field`.
///
/// # Errors
/// [`PathError::InvalidParameter`] on `field` outside `domain`.
pub fn in_domain(field: &str, v: Option<f64>, domain: Domain) -> Result<(), PathError> {
    match v {
        Some(x) => domain
            .check(x)
            .map(|_| ())
            .map_err(|message| PathError::InvalidParameter {
                field: field.into(),
                message,
            }),
        None => Ok(()),
    }
}

/// A scallop height limit `scallop` (when given) for `tool`: in [`SCALLOP`] and
/// below the tool's radius.
///
/// # Errors
/// [`PathError::InvalidParameter`] on `scallop`.
pub fn check_scallop(scallop: Option<f64>, tool: &Cutter) -> Result<(), PathError> {
    in_domain("scallop", scallop, SCALLOP)?;
    if let Some(h) = scallop {
        let r = tool.radius();
        if h >= r {
            return Err(PathError::InvalidParameter {
                field: "scallop".into(),
                message: format!(
                    "{h} mm is not smaller than the tool radius {r} mm; expected 0 < scallop < tool radius"
                ),
            });
        }
    }
    Ok(())
}

/// A fixed stepover (when given) in [`STEP`].
///
/// # Errors
/// [`PathError::InvalidParameter`] on `stepover`.
pub fn check_stepover(stepover: Option<f64>) -> Result<(), PathError> {
    in_domain("stepover", stepover, STEP)
}

/// The spacing a strategy needs: a scallop limit or a fixed stepover.
///
/// # Errors
/// [`PathError::InvalidParameter`] on the table itself (`field` empty) when both
/// are absent.
pub fn require_spacing(scallop: Option<f64>, stepover: Option<f64>) -> Result<(), PathError> {
    if scallop.is_none() && stepover.is_none() {
        return Err(PathError::InvalidParameter {
            field: String::new(),
            message: "expected `scallop` (scallop height limit, mm) or `stepover` (mm)".into(),
        });
    }
    Ok(())
}

/// A feed direction `angle` (radians): finite.
///
/// # Errors
/// [`PathError::InvalidParameter`] on `angle`.
pub fn check_angle(angle: f64) -> Result<(), PathError> {
    if angle.is_finite() {
        return Ok(());
    }
    Err(PathError::InvalidParameter {
        field: "angle".into(),
        message: "expected a finite angle in degrees".into(),
    })
}

/// An optional angle `field` (radians) strictly between 0 and 90 degrees; `what`
/// names it in the message (`an angle`, `a slope`).
///
/// # Errors
/// [`PathError::InvalidParameter`] on `field`.
pub fn check_open_angle(field: &str, angle: Option<f64>, what: &str) -> Result<(), PathError> {
    match angle {
        Some(a) if !(a > 0.0 && a < std::f64::consts::FRAC_PI_2) => {
            Err(PathError::InvalidParameter {
                field: field.into(),
                message: format!(
                    "{} degrees: expected {what} between 0 and 90 degrees",
                    shown_degrees(a)
                ),
            })
        }
        _ => Ok(()),
    }
}

/// A rectangle `[xmin, ymin, xmax, ymax]` (when given) of coordinates, with
/// `xmin < xmax` and `ymin < ymax`.
///
/// # Errors
/// [`PathError::InvalidParameter`] on `boundary`.
pub fn check_boundary(boundary: Option<[f64; 4]>) -> Result<(), PathError> {
    match boundary {
        Some(b) if !(b.iter().all(|&x| COORDINATE.contains(x)) && b[0] < b[2] && b[1] < b[3]) => {
            Err(PathError::InvalidParameter {
                field: "boundary".into(),
                message: format!(
                    "expected [xmin, ymin, xmax, ymax] with xmin < xmax and ymin < ymax, found [{}]",
                    b.map(show).join(", ")
                ),
            })
        }
        _ => Ok(()),
    }
}

/// A strategy's parameters with the cutting they are planned with, for the
/// strategies' unit tests: the parameters are its fields through `Deref`.
#[cfg(test)]
pub(crate) struct TestJob<P> {
    /// Tool, feeds, linking.
    pub cut: Cutting,
    /// The strategy's parameters.
    pub params: P,
}

#[cfg(test)]
impl<P> TestJob<P> {
    /// `params` planned with the cutter `tool` (a spec) and default feeds.
    pub fn new(tool: &str, params: P) -> TestJob<P> {
        TestJob {
            cut: Cutting::new(tool.parse().expect("a cutter spec")),
            params,
        }
    }
}

#[cfg(test)]
impl<P> std::ops::Deref for TestJob<P> {
    type Target = P;
    fn deref(&self) -> &P {
        &self.params
    }
}

#[cfg(test)]
impl<P> std::ops::DerefMut for TestJob<P> {
    fn deref_mut(&mut self) -> &mut P {
        &mut self.params
    }
}
