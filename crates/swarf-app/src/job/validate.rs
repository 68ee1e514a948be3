//! Checks of a job's parameter ranges that the TOML types cannot express: the
//! strategy, feeds and linking, a cleanup job's parent and regions, and what a
//! five-axis job can write.

use super::{Direction, Job, RestMaterial, RestSource, ZoneChoice};
use swarf_geom::domain::{COORDINATE, Domain, RATE, SAMPLE, SCALLOP, STEP, TOLERANCE, TOOL_LENGTH};

/// Spindle speeds, rev/min.
const SPINDLE: Domain = Domain::new(1e-3, 1e6, "rev/min", "a spindle speed");

/// Most drop-spin passes across a zone.
pub const MAX_DROP_SPIN_PASSES: usize = 1000;
use swarf_path::StrategyKind;

impl Job {
    /// Checks parameter ranges that the TOML types cannot express.
    pub(super) fn validate(&self) -> Result<(), String> {
        let s = &self.strategy;
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
        self.validate_spacing()?;
        if let Some(a) = s.max_ramp
            && (a.is_nan() || a <= 0.0 || a >= 90.0)
        {
            return Err(format!(
                "strategy.max_ramp: {a} degrees: expected an angle between 0 and 90 degrees"
            ));
        }
        if let Some(a) = s.max_slope
            && (a.is_nan() || a <= 0.0 || a >= 90.0)
        {
            return Err(format!(
                "strategy.max_slope: {a} degrees: expected a slope between 0 and 90 degrees"
            ));
        }
        if !s.angle.is_finite() {
            return Err("strategy.angle: expected a finite angle in degrees".into());
        }
        if let Some(b) = s.boundary
            && !(b.iter().all(|&x| COORDINATE.contains(x)) && b[0] < b[2] && b[1] < b[3])
        {
            return Err(format!(
                "strategy.boundary: expected [xmin, ymin, xmax, ymax] with xmin < xmax and ymin < ymax, found {b:?}"
            ));
        }
        self.validate_slopes()?;
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

    /// Tolerance, scallop, stepover and level step, and which strategy takes which.
    fn validate_spacing(&self) -> Result<(), String> {
        let s = &self.strategy;
        in_domain("strategy.tolerance", Some(s.tolerance), TOLERANCE)?;
        in_domain("strategy.scallop", s.scallop, SCALLOP)?;
        in_domain("strategy.stepover", s.stepover, STEP)?;
        in_domain("strategy.level_step", s.level_step, STEP)?;
        in_domain("strategy.sampling", s.sampling, SAMPLE)?;
        let waterline = s.kind == StrategyKind::Waterline && s.level_step.is_some();
        let drop_spin = s.kind == StrategyKind::DropSpin;
        let roughing = s.kind == StrategyKind::Roughing;
        if s.scallop.is_none() && s.stepover.is_none() && !waterline && !drop_spin && !roughing {
            return Err(
                "strategy: expected `scallop` (scallop height limit, mm) or `stepover` (mm)".into(),
            );
        }
        match (s.kind, s.scallop, s.stepover) {
            (
                StrategyKind::Raster
                | StrategyKind::Cleanup
                | StrategyKind::SteepShallow
                | StrategyKind::DropSpin
                | StrategyKind::Roughing,
                _,
                _,
            )
            | (_, _, None) => {}
            (StrategyKind::IsoPlanar, Some(_), Some(_)) => {
                return Err(
                    "strategy.stepover: give either `scallop` (plane spacing from a scallop limit) or `stepover` (a fixed cross feed), not both"
                        .into(),
                );
            }
            (StrategyKind::IsoPlanar, None, Some(step)) => {
                let d = 2.0 * self.tool.radius();
                if step >= d {
                    return Err(format!(
                        "strategy.stepover: {step} mm is not smaller than the tool diameter {d} mm"
                    ));
                }
            }
            (_, _, Some(_)) => {
                return Err(
                    "strategy.stepover: only the raster, steep-shallow and iso-planar strategies take a fixed stepover; use `scallop`"
                        .into(),
                );
            }
        }
        if let Some(h) = s.scallop {
            let r = self.tool.radius();
            if h >= r {
                return Err(format!(
                    "strategy.scallop: {h} mm is not smaller than the tool radius {r} mm; expected 0 < scallop < tool radius"
                ));
            }
        }
        Ok(())
    }

    /// Steep and flat angles, and the direction each strategy takes.
    fn validate_slopes(&self) -> Result<(), String> {
        let s = &self.strategy;
        for (name, a) in [
            ("strategy.steep_angle", s.steep_angle),
            ("strategy.flat_angle", s.flat_angle),
        ] {
            if let Some(a) = a
                && !(a > 0.0 && a < 90.0)
            {
                return Err(format!(
                    "{name}: {a} degrees: expected an angle between 0 and 90 degrees"
                ));
            }
        }
        let (steep, flat) = (s.steep_angle.unwrap_or(45.0), s.flat_angle.unwrap_or(15.0));
        if flat >= steep {
            return Err(format!(
                "strategy.steep_angle: {steep} degrees is not above strategy.flat_angle ({flat} degrees): expected flat_angle < steep_angle"
            ));
        }
        if s.kind == StrategyKind::SteepShallow && s.scallop.is_none() {
            return Err("strategy.scallop: steep-shallow needs the scallop height limit, mm (both spacings follow from it)".into());
        }
        let milling = matches!(s.kind, StrategyKind::Waterline | StrategyKind::SteepShallow)
            || (s.kind == StrategyKind::Cleanup && s.restmaterial.contains(&RestMaterial::Steep));
        match s.direction {
            Some(d @ (Direction::U | Direction::V)) if milling => Err(format!(
                "strategy.direction: \"{}\" is a parameter direction; the {} strategy takes \"climb\" or \"conventional\"",
                file_name(d),
                file_name(s.kind)
            )),
            Some(d @ (Direction::Climb | Direction::Conventional)) if !milling => Err(format!(
                "strategy.direction: \"{}\" is a milling direction for waterline, steep-shallow and steep cleanup; the {} strategy takes \"u\" or \"v\"",
                file_name(d),
                file_name(s.kind)
            )),
            _ => Ok(()),
        }
    }

    /// A cleanup job's parent and region parameters; other jobs have no parent.
    fn validate_cleanup(&self) -> Result<(), String> {
        let s = &self.strategy;
        let Some(parent) = &self.parent else {
            if s.kind == StrategyKind::Cleanup {
                return Err("parent: a cleanup job needs a [parent] table with `job` (a finishing job file) or `tool` (a reference tool)".into());
            }
            return Ok(());
        };
        if s.kind != StrategyKind::Cleanup {
            return Err(
                "parent: only a cleanup job (strategy.kind = \"cleanup\") has a parent".into(),
            );
        }
        match (&parent.job, &parent.tool) {
            (Some(_), Some(_)) | (None, None) => {
                return Err("parent: expected exactly one of `job` (a finishing job file) and `tool` (a reference tool)".into());
            }
            (None, Some(_)) if s.source != RestSource::Reference => {
                return Err(format!(
                    "strategy.source: {:?} needs a parent job (parent.job); a reference tool gives source = \"reference\" only",
                    s.source
                ));
            }
            _ => {}
        }
        if s.scallop.is_none() {
            return Err(
                "strategy.scallop: a cleanup job needs the scallop height of its passes, mm".into(),
            );
        }
        if self.positioning.is_some() {
            return Err("positioning: cleanup paths are three-axis".into());
        }
        self.validate_restmaterial()?;
        self.region_params().validate().map_err(|e| e.to_string())
    }

    /// The rest kinds a cleanup job names: some, each once; steep rest needs a
    /// parent job and is cleaned up by the job's tool alone.
    fn validate_restmaterial(&self) -> Result<(), String> {
        let s = &self.strategy;
        let kinds = &s.restmaterial;
        if kinds.is_empty() {
            return Err(
                "strategy.restmaterial: expected one or more of \"valley\", \"ramp\" and \"steep\""
                    .into(),
            );
        }
        if let Some(k) = kinds
            .iter()
            .enumerate()
            .find(|(i, k)| kinds[..*i].contains(k))
        {
            return Err(format!(
                "strategy.restmaterial: \"{}\" is listed twice",
                file_name(*k.1)
            ));
        }
        if !kinds.contains(&RestMaterial::Steep) {
            return Ok(());
        }
        if self.parent.as_ref().is_some_and(|p| p.job.is_none()) {
            return Err("strategy.restmaterial: \"steep\" needs a parent raster job (parent.job): its stepover and feed direction decide where its scallop is too high".into());
        }
        if kinds.len() == 1 && !s.chain.is_empty() {
            return Err("strategy.chain: steep rest alone is cleaned up by the job's tool in one stage; add \"valley\" or \"ramp\" to strategy.restmaterial for a chain".into());
        }
        Ok(())
    }

    /// A drop-spin job's stations, passes and faces.
    fn validate_drop_spin(&self) -> Result<(), String> {
        let s = &self.strategy;
        in_domain("strategy.step", s.step, STEP)?;
        if self.positioning.is_some() {
            return Err(
                "positioning: drop-spin places the tool itself; leave out the positioning table"
                    .into(),
            );
        }
        if s.zone == ZoneChoice::Full && s.passes == 0 && s.stepover.is_none() {
            return Err("strategy.passes: drop-spin over the full zone needs `passes` (across the zone) or `stepover` (mm)".into());
        }
        if s.passes > MAX_DROP_SPIN_PASSES {
            return Err(format!(
                "strategy.passes: {}: expected at most {MAX_DROP_SPIN_PASSES} passes across the zone",
                s.passes
            ));
        }
        if let Some([a, b]) = s.faces
            && a == b
        {
            return Err(format!(
                "strategy.faces: [{a}, {b}]: expected two different faces"
            ));
        }
        Ok(())
    }

    /// The positioning's ranges and the outputs a five-axis job can write.
    fn validate_five_axis(&self) -> Result<(), String> {
        if let Some(p) = &self.positioning {
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
        if self.strategy.kind == StrategyKind::DropSpin {
            self.validate_drop_spin()?;
        }
        let tilted = self.positioning.is_some() || self.strategy.kind == StrategyKind::DropSpin;
        if tilted && o.gcode.is_some() && o.machine.is_none() {
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

/// A value's name as a job file writes it.
fn file_name<T: serde::Serialize + std::fmt::Debug>(value: T) -> String {
    serde_json::to_value(&value)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_else(|| format!("{value:?}"))
}
