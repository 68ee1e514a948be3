//! A cleanup job's parameters as its `[strategy]` table gives them (`kind =
//! "cleanup"`): the pattern and its spacing, where the rest comes from, which rest
//! is cleaned up, the boundary operations of the regions (thesis 002 §5.3), the
//! tools of a chain, and the Z-levels of steep rest. Lengths mm; each field named by
//! its own name in errors (the application adds the table and the place).

use crate::cleanup::Pattern;
use crate::error::RestError;
use crate::region::{MERGE, MIN_AREA, OVERLAP, RegionParams, SMOOTHNESS, THRESHOLD};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_geom::domain::{SAMPLE, SCALLOP};
use swarf_path::Finish;
use swarf_path::strategy::waterline::Milling;
use swarf_tool::Cutter;

/// Where a cleanup takes its rest from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum RestSource {
    /// Crease scans of the part with the parent's tool (any parent).
    #[default]
    Reference,
    /// The double contacts the parent raster job records while it is planned.
    Contacts,
    /// The dexel stock after the parent job's program, minus the design.
    Stock,
}

/// A kind of rest a cleanup cleans up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum RestMaterial {
    /// Valleys the parent's tool touched on two sides at once (regions from the
    /// source; regions found on the stock count as valley and ramp rest).
    Valley,
    /// Where the parent's ramp limit held its tool above the part (regions).
    Ramp,
    /// Walls whose slope across a parent raster's passes leaves a scallop above the
    /// threshold, cleaned up by Z-levels ([`crate::steep`]).
    Steep,
}

/// Parameters of a cleanup (module doc).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct CleanupParams {
    /// Tolerance and zigzag.
    #[serde(flatten)]
    pub finish: Finish,
    /// Scallop height between parallel passes and rings, mm (required).
    #[schemars(extend("unit" = "mm", "domain" = format!("{SCALLOP}, below the tool radius")))]
    pub scallop: Option<f64>,
    /// The cut pattern.
    pub pattern: Pattern,
    /// Flow-cut: parallel passes on each side of the pencil pass.
    pub passes: usize,
    /// Where the rest comes from.
    pub source: RestSource,
    /// Rest thinner than this is left, mm (default: the tolerance plus the scallop
    /// height).
    #[schemars(extend("unit" = "mm", "domain" = THRESHOLD.to_string()))]
    pub threshold: Option<f64>,
    /// Regions closer than this are merged, mm.
    #[schemars(extend("unit" = "mm", "domain" = MERGE.to_string()))]
    pub merge: f64,
    /// Outward offset of the regions, mm.
    #[schemars(extend("unit" = "mm", "domain" = OVERLAP.to_string()))]
    pub overlap: f64,
    /// Regions with a smaller raw area are dropped, mm².
    #[schemars(extend("unit" = "mm²", "domain" = MIN_AREA.to_string()))]
    pub min_area: f64,
    /// Concave corners of the boundaries are rounded to at least this radius, mm.
    #[schemars(extend("unit" = "mm", "domain" = SMOOTHNESS.to_string()))]
    pub smoothness: f64,
    /// Intermediate tools, largest first, each cleaning up after the one before it
    /// (the parent's tool first); the job's tool cleans up last.
    pub chain: Vec<Cutter>,
    /// The rest to clean up.
    pub restmaterial: Vec<RestMaterial>,
    /// Steep rest: the milling direction of its Z-levels (climb unless given).
    pub direction: Option<Milling>,
    /// Steep rest: the Go-board cell and the levels' drop-field step, mm (default:
    /// a quarter of the tool radius).
    #[schemars(extend("unit" = "mm", "domain" = SAMPLE.to_string()))]
    pub sampling: Option<f64>,
}

impl Default for CleanupParams {
    /// Flow-cut, no parallel passes, rest from reference scans, valley and ramp
    /// rest, the regions' default boundary operations.
    fn default() -> Self {
        let regions = RegionParams::default();
        CleanupParams {
            finish: Finish::default(),
            scallop: None,
            pattern: Pattern::default(),
            passes: 0,
            source: RestSource::default(),
            threshold: None,
            merge: regions.merge,
            overlap: regions.overlap,
            min_area: regions.min_area,
            smoothness: regions.smoothness,
            chain: Vec::new(),
            restmaterial: vec![RestMaterial::Valley, RestMaterial::Ramp],
            direction: None,
            sampling: None,
        }
    }
}

impl CleanupParams {
    /// A cleanup leaving `scallop` (mm) between its passes, and the defaults.
    pub fn new(scallop: f64) -> CleanupParams {
        CleanupParams {
            scallop: Some(scallop),
            ..CleanupParams::default()
        }
    }

    /// The scallop height of the passes, mm (the tolerance when none is given).
    pub fn scallop_mm(&self) -> f64 {
        self.scallop.unwrap_or(self.finish.tolerance)
    }

    /// The regions' boundary operations (threshold: the tolerance plus the scallop
    /// height unless given).
    pub fn regions(&self) -> RegionParams {
        RegionParams {
            threshold: self
                .threshold
                .unwrap_or(self.finish.tolerance + self.scallop.unwrap_or(0.0)),
            merge: self.merge,
            overlap: self.overlap,
            min_area: self.min_area,
            smoothness: self.smoothness,
        }
    }

    /// Checks the parameters for the cleanup `tool`.
    ///
    /// # Errors
    /// [`RestError::InvalidParameter`] naming the field: a tolerance, scallop,
    /// sampling or region parameter out of range; no scallop; no rest kind or one
    /// listed twice; a chain for steep rest alone.
    pub fn validate(&self, tool: &Cutter) -> Result<(), RestError> {
        self.finish.validate()?;
        swarf_path::params::check_scallop(self.scallop, tool)?;
        swarf_path::params::in_domain("sampling", self.sampling, SAMPLE)?;
        if self.scallop.is_none() {
            return Err(RestError::Parameter {
                field: "scallop".into(),
                message: "a cleanup job needs the scallop height of its passes, mm".into(),
            });
        }
        self.validate_restmaterial()?;
        if let Some(d) = self.direction
            && !self.restmaterial.contains(&RestMaterial::Steep)
        {
            return Err(RestError::Parameter {
                field: "direction".into(),
                message: format!(
                    "\"{}\" is a milling direction for the Z-levels of steep rest; without \"steep\" in restmaterial a cleanup takes none",
                    d.name()
                ),
            });
        }
        self.regions().validate()
    }

    /// The rest kinds: some, each once; steep rest alone has no chain.
    fn validate_restmaterial(&self) -> Result<(), RestError> {
        let kinds = &self.restmaterial;
        let bad = |message: String| RestError::Parameter {
            field: "restmaterial".into(),
            message,
        };
        if kinds.is_empty() {
            return Err(bad(
                "expected one or more of \"valley\", \"ramp\" and \"steep\"".into(),
            ));
        }
        if let Some((_, k)) = kinds
            .iter()
            .enumerate()
            .find(|(i, k)| kinds[..*i].contains(k))
        {
            return Err(bad(format!("{:?} is listed twice", name(k))));
        }
        if kinds.len() == 1 && kinds[0] == RestMaterial::Steep && !self.chain.is_empty() {
            return Err(RestError::Parameter {
                field: "chain".into(),
                message: "steep rest alone is cleaned up by the job's tool in one stage; add \"valley\" or \"ramp\" to strategy.restmaterial for a chain".into(),
            });
        }
        Ok(())
    }
}

/// A rest kind's name as a job writes it.
fn name(k: &RestMaterial) -> &'static str {
    match k {
        RestMaterial::Valley => "valley",
        RestMaterial::Ramp => "ramp",
        RestMaterial::Steep => "steep",
    }
}
