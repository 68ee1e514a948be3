//! `G10` (LinuxCNC's `convert_setup`): `L1` sets a tool's offsets and radius in the
//! tool table, `L2` and `L20` a coordinate system's origin and rotation.

use super::{minus, plus, rotate, system_base};
use crate::read::modal::Interpreter;
use crate::read::words::Words;
use swarf_toolpath::program::Diagnostic;

impl Interpreter<'_> {
    /// G10: L1 (tool table), L2 and L20 (coordinate systems).
    pub(super) fn set_data(
        &mut self,
        parsed: &Words,
        w: crate::read::words::Word,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let err = |column: usize, m: String| Err(Diagnostic::new(line, column, m));
        let Some(l) = parsed.get('L') else {
            return err(w.column, "G10 without an L word (L1, L2 or L20)".into());
        };
        let p = parsed.get('P');
        let p_int = p.map_or(0.0, |p| p.value);
        if (p_int - p_int.round()).abs() > 0.0002 {
            return err(
                p.map_or(w.column, |p| p.column),
                "P value not an integer with G10".into(),
            );
        }
        let p_int = p_int.round() as i64;
        match l.value.round() as i64 {
            2 | 20 if !(0..=9).contains(&p_int) => err(
                p.map_or(w.column, |p| p.column),
                format!("P value out of range (0-9) with G10 L{}", l.value),
            ),
            2 | 20 => {
                if let Some(ij) = parsed.get('I').or(parsed.get('J')) {
                    return err(ij.column, "I J words not allowed with G10 L2".into());
                }
                let n = if p_int == 0 {
                    self.offsets.index
                } else {
                    p_int as u8
                };
                if self.comp.is_on() && n == self.offsets.index {
                    return err(
                        w.column,
                        "cannot change the active coordinate system with cutter radius \
                         compensation on"
                            .into(),
                    );
                }
                self.set_system(n, l.value.round() as i64 == 20, parsed, line)
            }
            1 => self.set_tool(p_int, parsed, line, w.column),
            10 | 11 => err(
                l.column,
                "tool touch-off (G10 L10, L11) is not supported by swarf: give the tool's \
                 offset with G10 L1 or the tool table"
                    .into(),
            ),
            _ => err(
                l.column,
                format!(
                    "line with G10 does not have L1, L2 or L20 (found L{})",
                    l.value
                ),
            ),
        }
    }

    /// G10 L2 / L20 for system `n`.
    fn set_system(
        &mut self,
        n: u8,
        l20: bool,
        parsed: &Words,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let base = system_base(n);
        let here = self.current_in_system(n);
        let rotation = match parsed.get('R') {
            Some(r) if l20 => {
                return Err(Diagnostic::new(line, r.column, "R not allowed in G10 L20"));
            }
            Some(r) => {
                self.params.set(base + 9, r.value);
                r.value
            }
            None => self.params.at(base + 9),
        };
        let mut origin = self.stored(base);
        let letters = ['X', 'Y', 'Z', 'A', 'B', 'C'];
        if l20 {
            let (ox, oy) = rotate(here[0], here[1], rotation);
            let x = parsed.get('X').map_or(here[0], |w| w.value);
            let y = parsed.get('Y').map_or(here[1], |w| w.value);
            let (tx, ty) = rotate(x, y, rotation);
            origin[0] += ox - tx;
            origin[1] += oy - ty;
            for (k, l) in letters.into_iter().enumerate().skip(2) {
                if let Some(w) = parsed.get(l) {
                    origin[k] += here[k] - w.value;
                }
            }
            if n == self.offsets.index {
                (self.cur[0], self.cur[1]) =
                    rotate(self.cur[0], self.cur[1], self.offsets.rotation);
                self.offsets.rotation = 0.0;
            }
        } else {
            for (k, l) in letters.into_iter().enumerate() {
                if let Some(w) = parsed.get(l) {
                    origin[k] = w.value;
                }
            }
        }
        for (k, &v) in origin.iter().enumerate() {
            let user = if k < 3 { self.program_to_user(v) } else { v };
            self.params.set(base + k, user);
        }
        if n == self.offsets.index {
            let o = self.offsets;
            (self.cur[0], self.cur[1]) = rotate(self.cur[0], self.cur[1], o.rotation);
            self.cur = minus(&plus(&self.cur, &o.origin), &origin);
            (self.cur[0], self.cur[1]) = rotate(self.cur[0], self.cur[1], -rotation);
            self.offsets.origin = origin;
            self.offsets.rotation = rotation;
        }
        Ok(())
    }

    /// G10 L1 P: a tool's offsets (X Y Z A B C) and radius (R) in the tool table.
    fn set_tool(
        &mut self,
        p: i64,
        parsed: &Words,
        line: usize,
        column: usize,
    ) -> Result<(), Diagnostic> {
        if p < 1 || p > i64::from(u32::MAX) {
            return Err(Diagnostic::new(
                line,
                column,
                "P value out of range with G10 L1",
            ));
        }
        let number = p as u32;
        let mut tool = self.tools.get(number).copied().unwrap_or_default();
        tool.number = number;
        for (k, l) in ['X', 'Y', 'Z', 'A', 'B', 'C'].into_iter().enumerate() {
            if let Some(w) = parsed.get(l) {
                tool.offset[k] = if k < 3 {
                    self.program_to_user(w.value)
                } else {
                    w.value
                };
            }
        }
        if let Some(r) = parsed.get('R') {
            tool.diameter = 2.0 * self.program_to_user(r.value);
        }
        self.tools.set(tool);
        Ok(())
    }
}
