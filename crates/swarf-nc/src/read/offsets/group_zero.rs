//! The non-modal codes of group 0 that change offsets or move: `G10` (in
//! `set_data`), `G28`/`G30` and their `.1` forms, `G52`, `G92` and its `.1`-`.3` forms.

use super::{minus, plus, rotate};
use crate::read::codes::Action;
use crate::read::modal::Interpreter;
use crate::read::words::Words;
use swarf_toolpath::program::{Diagnostic, MotionKind};

impl Interpreter<'_> {
    /// The non-modal codes of group 0 that change offsets or move: G10, G28, G30,
    /// G28.1, G30.1, G52, G92, G92.1, G92.2, G92.3.
    pub(crate) fn modal_zero(&mut self, parsed: &Words, line: usize) -> Result<(), Diagnostic> {
        for &(_, _, action, w) in &parsed.g {
            let comp_err = |what: &str| self.refuse_with_comp(what, line, w.column);
            match action {
                Action::SetData => self.set_data(parsed, w, line)?,
                Action::Home { .. } | Action::SaveHome { .. } if self.comp.is_on() => {
                    return comp_err("use G28 or G30, nor store their positions,");
                }
                Action::Home { second } => self.go_home(second, parsed, line)?,
                Action::SaveHome { second } => self.save_home(second),
                Action::AxisOffset { .. }
                | Action::AxisOffsetOff { .. }
                | Action::AxisOffsetRestore
                    if self.comp.is_on() =>
                {
                    return comp_err("change axis offsets");
                }
                Action::AxisOffset { local } => {
                    if parsed.axis_word(self.axes.rotary_letters()).is_none() {
                        return Err(Diagnostic::new(
                            line,
                            w.column,
                            "all axes missing with G52 or G92",
                        ));
                    }
                    self.axis_offsets(local, parsed);
                }
                Action::AxisOffsetOff { zero_params } => {
                    self.params.set(5210, 0.0);
                    for k in 0..6 {
                        self.cur[k] += self.offsets.axis[k];
                    }
                    self.offsets.axis = [0.0; 6];
                    if zero_params {
                        for i in 5211..=5219 {
                            self.params.set(i, 0.0);
                        }
                    }
                }
                Action::AxisOffsetRestore => {
                    self.params.set(5210, 1.0);
                    let g92 = self.stored(5211);
                    self.cur = minus(&plus(&self.cur, &self.offsets.axis), &g92);
                    self.offsets.axis = g92;
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// G52 (`local`) or G92 with the block's axis words.
    fn axis_offsets(&mut self, local: bool, parsed: &Words) {
        self.params.set(5210, 1.0);
        for (k, l) in ['X', 'Y', 'Z', 'A', 'B', 'C'].into_iter().enumerate() {
            let Some(w) = parsed.get(l) else {
                continue;
            };
            if local {
                self.cur[k] += self.offsets.axis[k] - w.value;
                self.offsets.axis[k] = w.value;
            } else {
                self.offsets.axis[k] = self.cur[k] + self.offsets.axis[k] - w.value;
                self.cur[k] = w.value;
            }
        }
        for k in 0..6 {
            let v = if k < 3 {
                self.program_to_user(self.offsets.axis[k])
            } else {
                self.offsets.axis[k]
            };
            self.params.set(5211 + k, v);
        }
    }

    /// G28.1 / G30.1: the current point in machine coordinates, stored.
    fn save_home(&mut self, second: bool) {
        let o = self.offsets;
        let mut m = plus(&self.cur, &o.axis);
        (m[0], m[1]) = rotate(m[0], m[1], o.rotation);
        let base = if second { 5181 } else { 5161 };
        for (k, v) in plus(&plus(&m, &o.tool), &o.origin).into_iter().enumerate() {
            let v = if k < 3 { self.program_to_user(v) } else { v };
            self.params.set(base + k, v);
        }
    }

    /// G28 / G30: a rapid through the block's axes, then to the stored position (only
    /// the axes given, or all of them when none is).
    fn go_home(&mut self, second: bool, parsed: &Words, line: usize) -> Result<(), Diagnostic> {
        let through = self.find_ends(parsed, line, false)?;
        self.suspicious_numbers(parsed, line);
        self.emit_straight(MotionKind::Rapid, through, None, line)?;
        self.cur = through;
        let base = if second { 5181 } else { 5161 };
        let stored = self.stored(base);
        let home = self.program_of_machine(&stored);
        let letters = ['X', 'Y', 'Z', 'A', 'B', 'C'];
        let any = letters.iter().any(|&l| parsed.get(l).is_some());
        let mut end = through;
        for (k, l) in letters.into_iter().enumerate() {
            if !any || parsed.get(l).is_some() {
                end[k] = home[k];
            }
        }
        self.emit_straight(MotionKind::Rapid, end, None, line)?;
        self.cur = end;
        Ok(())
    }
}
