//! A drop-and-spin job's parameters as its `[strategy]` table gives them (`kind =
//! "drop-spin"`): the two faces, the edge's direction, the stations along it, the
//! passes across the spin zone and the sides and bands cut. Lengths mm; angles
//! degrees in the file, radians here; each field named by its own name in errors.

use crate::error::FiveAxisError;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_geom::domain::STEP;
use swarf_path::Finish;

/// Most drop-spin passes across a zone.
pub const MAX_DROP_SPIN_PASSES: usize = 1000;

/// The bands of drop-spin passes: which faces the tool is dropped on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum BandChoice {
    /// Dropped on the first face, spun onto the second: the second face's band.
    First,
    /// Dropped on the second, spun onto the first.
    Second,
    /// Both, the first's passes first: the whole valley.
    #[default]
    Both,
}

impl BandChoice {
    /// The faces dropped on (0 for the first), in cutting order.
    pub fn faces(self) -> Vec<usize> {
        match self {
            BandChoice::First => vec![0],
            BandChoice::Second => vec![1],
            BandChoice::Both => vec![0, 1],
        }
    }
}

/// The cutting side of drop-spin passes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum SpinChoice {
    /// The second contact ahead of the axis along the feed.
    #[default]
    Leading,
    /// Behind it.
    Trailing,
    /// Both, leading passes first.
    Both,
}

/// Which passes of the spin zone a drop-spin job cuts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ZoneChoice {
    /// Passes across the zone, the last at its limit.
    #[default]
    Full,
    /// The one pass at the zone's limit, nearest the edge on the second face.
    Snug,
}

/// Parameters of drop-and-spin passes along a common edge (paper 003).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct DropSpinParams {
    /// Tolerance and zigzag.
    #[serde(flatten)]
    pub finish: Finish,
    /// The two faces (patch indices), dropped on the first and spun onto the second.
    pub faces: [usize; 2],
    /// The edge's overall direction in XY, degrees from +X.
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees"))]
    pub angle: f64,
    /// Spacing of the stations along the edge, mm (default: half the tool radius).
    #[schemars(extend("unit" = "mm", "domain" = STEP.to_string()))]
    pub step: Option<f64>,
    /// Passes across the spin zone, the last at its limit (or give `stepover`).
    #[schemars(extend("domain" = format!("0 to {MAX_DROP_SPIN_PASSES}")))]
    pub passes: usize,
    /// Distance between the passes across the zone at its middle station, mm
    /// (instead of `passes`).
    #[schemars(extend("unit" = "mm", "domain" = STEP.to_string()))]
    pub stepover: Option<f64>,
    /// Which side of the tool cuts the second face.
    pub spin: SpinChoice,
    /// The whole zone, or only its snug limit.
    pub zone: ZoneChoice,
    /// The faces dropped on (the bands of the valley).
    pub bands: BandChoice,
}

impl Default for DropSpinParams {
    /// Faces 0 then 1, the edge along +X, the leading side over the full zone on
    /// both bands; no pass count yet.
    fn default() -> Self {
        DropSpinParams {
            finish: Finish::default(),
            faces: [0, 1],
            angle: 0.0,
            step: None,
            passes: 0,
            stepover: None,
            spin: SpinChoice::default(),
            zone: ZoneChoice::default(),
            bands: BandChoice::default(),
        }
    }
}

impl DropSpinParams {
    /// Checks the parameters.
    ///
    /// # Errors
    /// [`FiveAxisError::InvalidParameter`] naming the field: a tolerance, step,
    /// stepover or angle out of range, too many passes, no pass count for the full
    /// zone, the same face twice.
    pub fn validate(&self) -> Result<(), FiveAxisError> {
        self.finish.validate().map_err(path)?;
        swarf_path::params::in_domain("step", self.step, STEP).map_err(path)?;
        swarf_path::params::in_domain("stepover", self.stepover, STEP).map_err(path)?;
        swarf_path::params::check_angle(self.angle).map_err(path)?;
        let bad = |field: &str, message: String| FiveAxisError::InvalidParameter {
            field: field.into(),
            message,
        };
        if self.zone == ZoneChoice::Full && self.passes == 0 && self.stepover.is_none() {
            return Err(bad(
                "passes",
                "drop-spin over the full zone needs `passes` (across the zone) or `stepover` (mm)"
                    .into(),
            ));
        }
        if self.passes > MAX_DROP_SPIN_PASSES {
            return Err(bad(
                "passes",
                format!(
                    "{}: expected at most {MAX_DROP_SPIN_PASSES} passes across the zone",
                    self.passes
                ),
            ));
        }
        let [a, b] = self.faces;
        if a == b {
            return Err(bad(
                "faces",
                format!("[{a}, {b}]: expected two different faces"),
            ));
        }
        Ok(())
    }
}

/// A path error about a field as the five-axis crate's.
fn path(e: swarf_path::PathError) -> FiveAxisError {
    match e {
        swarf_path::PathError::InvalidParameter { field, message } => {
            FiveAxisError::InvalidParameter { field, message }
        }
        other => FiveAxisError::InvalidParameter {
            field: String::new(),
            message: other.to_string(),
        },
    }
}
