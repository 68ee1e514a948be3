//! Coordinate systems and offsets as LinuxCNC keeps them (`interp_convert.cc`:
//! `convert_coordinate_system`, `convert_setup`, `convert_axis_offsets`,
//! `convert_tool_length_offset`, `convert_home`; `emccanon.cc`: the canonical
//! transform).
//!
//! A program point `p` (the current coordinate system, program units) sits on the
//! machine at `rot(p + g92) + g5x + tool`, where `g5x` is the active system's origin
//! (`G54`-`G59.3`, stored in `#5221 + 20 (n - 1)`), `rot` its XY rotation about the
//! origin (`G10 L2 R`), `g92` the axis offsets of `G92`/`G52` (`#5211-#5219`) and `tool`
//! the tool length offset of `G43`. Every change of offsets re-expresses the current
//! point in the new system, with LinuxCNC's own formulas (which, for instance, leave
//! the G92 offsets out of the rotation when a system's origin changes).
//!
//! `G10 L2 P` sets a system's origin (and `R` its rotation); `G10 L20 P` sets it so that
//! the current point has the given coordinates; `G10 L1 P` sets a tool's offsets and
//! radius in the tool table. `G28`/`G30` move (rapid) through the axes given to the
//! stored position `#5161`/`#5181`; `G28.1`/`G30.1` store the current position there.
//! `G53` moves to machine coordinates for one block.
//!
//! The non-modal codes of group 0 (`G10`, `G28`, `G30`, `G52`, `G92` ...) are in
//! `group_zero`, `G10` itself in `set_data`.

use crate::read::codes::Action;
use crate::read::kinematics::AxisPosition;
use crate::read::modal::{Interpreter, Pos};
use crate::read::words::Words;
use swarf_toolpath::program::Diagnostic;

mod group_zero;
mod set_data;

/// The offsets in force, program units (lengths) and degrees.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Offsets {
    /// The coordinate system: 1 (G54) to 9 (G59.3).
    pub index: u8,
    /// Its origin.
    pub origin: Pos,
    /// The G92/G52 axis offsets.
    pub axis: Pos,
    /// The XY rotation of the system, degrees.
    pub rotation: f64,
    /// The tool length offset (G43).
    pub tool: Pos,
}

impl Offsets {
    /// Carries the lengths into other units (`k` program units per old unit).
    pub fn scale(&mut self, k: f64) {
        for v in [&mut self.origin, &mut self.axis, &mut self.tool] {
            for x in v[..3].iter_mut() {
                *x *= k;
            }
        }
    }
}

/// `(x, y)` turned by `degrees` about the origin (LinuxCNC's `rotate`).
pub fn rotate(x: f64, y: f64, degrees: f64) -> (f64, f64) {
    if degrees == 0.0 {
        return (x, y);
    }
    let (s, c) = degrees.to_radians().sin_cos();
    (x * c - y * s, x * s + y * c)
}

/// `a + b`.
fn plus(a: &Pos, b: &Pos) -> Pos {
    std::array::from_fn(|k| a[k] + b[k])
}

/// `a - b`.
fn minus(a: &Pos, b: &Pos) -> Pos {
    std::array::from_fn(|k| a[k] - b[k])
}

/// The first parameter of system `n`'s block (`#5201 + 20 n`: X of G54 is #5221).
fn system_base(n: u8) -> usize {
    5201 + 20 * usize::from(n)
}

impl Interpreter<'_> {
    /// The start-up system: `#5220` (1 when unset), its origin and rotation, and the
    /// G92 offsets when `#5210` says they are applied.
    pub(crate) fn start_in_g54(&mut self) {
        let n = self.params.at(5220);
        let index = if (1.0..=9.0).contains(&n) { n as u8 } else { 1 };
        self.load_system(index);
        if self.params.at(5210) != 0.0 {
            self.offsets.axis = self.stored(5211);
        }
    }

    /// Six stored values from `first` (lengths then angles) in program units.
    fn stored(&self, first: usize) -> Pos {
        let mut p = [0.0; 6];
        for (k, v) in p.iter_mut().enumerate() {
            let raw = self.params.at(first + k);
            *v = if k < 3 {
                self.user_to_program(raw)
            } else {
                raw
            };
        }
        p
    }

    fn load_system(&mut self, index: u8) {
        let base = system_base(index);
        self.offsets.index = index;
        self.offsets.origin = self.stored(base);
        self.offsets.rotation = self.params.at(base + 9);
        self.params.set(5220, f64::from(index));
    }

    /// The canonical machine position of the program point `p`, program units:
    /// `rot(p + g92) + g5x + tool` (LinuxCNC's `#<_abs_x>` ...).
    pub(crate) fn canonical_machine(&self, p: &Pos) -> Pos {
        let o = &self.offsets;
        let (x, y) = rotate(p[0] + o.axis[0], p[1] + o.axis[1], o.rotation);
        let mut m = [x, y, p[2] + o.axis[2], 0.0, 0.0, 0.0];
        for k in 3..6 {
            m[k] = p[k] + o.axis[k];
        }
        for (k, v) in m.iter_mut().enumerate() {
            *v += o.origin[k] + o.tool[k];
        }
        m
    }

    /// The machine position (mm and degrees) of the program point `p`: the canonical
    /// transform, less the loaded tool's offset (module docs).
    pub(crate) fn to_machine(&self, p: &Pos) -> Pos {
        let loaded = self.loaded_offset();
        let mut m = self.canonical_machine(p);
        for (k, v) in m.iter_mut().enumerate() {
            *v -= loaded[k];
        }
        let s = self.scale();
        for v in m[..3].iter_mut() {
            *v *= s;
        }
        m
    }

    /// The axis position (mm, radians) of the program point `p`.
    pub(crate) fn axis_position(&self, p: &Pos) -> AxisPosition {
        let m = self.to_machine(p);
        let mut a = [m[0], m[1], m[2], 0.0, 0.0];
        if let Some(letters) = self.axes.rotary_letters() {
            for (slot, l) in letters.iter().enumerate() {
                let k = 3 + (*l as usize).saturating_sub('A' as usize).min(2);
                a[3 + slot] = m[k].to_radians();
            }
        }
        a
    }

    /// The program point where the axes stand (their part-frame tip at the start).
    pub(crate) fn program_of_axes(&self) -> Pos {
        let a = self.axes.position();
        let mut m = [a[0], a[1], a[2], 0.0, 0.0, 0.0];
        if let Some(letters) = self.axes.rotary_letters() {
            for (slot, l) in letters.iter().enumerate() {
                let k = 3 + (*l as usize).saturating_sub('A' as usize).min(2);
                m[k] = a[3 + slot].to_degrees();
            }
        }
        for v in m[..3].iter_mut() {
            *v /= self.scale();
        }
        self.program_of_machine(&m)
    }

    /// The program point of machine coordinates `m` (program units, without the tool
    /// offset and the loaded tool's: LinuxCNC's `find_relative`).
    fn program_of_machine(&self, m: &Pos) -> Pos {
        let o = &self.offsets;
        let mut p = minus(&minus(m, &o.origin), &o.tool);
        (p[0], p[1]) = rotate(p[0], p[1], -o.rotation);
        minus(&p, &o.axis)
    }

    /// G54 ... G59.3 (`n` = 1 ... 9).
    pub(crate) fn select_coordinate_system(
        &mut self,
        n: u8,
        w: crate::read::words::Word,
        line: usize,
    ) -> Result<(), Diagnostic> {
        self.refuse_with_comp("change coordinate systems", line, w.column)?;
        if n == self.offsets.index {
            return Ok(());
        }
        self.cur = self.current_in_system(n);
        self.load_system(n);
        Ok(())
    }

    /// The current point in system `n` (LinuxCNC's `find_current_in_system`).
    fn current_in_system(&self, n: u8) -> Pos {
        let o = &self.offsets;
        let mut p = plus(&self.cur, &o.axis);
        (p[0], p[1]) = rotate(p[0], p[1], o.rotation);
        let target = self.stored(system_base(n));
        let mut p = minus(&plus(&p, &o.origin), &target);
        (p[0], p[1]) = rotate(p[0], p[1], -self.params.at(system_base(n) + 9));
        if self.params.at(5210) != 0.0 {
            let g92 = self.stored(5211);
            for k in 0..6 {
                p[k] -= g92[k];
            }
        }
        p
    }

    /// G43 with H (or the loaded tool), G49, G43.1 (the offset in the block's axis
    /// words) or G43.2 (plus tool H's offset). Without a tool table every tool's offset
    /// is 0: the program's points are the tip.
    pub(crate) fn tool_length_offset(
        &mut self,
        action: Action,
        parsed: &Words,
        w: crate::read::words::Word,
        line: usize,
    ) -> Result<(), Diagnostic> {
        self.refuse_with_comp("change the tool offset", line, w.column)?;
        let letters = ['X', 'Y', 'Z', 'A', 'B', 'C'];
        let new = match action {
            Action::LengthOffset => {
                let number = match parsed.get('H') {
                    Some(h) => Some(crate::read::modal::whole(h, line, "H (tool number)")?),
                    None => self.loaded_tool,
                };
                let number = match number {
                    Some(0) | None => self.loaded_tool,
                    n => n,
                };
                self.table_offset(number, parsed.get('H').map_or(w.column, |h| h.column), line)?
            }
            Action::LengthOffsetGiven => {
                let mut new = self.offsets.tool;
                for (k, l) in letters.into_iter().enumerate() {
                    if let Some(v) = parsed.get(l) {
                        new[k] = v.value;
                    }
                }
                new
            }
            Action::LengthOffsetAdd => {
                let Some(h) = parsed.get('H') else {
                    return Err(Diagnostic::new(
                        line,
                        w.column,
                        "G43.2 without an H word: LinuxCNC 2.9 looks up tool -1 and refuses it",
                    ));
                };
                if let Some(a) = letters.iter().find_map(|&l| parsed.get(l)) {
                    return Err(Diagnostic::new(
                        line,
                        a.column,
                        "G43.2: cannot have both H and axis words",
                    ));
                }
                let n = crate::read::modal::whole(h, line, "H (tool number)")?;
                let add = self.table_offset(
                    Some(n).filter(|&n| n != 0).or(self.loaded_tool),
                    h.column,
                    line,
                )?;
                let mut new = self.offsets.tool;
                for k in 0..6 {
                    new[k] += add[k];
                }
                new
            }
            _ => [0.0; 6],
        };
        let old = self.offsets.tool;
        let (dx, dy) = rotate(old[0] - new[0], old[1] - new[1], -self.offsets.rotation);
        self.cur[0] += dx;
        self.cur[1] += dy;
        for k in 2..6 {
            self.cur[k] += old[k] - new[k];
        }
        self.offsets.tool = new;
        Ok(())
    }

    /// Tool `number`'s offsets from the table, program units (zero without a table).
    fn table_offset(
        &self,
        number: Option<u32>,
        column: usize,
        line: usize,
    ) -> Result<Pos, Diagnostic> {
        let mut out = [0.0; 6];
        let table = self.setup.tool_table.is_some() || !self.tools.tools.is_empty();
        let Some(n) = number.filter(|&n| n != 0 && table) else {
            return Ok(out);
        };
        let Some(tool) = self.tools.get(n).copied() else {
            return Err(Diagnostic::new(
                line,
                column,
                format!("tool number {n} not found in the tool table"),
            ));
        };
        for (k, v) in out.iter_mut().enumerate() {
            *v = if k < 3 {
                self.user_to_program(tool.offset[k])
            } else {
                tool.offset[k]
            };
        }
        Ok(out)
    }

    /// The end of a G53 move (machine coordinates for the axes given).
    pub(crate) fn machine_coordinates_end(&self, parsed: &Words) -> Pos {
        let o = self.offsets;
        let (cx, cy) = rotate(self.cur[0] + o.axis[0], self.cur[1] + o.axis[1], o.rotation);
        let x = parsed
            .get('X')
            .map_or(cx, |w| w.value - o.origin[0] - o.tool[0]);
        let y = parsed
            .get('Y')
            .map_or(cy, |w| w.value - o.origin[1] - o.tool[1]);
        let (x, y) = rotate(x, y, -o.rotation);
        let mut end = self.cur;
        end[0] = x - o.axis[0];
        end[1] = y - o.axis[1];
        for (k, l) in ['Z', 'A', 'B', 'C'].into_iter().enumerate() {
            let k = k + 2;
            if let Some(w) = parsed.get(l) {
                let tool = if k == 2 { o.tool[k] } else { 0.0 };
                end[k] = w.value - o.origin[k] - o.axis[k] - tool;
            }
        }
        end
    }
}
