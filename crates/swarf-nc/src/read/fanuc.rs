//! The Fanuc macro B dialect (`--dialect fanuc`): variables, `IF`/`GOTO`/`WHILE`
//! statements, subprograms (`M98`, `M99`) and macro calls (`G65`), after Fanuc's
//! Custom Macro B.
//!
//! - Variables: `#1-#33` local to a macro call, `#100-#199` and `#500-#999` common;
//!   `#0` and every variable never set are *vacant* ([`crate::read::expr`]); an address
//!   given a vacant variable is left out of the block. System variables read here:
//!   `#4001-#4022` (modal G codes of groups 1-22 as far as swarf keeps them), `#4109`
//!   (F), `#4120` (T), `#5001-#5006` and `#5041-#5046` (the current position in work
//!   coordinates), `#5021-#5026` (machine coordinates), `#5201-#5326` (work offsets, as
//!   LinuxCNC numbers them); setting `#3000` raises the program's alarm, which stops
//!   the reading with the alarm number. Others are refused by number.
//! - `GOTO n`, `IF [c] GOTO n` (to the block numbered `Nn`), `IF [c] THEN #i = e`,
//!   `WHILE [c] DOm ... ENDm` and `DOm ... ENDm` (m = 1, 2, 3).
//! - `M98 P<n> [L<k>]` runs program `O<n>` (in this file, or `O<n>.nc` on the search
//!   path) k times, sharing the caller's locals; `M99` returns (to `N<p>` with `P`).
//! - `G65 P<n> [L<k>] <arguments>` calls macro `O<n>` with fresh locals: `A B C I J K D E
//!   F H M Q R S T U V W X Y Z` set `#1 #2 #3 #4 #5 #6 #7 #8 #9 #11 #13 #17 #18 #19 #20
//!   #21 #22 #23 #24 #25 #26`.

use crate::read::expr::integer;
use crate::read::flow::{Frame, MAX_CALL_DEPTH, Runner};
use crate::read::lexer::{Statement, lex_line};
use crate::read::modal::Flow;
use crate::read::statement::{FanucStatement, Label};
use crate::read::words::Word;
use std::collections::HashMap;
use swarf_toolpath::program::Diagnostic;

/// Fanuc's local variables: `#1` to `#33`.
const LOCALS: usize = 33;

/// G65 argument letters and the locals they set (argument specification I).
const G65_ARGUMENTS: [(char, usize); 21] = [
    ('A', 1),
    ('B', 2),
    ('C', 3),
    ('I', 4),
    ('J', 5),
    ('K', 6),
    ('D', 7),
    ('E', 8),
    ('F', 9),
    ('H', 11),
    ('M', 13),
    ('Q', 17),
    ('R', 18),
    ('S', 19),
    ('T', 20),
    ('U', 21),
    ('V', 22),
    ('W', 23),
    ('X', 24),
    ('Y', 25),
    ('Z', 26),
];

impl Runner<'_> {
    /// Reads variable `#index` in the Fanuc dialect.
    pub(crate) fn fanuc_read(&self, index: i64) -> Result<f64, String> {
        let m = &self.machine;
        let i = usize::try_from(index).map_err(|_| format!("variable #{index} does not exist"))?;
        let position = |k: usize| m.current()[k];
        Ok(match i {
            0 => f64::NAN,
            1..=33 | 100..=199 | 500..=999 => m.params.at(i),
            4001 => m.motion_code(),
            4002 => m.plane_code() / 10.0,
            4003 => {
                if m.absolute {
                    90.0
                } else {
                    91.0
                }
            }
            4005 => {
                if m.inverse_time {
                    93.0
                } else {
                    94.0
                }
            }
            4006 => {
                if m.inch {
                    20.0
                } else {
                    21.0
                }
            }
            4007 => m.comp_code() / 10.0,
            4010 => {
                if m.cycle.retract_to_r {
                    99.0
                } else {
                    98.0
                }
            }
            4014 => m.coord_system_code() / 10.0,
            4109 => m.feed / m.scale(),
            4120 => f64::from(m.tool_number().unwrap_or(0)),
            5001..=5006 => position(i - 5001),
            5041..=5046 => position(i - 5041),
            5021..=5026 => {
                let p = m.current();
                let machine = m.to_machine(&p);
                machine[i - 5021] / if i < 5024 { m.scale() } else { 1.0 }
            }
            5201..=5326 => m.params.at(i),
            _ => {
                return Err(format!(
                    "Fanuc system variable #{i} is not supported by swarf"
                ));
            }
        })
    }

    /// Sets variable `#index` in the Fanuc dialect.
    pub(crate) fn set_fanuc(
        &mut self,
        i: i64,
        value: f64,
        line: usize,
        column: usize,
    ) -> Result<(), Diagnostic> {
        match i {
            1..=33 | 100..=199 | 500..=999 | 5201..=5326 => {
                self.machine.params.set(i as usize, value);
                Ok(())
            }
            3000 => Err(self.error(
                line,
                column,
                format!("the program raised alarm #3000 = {value}"),
            )),
            0 => Err(self.error(line, column, "#0 is always vacant and cannot be set")),
            _ => Err(self.error(
                line,
                column,
                format!("Fanuc variable #{i} cannot be set by swarf"),
            )),
        }
    }

    /// A Fanuc macro statement on `line`.
    pub(crate) fn fanuc_statement(
        &mut self,
        s: FanucStatement,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let at = line - 1;
        match s {
            FanucStatement::Goto { condition, target } => {
                if let Some(c) = condition
                    && self.eval(&c)? == 0.0
                {
                    return Ok(());
                }
                let n = self.eval(&target)?;
                let n = integer(n).ok().filter(|n| *n >= 0).ok_or_else(|| {
                    self.error(line, 1, format!("GOTO {n}: expected a sequence number"))
                })?;
                let file = self.pc.0;
                match self.sources[file].numbered(n as u64) {
                    Some(i) => {
                        self.pc.1 = i;
                        Ok(())
                    }
                    None => {
                        Err(self.error(line, 1, format!("GOTO {n}: no block N{n} in this program")))
                    }
                }
            }
            FanucStatement::IfThen { condition, then } => {
                if self.eval(&condition)? != 0.0 {
                    let index = match &then.target {
                        crate::read::lexer::Target::Numbered(e) => Some(
                            integer(self.eval(e)?).map_err(|m| self.error(line, then.column, m))?,
                        ),
                        crate::read::lexer::Target::Named(_) => None,
                    };
                    let value = self.eval(&then.value)?;
                    self.assign(&then, (index, value), line)?;
                }
                Ok(())
            }
            FanucStatement::Do { condition, id } => {
                let label = Label::Number(u32::from(id));
                let holds = match condition {
                    Some(c) => self.eval(&c)? != 0.0,
                    None => true,
                };
                if holds {
                    return self.fanuc_loop(&label, at, line);
                }
                if self.frame().loops.last().is_some_and(|l| l.label == label) {
                    self.frame().loops.pop();
                }
                let end = self.fanuc_end(id, at).ok_or_else(|| {
                    self.error(line, 1, format!("WHILE ... DO{id} without END{id}"))
                })?;
                self.pc.1 = end + 1;
                Ok(())
            }
            FanucStatement::End(id) => {
                let label = Label::Number(u32::from(id));
                let start = self
                    .frame()
                    .loops
                    .iter()
                    .rev()
                    .find(|l| l.label == label)
                    .map(|l| l.start);
                match start {
                    Some(s) => {
                        self.pc.1 = s;
                        Ok(())
                    }
                    None => Err(self.error(line, 1, format!("END{id} without DO{id}"))),
                }
            }
        }
    }

    fn fanuc_loop(&mut self, label: &Label, at: usize, line: usize) -> Result<(), Diagnostic> {
        let limit = self.opts.limits.loop_iterations;
        let frame = self.frame();
        match frame
            .loops
            .iter_mut()
            .rev()
            .find(|l| l.label == *label && l.start == at)
        {
            Some(ctx) => {
                ctx.turns += 1;
                if ctx.turns > limit {
                    return Err(self.error(
                        line,
                        1,
                        format!("loop DO{label} turned more than {limit} times: stopped here"),
                    ));
                }
            }
            None => frame.loops.push(crate::read::flow::LoopCtx {
                label: label.clone(),
                start: at,
                turns: 0,
            }),
        }
        Ok(())
    }

    /// The line index of the `ENDm` closing the loop at `at`.
    fn fanuc_end(&self, id: u8, at: usize) -> Option<usize> {
        let source = &self.sources[self.pc.0];
        (at + 1..source.line_count()).find(|&i| {
            source.line(i).is_some_and(|text| {
                matches!(
                    lex_line(text, i + 1, self.syntax()).map(|l| l.statement),
                    Ok(Statement::Fanuc(FanucStatement::End(m))) if m == id
                )
            })
        })
    }

    /// A block in the Fanuc dialect: M98, M99 and G65 are taken out and run after the
    /// rest of the block.
    pub(crate) fn fanuc_block(
        &mut self,
        block: Vec<Word>,
        line: usize,
    ) -> Result<Flow, Diagnostic> {
        let code =
            |w: &Word, letter: char, n: f64| w.letter == letter && (w.value - n).abs() < 1e-9;
        if let Some(g65) = block.iter().find(|w| code(w, 'G', 65.0)).copied() {
            return self.macro_call(&block, g65, line);
        }
        let m98 = block.iter().find(|w| code(w, 'M', 98.0)).copied();
        let m99 = block.iter().find(|w| code(w, 'M', 99.0)).copied();
        let (p, l) = (
            block.iter().find(|w| w.letter == 'P').copied(),
            block.iter().find(|w| w.letter == 'L').copied(),
        );
        if m98.is_none() && m99.is_none() {
            return self.execute(&block, line);
        }
        let rest: Vec<Word> = block
            .into_iter()
            .filter(|w| {
                !(code(w, 'M', 98.0) || code(w, 'M', 99.0) || w.letter == 'P' || w.letter == 'L')
            })
            .collect();
        if !rest.is_empty() && self.execute(&rest, line)? == Flow::End {
            return Ok(Flow::End);
        }
        if let Some(m) = m98 {
            let Some(p) = p else {
                return Err(self.error(line, m.column, "M98 without P (the subprogram number)"));
            };
            self.subprogram_call(p, l, None, line)?;
            return Ok(Flow::Continue);
        }
        self.subprogram_return(p, line)
    }

    /// G65 P.. L.. with its arguments.
    fn macro_call(&mut self, block: &[Word], g65: Word, line: usize) -> Result<Flow, Diagnostic> {
        let Some(p) = block.iter().find(|w| w.letter == 'P').copied() else {
            return Err(self.error(line, g65.column, "G65 without P (the macro program number)"));
        };
        let l = block.iter().find(|w| w.letter == 'L').copied();
        let mut locals = vec![f64::NAN; LOCALS];
        for w in block {
            if w.letter == 'G' && (w.value - 65.0).abs() < 1e-9 || matches!(w.letter, 'P' | 'L') {
                continue;
            }
            match G65_ARGUMENTS.iter().find(|(l, _)| *l == w.letter) {
                Some(&(_, k)) => locals[k - 1] = w.value,
                None => {
                    return Err(self.error(
                        line,
                        w.column,
                        format!("{} is not a G65 argument", w.letter),
                    ));
                }
            }
        }
        self.subprogram_call(p, l, Some(locals), line)?;
        Ok(Flow::Continue)
    }

    /// Enters program `O<p>`, `l` times; `locals`: a G65 call's fresh locals.
    fn subprogram_call(
        &mut self,
        p: Word,
        l: Option<Word>,
        locals: Option<Vec<f64>>,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let n = integer(p.value)
            .ok()
            .filter(|n| (0..=i64::from(u32::MAX)).contains(n))
            .ok_or_else(|| self.error(line, p.column, "P: expected a program number"))?
            as u32;
        let turns = match l {
            None => 1,
            Some(l) => integer(l.value)
                .ok()
                .filter(|k| *k >= 1 && (*k as u64) <= self.opts.limits.loop_iterations)
                .ok_or_else(|| {
                    self.error(line, l.column, "L: expected a repeat count of 1 or more")
                })? as u64,
        };
        if self.frames.len() > MAX_CALL_DEPTH {
            return Err(self.error(
                line,
                p.column,
                format!(
                    "too many nested levels of subprograms: at most {MAX_CALL_DEPTH} calls deep"
                ),
            ));
        }
        let (file, start) = self.find_program(n, line, p.column)?;
        let saved = match &locals {
            Some(_) => (1..=LOCALS).map(|i| self.machine.params.at(i)).collect(),
            None => Vec::new(),
        };
        if let Some(values) = locals {
            for (k, v) in values.into_iter().enumerate() {
                self.machine.params.set(k + 1, v);
            }
        }
        self.frames.push(Frame {
            return_to: self.pc,
            saved,
            named: HashMap::new(),
            loops: Vec::new(),
            repeat: Some((turns, start)),
            label: Some(Label::Number(n)),
        });
        self.pc = (file, start);
        Ok(())
    }

    /// The first line of program `O<n>` (after its `O` line): in this file, the
    /// program's, or a file `O<n>.nc` on the search path.
    fn find_program(
        &mut self,
        n: u32,
        line: usize,
        column: usize,
    ) -> Result<(usize, usize), Diagnostic> {
        let here = self.pc.0;
        for file in [here, 0] {
            if let Some(i) = self.sources[file].program(n) {
                return Ok((file, i + 1));
            }
        }
        for name in [
            format!("O{n:04}.nc"),
            format!("O{n}.nc"),
            format!("o{n}.ngc"),
            format!("{n}.nc"),
        ] {
            if let Some(file) = self.load_file(&name, line)? {
                let first = self.sources[file].program(n).map_or(0, |i| i + 1);
                return Ok((file, first));
            }
        }
        Err(self.error(
            line,
            column,
            format!("program O{n} not found in this file nor as O{n:04}.nc on the search path"),
        ))
    }

    /// M99 (`p`: return to the block numbered P).
    fn subprogram_return(&mut self, p: Option<Word>, line: usize) -> Result<Flow, Diagnostic> {
        if self.frames.len() < 2 {
            self.machine.warn(
                line,
                1,
                "M99 in the main program: the control would run it again from the start; swarf \
                 stops here",
            );
            return Ok(Flow::End);
        }
        let frame = self.frame();
        if let Some((turns, start)) = frame.repeat.as_mut()
            && *turns > 1
        {
            *turns -= 1;
            let start = *start;
            frame.loops.clear();
            self.pc.1 = start;
            return Ok(Flow::Continue);
        }
        let frame = self.frames.pop().expect("checked above");
        for (k, v) in frame.saved.iter().enumerate() {
            self.machine.params.set(k + 1, *v);
        }
        self.pc = frame.return_to;
        if let Some(p) = p {
            let n = integer(p.value).unwrap_or(-1);
            let file = self.pc.0;
            match u64::try_from(n)
                .ok()
                .and_then(|n| self.sources[file].numbered(n))
            {
                Some(i) => self.pc.1 = i,
                None => {
                    return Err(self.error(
                        line,
                        p.column,
                        format!("M99 P{n}: no block N{n} in the caller"),
                    ));
                }
            }
        }
        Ok(Flow::Continue)
    }
}
