//! Parameters as a line's expressions see them ([`ParamSource`] over the runner:
//! numbered, local and global named, and the predefined read-only `#<_x>` ...) and
//! the settings of a line (`#1 = ...`, `#<name> = ...`).

use super::Runner;
use crate::read::expr::{Expr, ParamSource, integer};
use crate::read::lexer::{Assignment, Target};
use crate::read::params::{PARAMETER_COUNT, is_read_only};
use swarf_toolpath::program::Diagnostic;

impl Runner<'_> {
    /// The value of an expression with the parameters as they are now.
    pub fn eval(&self, e: &Expr) -> Result<f64, Diagnostic> {
        let scope = Scope { runner: self };
        e.eval(&scope).map_err(|err| {
            let line = self.pc.1;
            self.error(line, err.column, err.message)
        })
    }

    /// The value a setting gives (read before any setting of the line takes effect).
    pub(super) fn assignment_value(
        &self,
        a: &Assignment,
    ) -> Result<(Option<i64>, f64), Diagnostic> {
        let index = match &a.target {
            Target::Numbered(e) => {
                let raw = self.eval(e)?;
                let i = integer(raw).map_err(|m| self.error(self.pc.1, a.column, m))?;
                Some(i)
            }
            Target::Named(_) => None,
        };
        Ok((index, self.eval(&a.value)?))
    }

    /// Makes a setting.
    pub fn assign(
        &mut self,
        a: &Assignment,
        (index, value): (Option<i64>, f64),
        line: usize,
    ) -> Result<(), Diagnostic> {
        match (&a.target, index) {
            (Target::Named(name), _) => {
                if let Some(global) = name.strip_prefix('_') {
                    if predefined(global).is_some() {
                        return Err(self.error(line, a.column, format!("#<{name}> is read-only")));
                    }
                    self.machine.params.set_global(name, value);
                } else {
                    self.frame().named.insert(name.clone(), value);
                }
                Ok(())
            }
            (Target::Numbered(_), Some(i)) => self.set_numbered(i, value, line, a.column),
            (Target::Numbered(_), None) => Ok(()),
        }
    }

    fn set_numbered(
        &mut self,
        i: i64,
        value: f64,
        line: usize,
        column: usize,
    ) -> Result<(), Diagnostic> {
        if self.opts.fanuc {
            return self.set_fanuc(i, value, line, column);
        }
        if i < 1 || i >= PARAMETER_COUNT as i64 {
            return Err(self.error(
                line,
                column,
                format!(
                    "parameter number #{i} out of range (expected #1 to #{})",
                    PARAMETER_COUNT - 1
                ),
            ));
        }
        if is_read_only(i as usize) {
            return Err(self.error(line, column, format!("parameter #{i} is read-only")));
        }
        self.machine.params.set(i as usize, value);
        Ok(())
    }
}

/// Parameters as a line's expressions see them.
pub(super) struct Scope<'r, 'k> {
    pub(super) runner: &'r Runner<'k>,
}

impl ParamSource for Scope<'_, '_> {
    fn numbered(&self, index: i64) -> Result<f64, String> {
        let r = self.runner;
        if r.opts.fanuc {
            return r.fanuc_read(index);
        }
        if index < 1 || index >= PARAMETER_COUNT as i64 {
            return Err(format!(
                "parameter number #{index} out of range (expected #1 to #{})",
                PARAMETER_COUNT - 1
            ));
        }
        let m = &r.machine;
        let i = index as usize;
        match i {
            5420..=5428 if m.comp.is_on() => Err(
                "cannot read the current position (#5420-#5428) with cutter radius compensation on"
                    .into(),
            ),
            5420..=5425 => Ok(m.current()[i - 5420]),
            5426..=5428 => Ok(0.0),
            5400 => Ok(f64::from(m.tool_number().unwrap_or(0))),
            5401..=5410 => Ok(m.loaded_tool_parameter(i - 5401)),
            _ => Ok(m.params.at(i)),
        }
    }

    fn named(&self, name: &str) -> Result<f64, String> {
        let r = self.runner;
        if let Some(global) = name.strip_prefix('_') {
            if let Some(v) = predefined(global).and_then(|f| f(r)) {
                return Ok(v);
            }
            return r
                .machine
                .params
                .global(name)
                .ok_or_else(|| format!("named parameter #<{name}> not defined"));
        }
        match r.frames.last().and_then(|f| f.named.get(name).copied()) {
            Some(v) => Ok(v),
            None if r.o.defining_sub => Ok(0.0),
            None => Err(format!("named parameter #<{name}> not defined")),
        }
    }

    fn exists(&self, name: &str) -> bool {
        self.named(name).is_ok()
    }

    fn fanuc(&self) -> bool {
        self.runner.opts.fanuc
    }
}

/// A predefined read-only named parameter (`#<_x>` ...), by its name without `_`.
type Predefined = fn(&Runner) -> Option<f64>;

fn predefined(name: &str) -> Option<Predefined> {
    fn flag(b: bool) -> Option<f64> {
        Some(f64::from(u8::from(b)))
    }
    let f: Predefined = match name {
        "x" => |r| Some(r.machine.current()[0]),
        "y" => |r| Some(r.machine.current()[1]),
        "z" => |r| Some(r.machine.current()[2]),
        "a" => |r| Some(r.machine.current()[3]),
        "b" => |r| Some(r.machine.current()[4]),
        "c" => |r| Some(r.machine.current()[5]),
        "u" | "v" | "w" => |_| Some(0.0),
        "metric" => |r| flag(!r.machine.inch),
        "imperial" => |r| flag(r.machine.inch),
        "absolute" => |r| flag(r.machine.absolute),
        "incremental" => |r| flag(!r.machine.absolute),
        "inverse_time" => |r| flag(r.machine.inverse_time),
        "units_per_minute" => |r| flag(!r.machine.inverse_time),
        "units_per_rev" => |_| flag(false),
        "abs_x" => |r| Some(r.machine.canonical_machine(&r.machine.current())[0]),
        "abs_y" => |r| Some(r.machine.canonical_machine(&r.machine.current())[1]),
        "abs_z" => |r| Some(r.machine.canonical_machine(&r.machine.current())[2]),
        "abs_a" => |r| Some(r.machine.canonical_machine(&r.machine.current())[3]),
        "abs_b" => |r| Some(r.machine.canonical_machine(&r.machine.current())[4]),
        "abs_c" => |r| Some(r.machine.canonical_machine(&r.machine.current())[5]),
        "motion_mode" => |r| Some(10.0 * r.machine.motion_code()),
        "selected_tool" => |r| Some(r.machine.selected_tool()),
        "tool_offset" => |r| flag(r.machine.offsets.tool.iter().any(|v| *v != 0.0)),
        "coord_system" => |r| Some(r.machine.coord_system_code()),
        "plane" => |r| Some(r.machine.plane_code()),
        "ccomp" => |r| Some(r.machine.comp_code()),
        "ijk_absolute_mode" => |r| flag(r.machine.ijk_absolute),
        "retract_r_plane" => |r| flag(r.machine.cycle.retract_to_r),
        "retract_old_z" => |r| flag(!r.machine.cycle.retract_to_r),
        "feed" => |r| Some(r.machine.feed / r.machine.scale()),
        "current_tool" => |r| Some(f64::from(r.machine.tool_number().unwrap_or(0))),
        "value" => |r| Some(r.value.0),
        "value_returned" => |r| flag(r.value.1),
        "call_level" => |r| Some((r.frames.len() - 1) as f64),
        "line" => |r| Some(r.pc.1 as f64),
        _ => return None,
    };
    Some(f)
}
