//! Running a program's lines: the line loop around the lexer, parameters and their
//! settings, O-word control flow and subroutines ([`crate::read::oword`]), the Fanuc
//! dialect's macro statements ([`crate::read::fanuc`]), and the modal machine
//! ([`crate::read::modal`]) for the blocks' words.
//!
//! As LinuxCNC reads a line: every value on it is read with the parameters as they
//! were before the line (`#1 = 2 #2 = #1` sets `#2` to the old `#1`); the settings then
//! take effect, and the block runs. Lines are read when they run, so a loop runs its
//! lines again, and text skipped by a false `if` or a subroutine definition is not
//! read beyond its O words.
//!
//! Every loop stops at [`FlowLimits::loop_iterations`] turns and the program at
//! [`FlowLimits::blocks`] lines run beyond its own, with an error naming the line, so that a loop
//! that never ends is a refusal, not a hang; calls nest at most
//! [`MAX_CALL_DEPTH`] deep (LinuxCNC's limit).

use crate::read::expr::{Expr, ParamSource, integer};
use crate::read::lexer::{Assignment, Line, Statement, Syntax, Target, lex_line};
use crate::read::modal::{Flow, Interpreter};
use crate::read::oword::OState;
use crate::read::params::{PARAMETER_COUNT, is_read_only};
use crate::read::program::Diagnostic;
use crate::read::source::Source;
use crate::read::statement::Label;
use crate::read::words::Word;
use std::collections::HashMap;
use std::path::PathBuf;

/// Calls nest at most this deep below the program (LinuxCNC's
/// `INTERP_SUB_ROUTINE_LEVELS` is 10 levels, the program being the first).
pub const MAX_CALL_DEPTH: usize = 9;

/// Bounds on the work a program may ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FlowLimits {
    /// Most turns of one loop (while, do, repeat, Fanuc WHILE/DO, M98 L, G65 L).
    pub loop_iterations: u64,
    /// Most lines run beyond the program's own line count: a straight program of any
    /// length runs, loops and calls may add this many lines.
    pub blocks: u64,
}

impl Default for FlowLimits {
    /// One million turns per loop, 20 million lines beyond the program's own (an
    /// endless loop stops in seconds; LinuxCNC's example programs turn at most a few
    /// thousand times).
    fn default() -> Self {
        FlowLimits {
            loop_iterations: 1_000_000,
            blocks: 20_000_000,
        }
    }
}

/// What the runner needs besides the program text.
#[derive(Debug, Clone, Default)]
pub struct FlowOptions {
    /// Directories searched, in order, for `o<name> call` subroutine files
    /// (`name.ngc`) and Fanuc subprograms (`O1234.nc`); the program's own directory is
    /// searched last.
    pub sub_path: Vec<PathBuf>,
    /// The program's directory, if it came from a file.
    pub program_dir: Option<PathBuf>,
    /// Fanuc macro B dialect.
    pub fanuc: bool,
    /// The block delete switch.
    pub block_delete: bool,
    /// Work bounds.
    pub limits: FlowLimits,
}

/// A Fanuc `WHILE`/`DO` loop in progress.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LoopCtx {
    /// The DO number as `Label::Number`.
    pub label: Label,
    /// The line index of its head (`WHILE`, `DO`).
    pub start: usize,
    /// Turns so far.
    pub turns: u64,
}

/// One call level.
#[derive(Debug, Clone)]
pub(crate) struct Frame {
    /// Where to go on return: (source, line index).
    pub return_to: (usize, usize),
    /// The caller's `#1`.. (restored on return).
    pub saved: Vec<f64>,
    /// Local named parameters.
    pub named: HashMap<Box<str>, f64>,
    /// Fanuc loops in progress in this frame.
    pub loops: Vec<LoopCtx>,
    /// Fanuc M98/G65 with L: (turns left, line index of the subprogram's first line).
    pub repeat: Option<(u64, usize)>,
    /// The label of the subroutine (None for the program).
    pub label: Option<Label>,
}

/// The runner: sources, call stack, position, and the machine.
pub(crate) struct Runner<'k> {
    pub machine: Interpreter<'k>,
    pub sources: Vec<Source>,
    pub frames: Vec<Frame>,
    pub opts: FlowOptions,
    /// (source, line index) of the next line.
    pub pc: (usize, usize),
    pub messages: Vec<Diagnostic>,
    /// The O-word flow's skipping state.
    pub(crate) o: OState,
    blocks: u64,
    /// The value of the last `return`/`endsub` (`#<_value>`), and whether one was given.
    pub value: (f64, bool),
}

/// How a run ended.
pub(crate) enum End {
    /// M2/M30 or the closing `%`, at this line (1-based, of the program).
    Ended(&'static str),
    /// The end of the text.
    Eof,
}

impl<'k> Runner<'k> {
    pub fn new(machine: Interpreter<'k>, main: Source, opts: FlowOptions) -> Self {
        let mut machine = machine;
        if opts.fanuc {
            for i in (1..=33).chain(100..=199) {
                machine.params.set(i, f64::NAN);
            }
        }
        Runner {
            machine,
            sources: vec![main],
            frames: vec![Frame {
                return_to: (0, 0),
                saved: Vec::new(),
                named: HashMap::new(),
                loops: Vec::new(),
                repeat: None,
                label: None,
            }],
            opts,
            pc: (0, 0),
            messages: Vec::new(),
            o: OState::default(),
            blocks: 0,
            value: (0.0, false),
        }
    }

    pub fn syntax(&self) -> Syntax {
        Syntax {
            fanuc: self.opts.fanuc,
        }
    }

    /// The frame in force.
    pub fn frame(&mut self) -> &mut Frame {
        let last = self.frames.len() - 1;
        &mut self.frames[last]
    }

    /// The line of the program (source 0) motions of the current line are attributed
    /// to: the line itself in the program, else the outermost call in the program.
    fn program_line(&self, line: usize) -> usize {
        if self.pc.0 == 0 {
            return line;
        }
        self.frames
            .iter()
            .skip(1)
            .find(|f| f.return_to.0 == 0)
            .map_or(line, |f| f.return_to.1)
    }

    /// An error at `line` (1-based) of the current source.
    pub fn error(&self, line: usize, column: usize, message: impl Into<String>) -> Diagnostic {
        let d = Diagnostic::new(line, column, message);
        if self.pc.0 == 0 {
            d
        } else {
            d.in_file(self.sources[self.pc.0].name.clone())
        }
    }

    /// Places a diagnostic from the lexer or the machine in the current source.
    pub fn place(&self, d: Diagnostic) -> Diagnostic {
        if self.pc.0 == 0 || d.file.is_some() {
            d
        } else {
            d.in_file(self.sources[self.pc.0].name.clone())
        }
    }

    /// Runs lines until the program ends or an error stops it.
    pub fn run(&mut self) -> Result<End, Diagnostic> {
        let mut started = false;
        loop {
            let (file, index) = self.pc;
            let Some(text) = self.sources[file].line(index) else {
                if self.o.skipping() {
                    return Err(self.eof_while_skipping());
                }
                if self.frames.len() > 1 {
                    let label = self.frames.last().and_then(|f| f.label.clone());
                    let name = label.map_or_else(String::new, |l| format!(" {l}"));
                    return Err(self.error(
                        self.sources[file].line_count().max(1),
                        1,
                        format!("end of file in subroutine{name}: endsub or M99 missing"),
                    ));
                }
                return Ok(End::Eof);
            };
            let line = index + 1;
            self.pc.1 += 1;
            self.blocks += 1;
            let own = self.sources[0].line_count() as u64;
            if self.blocks > own.saturating_add(self.opts.limits.blocks) {
                return Err(self.error(
                    line,
                    1,
                    format!(
                        "the program runs more than {} lines beyond its own {own}: stopped \
                         here (a loop that never ends?)",
                        self.opts.limits.blocks
                    ),
                ));
            }
            if self.o.skipping() {
                if let Some(c) = o_word_line(text, line, self.syntax()) {
                    self.control(c, line)?;
                }
                continue;
            }
            let lexed = lex_line(text, line, self.syntax()).map_err(|d| self.place(d))?;
            if lexed.percent {
                if started && file == 0 {
                    return Ok(End::Ended("the closing %"));
                }
                started = true;
                continue;
            }
            if lexed.is_empty() {
                self.comments(&lexed, line);
                continue;
            }
            started = true;
            if lexed.block_delete && self.block_delete(line) {
                continue;
            }
            if self.step(lexed, line)? == Flow::End {
                return Ok(End::Ended("M2/M30"));
            }
        }
    }

    /// Whether a block delete (`/`) line is skipped; the first such line warns which
    /// way the switch is.
    fn block_delete(&mut self, line: usize) -> bool {
        let what = if self.opts.block_delete {
            "block delete (/) lines are skipped: the block delete switch is on"
        } else {
            "block delete (/) lines run: the block delete switch is off, as LinuxCNC starts"
        };
        if !self.machine.warnings.has(what) {
            self.machine.warn(line, 1, what);
        }
        self.opts.block_delete
    }

    /// Runs one lexed line.
    fn step(&mut self, lexed: Line, line: usize) -> Result<Flow, Diagnostic> {
        match lexed.statement {
            Statement::Empty => Ok(Flow::Continue),
            Statement::ProgramNumber(n, column) => {
                self.machine.fanuc = true;
                self.program_number(n, line, column)
            }
            Statement::Control(c) => {
                self.control(c, line)?;
                Ok(Flow::Continue)
            }
            Statement::Fanuc(s) => {
                self.fanuc_statement(s, line)?;
                Ok(Flow::Continue)
            }
            Statement::Words { words, assignments } => {
                let mut block = Vec::with_capacity(words.len());
                for w in &words {
                    let value = self.eval(&w.value)?;
                    if value.is_nan() {
                        continue;
                    }
                    block.push(Word {
                        letter: w.letter,
                        value,
                        has_point: w.has_point,
                        column: w.column,
                    });
                }
                let values = assignments
                    .iter()
                    .map(|a| self.assignment_value(a))
                    .collect::<Result<Vec<_>, _>>()?;
                for (a, v) in assignments.iter().zip(values) {
                    self.assign(a, v, line)?;
                }
                self.comments(&lexed_comments(lexed.comments), line);
                if self.opts.fanuc {
                    return self.fanuc_block(block, line);
                }
                self.execute(&block, line)
            }
        }
    }

    /// Runs a block of evaluated words on the machine.
    pub fn execute(&mut self, block: &[Word], line: usize) -> Result<Flow, Diagnostic> {
        let attributed = self.program_line(line);
        let before = self.machine.motions.len();
        let flow = self
            .machine
            .execute(block, line)
            .map_err(|d| self.place(d))?;
        if attributed != line {
            for m in &mut self.machine.motions[before..] {
                m.line = attributed;
            }
        }
        Ok(flow)
    }

    /// The value of an expression with the parameters as they are now.
    pub fn eval(&self, e: &Expr) -> Result<f64, Diagnostic> {
        let scope = Scope { runner: self };
        e.eval(&scope).map_err(|err| {
            let line = self.pc.1;
            self.error(line, err.column, err.message)
        })
    }

    /// The value a setting gives (read before any setting of the line takes effect).
    fn assignment_value(&self, a: &Assignment) -> Result<(Option<i64>, f64), Diagnostic> {
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

    /// `(MSG, ...)`, `(DEBUG, ...)` and `(PRINT, ...)` comments become messages.
    fn comments(&mut self, lexed: &Line, line: usize) {
        for c in &lexed.comments {
            let lower = c.trim_start().to_ascii_lowercase();
            let Some((kind, rest)) = lower.split_once(',') else {
                continue;
            };
            let body = &c.trim_start()[kind.len() + 1..];
            let text = match kind.trim() {
                "msg" => body.to_string(),
                "debug" | "print" => self.expand(body),
                _ => continue,
            };
            let _ = rest;
            let d = self.error(line, 1, text);
            self.messages.push(d);
        }
    }

    /// `#n` and `#<name>` in a comment replaced by their values, as LinuxCNC's
    /// `convert_param_comment` writes them: six decimals, or as set by a preceding
    /// `%d` (none), `%f` (four) or `%.Nf` (N); `######` for an unknown parameter.
    fn expand(&self, body: &str) -> String {
        let scope = Scope { runner: self };
        let chars: Vec<char> = body.chars().collect();
        let mut out = String::new();
        let mut decimals = 6;
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            i += 1;
            match c {
                '%' => match (chars.get(i), chars.get(i + 1), chars.get(i + 2)) {
                    (Some('d'), _, _) => (decimals, i) = (0, i + 1),
                    (Some('f'), _, _) => (decimals, i) = (4, i + 1),
                    (Some('.'), Some(d), Some('f')) if d.is_ascii_digit() => {
                        (decimals, i) = (d.to_digit(10).unwrap_or(6) as usize, i + 3);
                    }
                    _ => out.push('%'),
                },
                '#' => {
                    let value = if chars.get(i) == Some(&'<') {
                        let close = chars[i..].iter().position(|&c| c == '>');
                        let name: String = chars[i + 1..i + close.unwrap_or(1)]
                            .iter()
                            .filter(|c| !c.is_whitespace())
                            .map(|c| c.to_ascii_lowercase())
                            .collect();
                        i += close.map_or(chars.len(), |k| k + 1);
                        scope.named(&name).ok()
                    } else {
                        let digits: String = chars[i..]
                            .iter()
                            .take_while(|c| c.is_ascii_digit())
                            .collect();
                        if digits.is_empty() {
                            out.push('#');
                            continue;
                        }
                        i += digits.len();
                        digits
                            .parse::<i64>()
                            .ok()
                            .and_then(|n| scope.numbered(n).ok())
                    };
                    match value {
                        Some(v) => {
                            let v = if v.abs() < crate::read::expr::TOLERANCE_EQUAL {
                                0.0
                            } else {
                                v
                            };
                            out.push_str(&format!("{v:.decimals$}"));
                        }
                        None => out.push_str("######"),
                    }
                }
                c => out.push(c),
            }
        }
        out
    }

    /// An `O1234` line: the Fanuc program number (it starts a subprogram that M98
    /// calls; in the program's flow it is only a label).
    fn program_number(
        &mut self,
        _n: u32,
        _line: usize,
        _column: usize,
    ) -> Result<Flow, Diagnostic> {
        Ok(Flow::Continue)
    }
}

/// The O-word statement of a line, when it holds one and lexes (lines skipped past
/// are read for their O words only).
fn o_word_line(text: &str, line: usize, syntax: Syntax) -> Option<crate::read::statement::Control> {
    let head = text.chars().find(|c| !matches!(c, ' ' | '\t' | '/'))?;
    if !matches!(head, 'o' | 'O' | 'n' | 'N') {
        return None;
    }
    match lex_line(text, line, syntax).ok()?.statement {
        Statement::Control(c) => Some(c),
        _ => None,
    }
}

/// A line holding only the comments of another (for [`Runner::comments`]).
fn lexed_comments(comments: Vec<String>) -> Line {
    Line {
        comments,
        ..Line::default()
    }
}

/// Parameters as a line's expressions see them.
struct Scope<'r, 'k> {
    runner: &'r Runner<'k>,
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
