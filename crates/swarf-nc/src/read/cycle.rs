//! Canned cycles G73, G74, G81-G89, expanded into the moves LinuxCNC makes
//! (`interp_cycles.cc`: `convert_cycle`, `convert_cycle_xy`/`_yz`/`_zx`, the
//! `CYCLE_MACRO` loop and the cycle bodies).
//!
//! In the plane's frame `(a, b, c)` (G17: X Y Z; G18: Z X Y; G19: Y Z X) with `c` the
//! drilling axis: the *initial level* is `c` where the first of a run of cycle blocks
//! starts; R is the retract plane and the `c` word the bottom. In G90 they are
//! absolute; in G91 `R` is measured from the initial level, the bottom from R, and the
//! `a b` words (or polar words) step from hole to hole, `L` times. A cycle block first
//! rises to R when it starts below it; each hole is reached by a rapid at the
//! clearance level (the initial level in G98, R in G99, never below R) and a rapid
//! down to R; the body then feeds and retracts:
//!
//! - G81: feed to the bottom, rapid out. G82: the same with a dwell.
//! - G73: pecks of Q, each backed off 0.010 in (0.254 mm) at rapid; G83: pecks of Q,
//!   each followed by a rapid out to R and back down to 0.010 in above the last depth.
//! - G74/G84 (tapping, spindle reversed at the bottom), G85 (feed out to R), G89 (dwell,
//!   feed out): feed in and out. G86: feed in, rapid out with the spindle stopped.
//! - G87 (back boring): in at an offset (I, J) with the spindle stopped, over to the
//!   hole, feed up to K and back, out again at the offset.
//! - G88: feed in, dwell, stop for the operator to retract by hand: swarf simulates the
//!   retract as a rapid straight up to the clearance level, and warns.
//!
//! Dwells are not simulated (machining times exclude them).

use crate::read::codes::{Action, SpindleTurn};
use crate::read::expr::integer;
use crate::read::modal::{Interpreter, Pos};
use crate::read::words::Words;
use swarf_toolpath::program::{Diagnostic, MotionKind};

/// Most holes one cycle block may make (`L`), and most pecks one hole may take.
pub const MAX_CYCLE_STEPS: i64 = 1_000_000;

/// LinuxCNC's `G83_RAPID_DELTA`: the back-off of G73 and the stop above the last peck
/// of G83, inches.
const PECK_CLEARANCE_INCH: f64 = 0.010;

/// What the cycles remember between blocks.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CycleState {
    /// G99: retract to R rather than to the initial level (G98).
    pub retract_to_r: bool,
    /// The initial level of the current run of cycle blocks.
    pub initial_level: Option<f64>,
    /// The last R word.
    pub r: f64,
    /// The last bottom word (absolute, or the increment from R in G91).
    pub bottom: f64,
    /// The last P (dwell) and Q (peck).
    pub p: f64,
    /// The last Q.
    pub q: f64,
    /// The last I, J, K (G87).
    pub ijk: [f64; 3],
}

/// One cycle block resolved: levels and the hole's place in the plane frame.
struct Levels {
    r: f64,
    bottom: f64,
    clear: f64,
    abc: [usize; 3],
}

impl Interpreter<'_> {
    /// A canned cycle block `G{n}`; `previous` is the motion mode before the block.
    pub(crate) fn canned_cycle(
        &mut self,
        n: u8,
        previous: Option<Action>,
        parsed: &Words,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let column = self.motion_column(parsed);
        let err = |column: usize, m: String| Err(Diagnostic::new(line, column, m));
        self.cycle_allowed(n, line, column)?;
        let same = previous == Some(Action::Cycle(n));
        let (r_word, bottom_word) = self.cycle_levels(same, parsed, line, column)?;
        let repeats = cycle_repeats(parsed, line)?;
        self.cycle_words(n, same, parsed, line, column)?;
        self.spindle_for(n, line, column)?;
        let abc = self.plane.indices();
        let c_letter = ['X', 'Y', 'Z'][abc[2]];
        let current_c = self.cur[abc[2]];
        let mut old_c = *self.cycle.initial_level.get_or_insert(current_c);
        let (r, bottom) = if self.absolute {
            (r_word, bottom_word)
        } else {
            (r_word + old_c, r_word + old_c + bottom_word)
        };
        if r < bottom {
            return err(
                column,
                format!(
                    "R less than {c_letter} in a canned cycle in the {} plane",
                    self.plane.name()
                ),
            );
        }
        let mut current_c = current_c;
        if old_c < r {
            let mut p = self.cur;
            p[abc[2]] = r;
            self.emit_straight(MotionKind::Rapid, p, None, line)?;
            old_c = r;
            current_c = r;
        }
        let clear = if self.cycle.retract_to_r { r } else { old_c };
        let levels = Levels {
            r,
            bottom,
            clear,
            abc,
        };
        let (mut a, mut b, steps) = self.hole_steps(parsed, line)?;
        for k in 0..repeats {
            (a, b) = step_hole(a, b, &steps).map_err(|m| Diagnostic::new(line, column, m))?;
            let over = if k == 0 && current_c > r {
                current_c
            } else {
                clear
            };
            self.cycle_move(true, &levels, a, b, over, line)?;
            if over > r {
                self.cycle_move(true, &levels, a, b, r, line)?;
            }
            self.cycle_body(n, &levels, a, b, line, column)?;
        }
        self.cur[abc[0]] = a;
        self.cur[abc[1]] = b;
        self.cur[abc[2]] = clear;
        self.cycle.bottom = bottom_word;
        self.cycle.r = r_word;
        Ok(())
    }

    /// Refuses a cycle without feed, in inverse time, with compensation on, or G87
    /// out of G17.
    fn cycle_allowed(&self, n: u8, line: usize, column: usize) -> Result<(), Diagnostic> {
        let why = if self.inverse_time {
            "cannot use inverse time feed (G93) with canned cycles"
        } else if self.feed <= 0.0 {
            "cannot feed with zero feed rate: program F before a canned cycle"
        } else if self.comp.is_on() {
            "cannot use canned cycles with cutter radius compensation on"
        } else if n == 87 && self.plane != crate::read::arc::Plane::Xy {
            "G87 back boring is supported in the G17 plane only"
        } else {
            return Ok(());
        };
        Err(Diagnostic::new(line, column, why))
    }

    /// The R word and the bottom word (the drilling axis's), given or kept from the
    /// same cycle before (`same`).
    fn cycle_levels(
        &self,
        same: bool,
        parsed: &Words,
        line: usize,
        column: usize,
    ) -> Result<(f64, f64), Diagnostic> {
        let c_letter = ['X', 'Y', 'Z'][self.plane.indices()[2]];
        let r = match parsed.get('R') {
            Some(r) => r.value,
            None if same => self.cycle.r,
            None => {
                let m = "R clearance plane unspecified in canned cycle";
                return Err(Diagnostic::new(line, column, m));
            }
        };
        let bottom = match parsed.get(c_letter) {
            Some(w) => w.value,
            None if same => self.cycle.bottom,
            None => {
                let plane = self.plane.name();
                let m = format!("{c_letter} value unspecified in a {plane} plane canned cycle");
                return Err(Diagnostic::new(line, column, m));
            }
        };
        Ok((r, bottom))
    }

    /// P, Q and I J K of the cycle: given, or kept from the same cycle before.
    fn cycle_words(
        &mut self,
        n: u8,
        same: bool,
        parsed: &Words,
        line: usize,
        column: usize,
    ) -> Result<(), Diagnostic> {
        let err = |m: String| Err(Diagnostic::new(line, column, m));
        match (n, parsed.get('P')) {
            (_, Some(p)) => self.cycle.p = p.value,
            (82 | 86 | 88 | 89, None) if !same => {
                return err(format!("dwell time P word missing with G{n}"));
            }
            _ => {}
        }
        if matches!(n, 73 | 83) {
            match parsed.get('Q') {
                Some(q) => self.cycle.q = q.value,
                None if !same => return err(format!("Q word missing with G{n}")),
                None => {}
            }
            if self.cycle.q <= 0.0 {
                return err(format!("negative or zero Q value used with G{n}"));
            }
        }
        if n == 87 {
            for (k, l) in ['I', 'J', 'K'].into_iter().enumerate() {
                match parsed.get(l) {
                    Some(w) => self.cycle.ijk[k] = w.value,
                    None if !same => return err(format!("{l} word missing with G87")),
                    None => {}
                }
            }
        }
        Ok(())
    }

    /// The spindle a cycle needs: turning for G86-G88, clockwise for G84,
    /// counter-clockwise for G74.
    fn spindle_for(&self, n: u8, line: usize, column: usize) -> Result<(), Diagnostic> {
        let turn = self.spindle;
        let message = match (n, turn) {
            (74 | 84 | 86 | 87 | 88, SpindleTurn::Stopped) => {
                format!("spindle not turning in G{n}")
            }
            (74, SpindleTurn::Clockwise) => "spindle turning clockwise in G74".to_string(),
            (84, SpindleTurn::CounterClockwise) => {
                "spindle turning counterclockwise in G84".to_string()
            }
            _ => return Ok(()),
        };
        Err(Diagnostic::new(line, column, message))
    }

    /// The first hole's `(a, b)` before stepping, and the steps between holes.
    fn hole_steps(&self, parsed: &Words, line: usize) -> Result<(f64, f64, Steps), Diagnostic> {
        let [ia, ib, _] = self.plane.indices();
        let [la, lb] = self.plane.axis_letters();
        let (a0, b0) = (self.cur[ia], self.cur[ib]);
        let radius = parsed.get('@');
        let angle = parsed.get('^');
        if self.absolute {
            let (a, b) = if radius.is_some() || angle.is_some() {
                let r = radius.map_or(b0.hypot(a0), |w| w.value);
                let t = angle.map_or(b0.atan2(a0), |w| w.value.to_radians());
                (r * t.cos(), r * t.sin())
            } else {
                (
                    parsed.get(la).map_or(a0, |w| w.value),
                    parsed.get(lb).map_or(b0, |w| w.value),
                )
            };
            let _ = line;
            return Ok((a, b, Steps::default()));
        }
        let steps = Steps {
            a: parsed.get(la).map_or(0.0, |w| w.value),
            b: parsed.get(lb).map_or(0.0, |w| w.value),
            radius: radius.map_or(0.0, |w| w.value),
            angle: angle.map_or(0.0, |w| w.value.to_radians()),
        };
        Ok((a0, b0, steps))
    }

    /// A straight move of a cycle to `(a, b, c)` in the plane frame, rapid or feed.
    fn cycle_move(
        &mut self,
        rapid: bool,
        levels: &Levels,
        a: f64,
        b: f64,
        c: f64,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let mut p: Pos = self.cur;
        let [ia, ib, ic] = levels.abc;
        p[ia] = a;
        p[ib] = b;
        p[ic] = c;
        let (kind, feed) = if rapid {
            (MotionKind::Rapid, None)
        } else {
            (MotionKind::Linear, Some(self.per_minute()))
        };
        self.emit_straight(kind, p, feed, line)
    }

    /// The moves of one hole, from R at `(a, b)`.
    fn cycle_body(
        &mut self,
        n: u8,
        l: &Levels,
        a: f64,
        b: f64,
        line: usize,
        column: usize,
    ) -> Result<(), Diagnostic> {
        let (feed, rapid) = (false, true);
        match n {
            81 | 82 | 86 => {
                self.cycle_move(feed, l, a, b, l.bottom, line)?;
                self.cycle_move(rapid, l, a, b, l.clear, line)?;
            }
            73 | 83 => self.pecks(n == 83, l, a, b, line, column)?,
            74 | 84 | 89 => {
                self.cycle_move(feed, l, a, b, l.bottom, line)?;
                self.cycle_move(feed, l, a, b, l.clear, line)?;
            }
            85 => {
                self.cycle_move(feed, l, a, b, l.bottom, line)?;
                self.cycle_move(feed, l, a, b, l.r, line)?;
                self.cycle_move(rapid, l, a, b, l.clear, line)?;
            }
            87 => {
                let [i, j, k] = self.cycle.ijk;
                let middle = if self.absolute { k } else { l.bottom + k };
                let (oa, ob) = (a + i, b + j);
                self.cycle_move(rapid, l, oa, ob, l.r, line)?;
                self.cycle_move(rapid, l, oa, ob, l.bottom, line)?;
                self.cycle_move(rapid, l, a, b, l.bottom, line)?;
                self.cycle_move(feed, l, a, b, middle, line)?;
                self.cycle_move(feed, l, a, b, l.bottom, line)?;
                self.cycle_move(rapid, l, oa, ob, l.bottom, line)?;
                self.cycle_move(rapid, l, oa, ob, l.clear, line)?;
                self.cycle_move(rapid, l, a, b, l.clear, line)?;
            }
            _ => {
                self.cycle_move(feed, l, a, b, l.bottom, line)?;
                self.warn(
                    line,
                    column,
                    "G88: the operator retracts the tool by hand; swarf simulates a rapid \
                     straight out to the clearance level",
                );
                self.cycle_move(rapid, l, a, b, l.clear, line)?;
            }
        }
        Ok(())
    }

    /// G83 (`full`: out to R after each peck) and G73 (a short back-off).
    fn pecks(
        &mut self,
        full: bool,
        l: &Levels,
        a: f64,
        b: f64,
        line: usize,
        column: usize,
    ) -> Result<(), Diagnostic> {
        let delta = self.cycle.q;
        let back = if self.inch {
            PECK_CLEARANCE_INCH
        } else {
            PECK_CLEARANCE_INCH * swarf_geom::units::MM_PER_INCH
        };
        if (l.r - l.bottom) / delta > MAX_CYCLE_STEPS as f64 {
            return Err(Diagnostic::new(
                line,
                column,
                format!(
                    "Q {delta} makes more than {MAX_CYCLE_STEPS} pecks over the {} of the hole",
                    l.r - l.bottom
                ),
            ));
        }
        let mut depth = l.r - delta;
        while depth > l.bottom {
            self.cycle_move(false, l, a, b, depth, line)?;
            if full {
                self.cycle_move(true, l, a, b, l.r, line)?;
            }
            self.cycle_move(true, l, a, b, depth + back, line)?;
            depth -= delta;
        }
        self.cycle_move(false, l, a, b, l.bottom, line)?;
        self.cycle_move(true, l, a, b, l.clear, line)
    }
}

/// The repeats of a cycle block (`L`, 1 without).
fn cycle_repeats(parsed: &Words, line: usize) -> Result<i64, Diagnostic> {
    let Some(l) = parsed.get('L') else {
        return Ok(1);
    };
    match integer(l.value) {
        Ok(0) => Err(Diagnostic::new(
            line,
            l.column,
            "cannot do zero repeats of a canned cycle (L0)",
        )),
        Ok(k) if (1..=MAX_CYCLE_STEPS).contains(&k) => Ok(k),
        _ => Err(Diagnostic::new(
            line,
            l.column,
            format!("L (repeats) must be a whole number from 1 to {MAX_CYCLE_STEPS}"),
        )),
    }
}

/// The steps between holes of an incremental cycle: in the plane, and polar.
#[derive(Debug, Clone, Copy, Default)]
struct Steps {
    a: f64,
    b: f64,
    radius: f64,
    angle: f64,
}

/// The next hole from `(a, b)`.
fn step_hole(a: f64, b: f64, s: &Steps) -> Result<(f64, f64), String> {
    let (mut a, mut b) = (a + s.a, b + s.b);
    for (radius, angle) in [(s.radius, 0.0), (0.0, s.angle)] {
        if radius == 0.0 && angle == 0.0 {
            continue;
        }
        if a == 0.0 && b == 0.0 {
            return Err(
                "incremental motion with polar coordinates is indeterminate at the origin".into(),
            );
        }
        let r = b.hypot(a) + radius;
        let t = b.atan2(a) + angle;
        (a, b) = (r * t.cos(), r * t.sin());
    }
    Ok((a, b))
}
