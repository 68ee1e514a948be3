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
//!
//! Parameters as a line's expressions and settings see them are in `scope`; the
//! messages of `(MSG, ...)`, `(DEBUG, ...)` and `(PRINT, ...)` comments in `comments`.

use crate::read::lexer::{Line, Statement, Syntax, lex_line};
use crate::read::modal::{Flow, Interpreter};
use crate::read::oword::OState;
use crate::read::source::Source;
use crate::read::statement::Label;
use crate::read::words::Word;
use std::collections::HashMap;
use std::path::PathBuf;
use swarf_toolpath::program::Diagnostic;

mod comments;
mod scope;

use comments::lexed_comments;

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
