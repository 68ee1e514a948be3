//! The tool words (M6, M61, M3/M4/M5), the tool a motion is made with, and the
//! loaded tool's offsets and table entry.

use super::{Interpreter, Pos, whole};
use crate::read::codes::Action;
use crate::read::words::{Word, Words};
use swarf_toolpath::program::{Diagnostic, ToolUse};

impl Interpreter<'_> {
    /// M6, M61, M3/M4/M5.
    pub(super) fn m_codes(&mut self, parsed: &Words, line: usize) -> Result<(), Diagnostic> {
        for &(_, action, w) in &parsed.m {
            match action {
                Action::ToolChange => self.tool_change(self.selected_tool.unwrap_or(0), w, line)?,
                Action::SetTool => {
                    let Some(q) = parsed.get('Q') else {
                        return Err(Diagnostic::new(line, w.column, "M61 requires a Q word"));
                    };
                    let tool = whole(q, line, "tool number Q of M61")?;
                    self.tool_change(tool, w, line)?;
                }
                Action::Spindle(turn) => self.spindle = turn,
                _ => {}
            }
        }
        if let Some(g4) = parsed.has_g(Action::Dwell) {
            if parsed.get('P').is_none() {
                return Err(Diagnostic::new(
                    line,
                    g4.column,
                    "dwell time P word missing with G4",
                ));
            }
            self.warn(
                line,
                g4.column,
                "G4 dwell ignored: machining times exclude it",
            );
        }
        Ok(())
    }

    /// Loads `tool` (M6 or M61); T0 unloads it. The tools a program cuts with are
    /// recorded at their first motion ([`crate::read::Program::tools`]).
    fn tool_change(&mut self, tool: u32, _w: Word, _line: usize) -> Result<(), Diagnostic> {
        self.loaded_tool = Some(tool);
        Ok(())
    }

    /// Notes the tool a motion is made with (a new one from this motion on); feed
    /// motions need one loaded once a tool has been (T0 M6 unloads it).
    pub(crate) fn check_tool(&mut self, feed: bool, line: usize) -> Result<(), Diagnostic> {
        match self.loaded_tool {
            Some(0) if feed && self.cutting_tool.is_some() => Err(Diagnostic::new(
                line,
                1,
                "feed motion with no tool in the spindle: T0 M6 unloaded it",
            )),
            Some(t) if t != 0 && self.cutting_tool != Some(t) => {
                self.cutting_tool = Some(t);
                self.tool_uses.push(ToolUse {
                    first_motion: self.motions.len(),
                    number: t,
                    line,
                });
                Ok(())
            }
            _ => Ok(()),
        }
    }

    /// Warns once when the tool length offset in force is not the loaded tool's: the
    /// tip is then off the programmed point.
    pub(crate) fn check_tool_offset(&mut self, line: usize) {
        if self.tool_warned {
            return;
        }
        let loaded = self.loaded_offset();
        let dz = (self.offsets.tool[2] - loaded[2]) * self.scale();
        if dz.abs() > 1e-9 {
            self.tool_warned = true;
            let tool = self.loaded_tool.unwrap_or(0);
            self.warn(
                line,
                1,
                format!(
                    "the tool length offset in force differs from the loaded tool T{tool}'s by \
                     {dz:.4} mm: the tip is simulated {:.4} mm {} the programmed point",
                    dz.abs(),
                    if dz > 0.0 { "above" } else { "below" }
                ),
            );
        }
    }

    /// The loaded tool's offsets from the tool table, program units.
    pub(crate) fn loaded_offset(&self) -> Pos {
        let tool = self.loaded_tool.and_then(|t| self.tools.get(t));
        let mut out = [0.0; 6];
        if let Some(t) = tool {
            for (k, o) in out.iter_mut().enumerate() {
                *o = if k < 3 {
                    self.user_to_program(t.offset[k])
                } else {
                    t.offset[k]
                };
            }
        }
        out
    }

    /// `#5401 + k` of the loaded tool's table entry, machine units: its offsets
    /// X Y Z A B C U V W (k = 0 ... 8) and its diameter (k = 9).
    pub(crate) fn loaded_tool_parameter(&self, k: usize) -> f64 {
        let Some(tool) = self.loaded_tool.and_then(|t| self.tools.get(t)) else {
            return 0.0;
        };
        match k {
            0..=5 => tool.offset[k],
            9 => tool.diameter,
            _ => 0.0,
        }
    }
}
