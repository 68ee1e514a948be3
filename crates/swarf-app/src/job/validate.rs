//! Checks of a job that the types cannot express: the strategy's own checks (its
//! [`crate::strategy::Kind::validate`], placed in `strategy.`), then what concerns
//! the job as a whole: feeds and linking, a cleanup job's parent, what a five-axis
//! job can write.

use super::Job;
use crate::strategy::Strategy;
use swarf_geom::domain::{COORDINATE, Domain, RATE, STEP, TOOL_LENGTH};
use swarf_rest::{RestMaterial, RestSource};

/// Spindle speeds, rev/min.
const SPINDLE: Domain = Domain::new(1e-3, 1e6, "rev/min", "a spindle speed");

impl Job {
    /// Checks what the types cannot express (module doc).
    ///
    /// # Errors
    /// The first field out of its domain or inconsistent with the job, as
    /// `field: message` (`strategy.scallop: ...`).
    pub(crate) fn validate(&self) -> Result<(), String> {
        if self.part.trim().is_empty() {
            return Err(
                "part: expected a part file, a mesh or builtin:NAME, found an empty name".into(),
            );
        }
        if !(swarf_io::cad::MIN_TRIM_CHORD..=swarf_io::cad::MAX_TRIM_CHORD)
            .contains(&self.import.trim_chord)
        {
            return Err(format!(
                "import.trim_chord: {}: expected a chordal tolerance from {} to {} mm",
                swarf_geom::domain::show(self.import.trim_chord),
                swarf_io::cad::MIN_TRIM_CHORD,
                swarf_io::cad::MAX_TRIM_CHORD
            ));
        }
        self.strategy
            .validate(&self.tool)
            .map_err(|e| e.in_table("strategy"))?;
        self.validate_cleanup()?;
        let f = &self.feeds;
        for (name, v) in [
            ("feeds.feed", f.feed),
            ("feeds.plunge", f.plunge),
            ("feeds.rapid", f.rapid),
        ] {
            in_domain(name, Some(v), RATE)?;
        }
        in_domain("feeds.spindle", Some(f.spindle), SPINDLE)?;
        in_domain("linking.clearance", self.linking.clearance, COORDINATE)?;
        in_domain("linking.approach", Some(self.linking.approach), STEP)?;
        self.validate_five_axis()
    }

    /// A cleanup job's parent and its rest source; other jobs have no parent.
    fn validate_cleanup(&self) -> Result<(), String> {
        let Strategy::Cleanup(c) = &self.strategy else {
            if self.parent.is_some() {
                return Err(
                    "parent: only a cleanup job (strategy.kind = \"cleanup\") has a parent".into(),
                );
            }
            return Ok(());
        };
        let Some(parent) = &self.parent else {
            return Err("parent: a cleanup job needs a [parent] table with `job` (a finishing job file) or `tool` (a reference tool)".into());
        };
        match (&parent.job, &parent.tool) {
            (Some(_), Some(_)) | (None, None) => {
                return Err("parent: expected exactly one of `job` (a finishing job file) and `tool` (a reference tool)".into());
            }
            (None, Some(_)) if c.source != RestSource::Reference => {
                return Err(format!(
                    "strategy.source: {:?} needs a parent job (parent.job); a reference tool gives source = \"reference\" only",
                    c.source
                ));
            }
            (None, Some(_)) if c.restmaterial.contains(&RestMaterial::Steep) => {
                return Err("strategy.restmaterial: \"steep\" needs a parent raster job (parent.job): its stepover and feed direction decide where its scallop is too high".into());
            }
            _ => {}
        }
        if self.positioning.is_some() {
            return Err("positioning: cleanup paths are three-axis".into());
        }
        Ok(())
    }

    /// The positioning's ranges and the outputs a five-axis job can write.
    fn validate_five_axis(&self) -> Result<(), String> {
        if let Some(p) = &self.positioning {
            if self.strategy.tilted() {
                return Err(format!(
                    "positioning: {} places the tool itself; leave out the positioning table",
                    self.strategy.kind()
                ));
            }
            p.validate()
                .map_err(|(field, message)| format!("{field}: {message}"))?;
        }
        let o = &self.output;
        for (name, file) in [
            ("output.gcode", &o.gcode),
            ("output.cl", &o.cl),
            ("output.csv", &o.csv),
            ("output.summary", &o.summary),
            ("output.contacts", &o.contacts),
            ("output.double_contacts", &o.double_contacts),
        ] {
            if let Some(f) = file {
                output_file(name, f)?;
            }
        }
        if self.tilted() && o.gcode.is_some() && o.machine.is_none() {
            return Err(
                "output.machine: a tilted tool path needs a machine file for G-code (e.g. machine = \"builtin:xyzac-trunnion\"); or drop output.gcode (output.cl and output.csv carry the tool axis)"
                    .into(),
            );
        }
        if o.post.is_some() && o.dialect.is_some() {
            return Err(
                "output.dialect: give output.post or its older name output.dialect, not both"
                    .into(),
            );
        }
        if o.machine.as_deref().is_some_and(str::is_empty) {
            return Err("output.machine: expected a machine file or builtin:NAME".into());
        }
        check_arcs(o.arcs, o.arc_tolerance)?;
        if o.arcs && o.machine.is_some() {
            return Err(
                "output.arcs: five-axis programs (output.machine) are written without arcs".into(),
            );
        }
        in_domain("output.tool_length", o.tool_length, TOOL_LENGTH)
    }
}

/// `output.arcs` and `output.arc_tolerance`: a tolerance only with arcs, within
/// swarf-nc's arc tolerance domain.
pub(crate) fn check_arcs(arcs: bool, tolerance: Option<f64>) -> Result<(), String> {
    use swarf_nc::gcode_writer::{MAX_ARC_TOLERANCE_MM, MIN_ARC_TOLERANCE_MM};
    match tolerance {
        Some(_) if !arcs => {
            Err("output.arc_tolerance: given without arcs = true (no arcs are written)".into())
        }
        Some(t) if !(MIN_ARC_TOLERANCE_MM..=MAX_ARC_TOLERANCE_MM).contains(&t) => Err(format!(
            "output.arc_tolerance: expected {MIN_ARC_TOLERANCE_MM} to {MAX_ARC_TOLERANCE_MM} mm, found {t}"
        )),
        _ => Ok(()),
    }
}

/// `v`, when given, in `domain`.
fn in_domain(name: &str, v: Option<f64>, domain: Domain) -> Result<(), String> {
    match v {
        Some(x) => domain.check_named(name, x).map(|_| ()),
        None => Ok(()),
    }
}

/// An output named `name` is a file name inside the output folder: not empty, not a
/// folder (`.`, `..`, a trailing `/`), not absolute and not climbing out with `..`.
pub(crate) fn output_file(name: &str, file: &str) -> Result<(), String> {
    let path = std::path::Path::new(file);
    let climbs = path
        .components()
        .any(|c| !matches!(c, std::path::Component::Normal(_)));
    if file.trim().is_empty() || file.ends_with(['/', '\\']) || climbs {
        return Err(format!(
            "{name}: expected a file name inside the output folder (e.g. \"part.ngc\"), found {file:?}"
        ));
    }
    Ok(())
}
