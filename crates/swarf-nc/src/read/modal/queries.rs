//! The state as parameters and callers read it: the selected tool, the modal codes
//! (`#<_coord_system>`, `#<_plane>`, `#<_ccomp>`, `#<_motion_mode>`), the tool
//! number and the current point.

use super::{Interpreter, Pos};
use crate::read::arc::Plane;
use crate::read::codes::Action;
use swarf_geom::Point3;

impl Interpreter<'_> {
    /// The selected tool (T), 0 when none.
    pub(crate) fn selected_tool(&self) -> f64 {
        f64::from(self.selected_tool.unwrap_or(0))
    }

    /// The coordinate system as a G code times ten: 540 (G54) ... 593 (G59.3).
    pub(crate) fn coord_system_code(&self) -> f64 {
        let n = f64::from(self.offsets.index);
        if n <= 6.0 {
            530.0 + 10.0 * n
        } else {
            590.0 + (n - 6.0)
        }
    }

    /// The plane as a G code times ten: 170, 180, 190.
    pub(crate) fn plane_code(&self) -> f64 {
        match self.plane {
            Plane::Xy => 170.0,
            Plane::Xz => 180.0,
            Plane::Yz => 190.0,
        }
    }

    /// Cutter compensation as a G code times ten: 400, 410, 420.
    pub(crate) fn comp_code(&self) -> f64 {
        match self.comp.side() {
            None => 400.0,
            Some(true) => 410.0,
            Some(false) => 420.0,
        }
    }

    /// The motion mode as its G code number (80 when none).
    pub(crate) fn motion_code(&self) -> f64 {
        match self.motion {
            Some(Action::Rapid) => 0.0,
            Some(Action::Linear) => 1.0,
            Some(Action::ArcCw) => 2.0,
            Some(Action::ArcCcw) => 3.0,
            Some(Action::Cycle(n)) => f64::from(n),
            _ => 80.0,
        }
    }

    /// The tool number of the last M6, if any.
    pub fn tool_number(&self) -> Option<u32> {
        self.loaded_tool
    }

    /// The current point in program coordinates (program units, degrees).
    pub fn current(&self) -> Pos {
        self.cur
    }

    /// The part-frame point of the program position `p` (see the module docs), mm.
    pub fn part_point(&self, p: &Pos) -> Point3 {
        let m = self.to_machine(p);
        Point3::new(m[0], m[1], m[2])
    }
}
