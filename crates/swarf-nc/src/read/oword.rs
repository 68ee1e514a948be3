//! LinuxCNC's O-word control flow (`interp_o_word.cc`, `read_o` in `interp_read.cc`),
//! run the way LinuxCNC runs it: by *skipping* lines until one with a given label,
//! and by jumping back to a label's line, with its flags (`executed_if`,
//! `doing_break`, `doing_continue`) and its table of labels, so that programs behave
//! exactly as under LinuxCNC, corner cases included (a `break` met while skipping for a
//! `continue` ends the loop, as it does there).
//!
//! - `sub ... endsub` met by the flow at the program's level is defined and skipped;
//!   `call [a] [b] ...` sets `#1-#30` to the arguments (missing ones 0), keeps the
//!   caller's to restore on return, and goes to the subroutine: defined before; else
//!   in a file `name.ngc` on the search path; else ahead in the current file. A
//!   subroutine found ahead must not be met by the flow later ("found in illegal
//!   location"); a label is defined once. `return [v]` and `endsub [v]` set
//!   `#<_value>` and `#<_value_returned>`. Named parameters without `_` are local to a
//!   call. Calls nest [`MAX_CALL_DEPTH`] deep.
//! - `while [c] ... endwhile`, `do ... while [c]`, `repeat [n] ... endrepeat` (n
//!   rounded), `break` and `continue` (in while and do loops), `if [c] ... elseif [c]
//!   ... else ... endif`. A condition is read only when its line is not being skipped
//!   past.
//! - One label, one line: a loop or `if` label used again on another line is refused,
//!   as LinuxCNC refuses it.

use crate::read::flow::{Frame, MAX_CALL_DEPTH, Runner};
use crate::read::source::Source;
use crate::read::statement::{Control, Keyword, Label};
use std::collections::HashMap;
use swarf_toolpath::program::Diagnostic;

/// Subroutine arguments: `#1` to `#30`.
pub const SUB_PARAMETERS: usize = 30;

/// Where a label was met (LinuxCNC's `offset_map`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LabelSite {
    /// The statement that defined it (sub, do, while, repeat, if).
    pub kind: Keyword,
    /// Source and line index.
    pub file: usize,
    /// Line index.
    pub line: usize,
    /// Turns left of a repeat loop (-1: not counting).
    pub repeat: i64,
    /// Jumps back to it so far.
    pub turns: u64,
}

/// The skipping state of the O-word flow.
#[derive(Debug, Clone, Default)]
pub(crate) struct OState {
    /// Skipping lines until one with this label.
    pub skipping: Option<Label>,
    /// Skipping until this subroutine's `sub` line.
    pub skipping_to_sub: Option<Label>,
    /// The line the skipping started at (1-based), for messages.
    pub skipping_from: usize,
    /// A branch of the current `if` ran.
    pub executed_if: bool,
    /// A `break` is being carried out.
    pub doing_break: bool,
    /// A `continue` is being carried out.
    pub doing_continue: bool,
    /// The last condition read.
    pub test: f64,
    /// A subroutine is being defined (skipped) at the program's level.
    pub defining_sub: bool,
    /// The subroutine being defined or run.
    pub sub_name: Option<Label>,
    /// Labels met so far.
    pub sites: HashMap<Label, LabelSite>,
}

impl OState {
    /// Whether lines are being skipped.
    pub fn skipping(&self) -> bool {
        self.skipping.is_some() || self.skipping_to_sub.is_some()
    }
}

impl Runner<'_> {
    /// Reads and runs an O-word statement on `line` (1-based) of the current source.
    pub(crate) fn control(&mut self, mut c: Control, line: usize) -> Result<(), Diagnostic> {
        let scoped = !matches!(
            c.keyword,
            Keyword::Sub | Keyword::EndSub | Keyword::Call | Keyword::Return
        );
        let scope = if self.frames.len() > 1 {
            self.frames.last().and_then(|f| f.label.clone())
        } else if self.o.defining_sub {
            self.o.sub_name.clone()
        } else {
            None
        };
        if let (true, Some(sub)) = (scoped, scope) {
            c.label = Label::Scoped(Box::new(sub), Box::new(c.label));
        }
        if !self.read_o(&c, line)? {
            return Ok(());
        }
        let o = &self.o;
        if o.skipping.as_ref().is_some_and(|s| *s != c.label) {
            return Ok(());
        }
        if o.skipping_to_sub.is_some() && c.keyword != Keyword::Sub {
            return Ok(());
        }
        let at = line - 1;
        match c.keyword {
            Keyword::Sub => self.sub_line(&c, at, line),
            Keyword::EndSub | Keyword::Return => self.sub_return(&c, line),
            Keyword::Call => self.call(&c, line),
            Keyword::Do => {
                self.o.skipping = None;
                if !self.o.sites.contains_key(&c.label) {
                    self.save_site(&c, at, line)?;
                }
                Ok(())
            }
            Keyword::While => self.while_line(&c, at, line),
            Keyword::Repeat => self.repeat_line(&c, at, line),
            Keyword::If | Keyword::ElseIf | Keyword::Else | Keyword::EndIf => {
                self.if_line(&c, at, line)
            }
            Keyword::Break => {
                self.expect_site(&c, &[Keyword::While, Keyword::Do], line)?;
                self.skip_to(&c.label, line);
                self.o.doing_break = true;
                Ok(())
            }
            Keyword::Continue => {
                self.expect_site(&c, &[Keyword::While, Keyword::Do], line)?;
                if self.o.skipping.as_ref() != Some(&c.label) {
                    self.skip_to(&c.label, line);
                    self.o.doing_continue = true;
                }
                Ok(())
            }
            Keyword::EndWhile | Keyword::EndRepeat => self.loop_end(&c, line),
        }
    }

    /// `if`, `elseif`, `else`, `endif`.
    fn if_line(&mut self, c: &Control, at: usize, line: usize) -> Result<(), Diagnostic> {
        if c.keyword == Keyword::If {
            self.check_or_save(c, at, line)?;
            if self.o.test != 0.0 {
                self.o.skipping = None;
                self.o.executed_if = true;
            } else {
                self.skip_to(&c.label, line);
                self.o.executed_if = false;
            }
            return Ok(());
        }
        self.expect_site(c, &[Keyword::If], line)?;
        match c.keyword {
            Keyword::EndIf => {
                self.o.skipping = None;
                self.o.executed_if = true;
            }
            _ if self.o.executed_if => self.skip_to(&c.label, line),
            Keyword::ElseIf if self.o.test != 0.0 => {
                self.o.skipping = None;
                self.o.executed_if = true;
            }
            Keyword::Else if self.o.skipping.as_ref() == Some(&c.label) => {
                self.o.executed_if = true;
                self.o.skipping = None;
            }
            _ => {}
        }
        Ok(())
    }

    /// `endwhile`, `endrepeat`: back to the head, unless a break ends the loop.
    fn loop_end(&mut self, c: &Control, line: usize) -> Result<(), Diagnostic> {
        let head = if c.keyword == Keyword::EndWhile {
            Keyword::While
        } else {
            Keyword::Repeat
        };
        self.expect_site(c, &[head], line)?;
        if self.o.skipping.as_ref() == Some(&c.label) {
            self.o.skipping = None;
            if !self.o.doing_continue {
                return Ok(());
            }
            self.o.doing_continue = false;
        }
        self.back_to(&c.label, line)
    }

    /// LinuxCNC's `read_o`: reads the statement's values where LinuxCNC reads them
    /// (not while skipping past another label, nor inside a definition); `false` when
    /// the statement does nothing.
    fn read_o(&mut self, c: &Control, line: usize) -> Result<bool, Diagnostic> {
        let other = self.o.skipping.as_ref().is_some_and(|s| *s != c.label);
        match c.keyword {
            Keyword::Sub => {
                if self.o.defining_sub {
                    return Err(self.error(line, c.column, "nested subroutine definition"));
                }
                Ok(true)
            }
            Keyword::EndSub | Keyword::Return => {
                if other {
                    return Ok(false);
                }
                self.value = match c.args.first() {
                    Some(e) => (self.eval(e)?, true),
                    None => (0.0, false),
                };
                Ok(true)
            }
            _ if self.o.defining_sub => Ok(false),
            Keyword::Call => Ok(!self.o.skipping()),
            Keyword::While | Keyword::Repeat | Keyword::If | Keyword::ElseIf => {
                if other {
                    return Ok(false);
                }
                self.o.test = self.eval(&c.args[0])?;
                Ok(true)
            }
            _ => Ok(true),
        }
    }

    fn skip_to(&mut self, label: &Label, line: usize) {
        self.o.skipping = Some(label.clone());
        self.o.skipping_from = line;
    }

    /// Records where `c.label` is (`control_save_offset`): a label already met on its
    /// own line again was reached out of order; on another line it is a second use.
    fn save_site(&mut self, c: &Control, at: usize, line: usize) -> Result<(), Diagnostic> {
        let file = self.pc.0;
        if let Some(site) = self.o.sites.get(&c.label) {
            let message = if site.line == at {
                format!(
                    "sub {} found in illegal location: it was called before the flow reached it",
                    c.label
                )
            } else {
                format!(
                    "redefining {}: already defined in {} line {}",
                    c.label,
                    self.sources[site.file].name,
                    site.line + 1
                )
            };
            return Err(self.error(line, c.column, message));
        }
        self.o.sites.insert(
            c.label.clone(),
            LabelSite {
                kind: c.keyword,
                file,
                line: at,
                repeat: -1,
                turns: 0,
            },
        );
        Ok(())
    }

    /// A loop or `if` head: its label must not have been used on another line.
    fn check_or_save(&mut self, c: &Control, at: usize, line: usize) -> Result<(), Diagnostic> {
        match self.o.sites.get(&c.label) {
            Some(site)
                if site.line != at
                    && !(c.keyword == Keyword::While && site.kind == Keyword::Do) =>
            {
                Err(self.error(
                    line,
                    c.column,
                    format!(
                        "duplicate O-word label {}: already used on line {}",
                        c.label,
                        site.line + 1
                    ),
                ))
            }
            Some(_) => Ok(()),
            None => self.save_site(c, at, line),
        }
    }

    /// The label's site, which must be one of `kinds`.
    fn expect_site(
        &self,
        c: &Control,
        kinds: &[Keyword],
        line: usize,
    ) -> Result<LabelSite, Diagnostic> {
        match self.o.sites.get(&c.label) {
            None => Err(self.error(
                line,
                c.column,
                format!("undefined O-word label {}", c.label),
            )),
            Some(site) if !kinds.contains(&site.kind) => Err(self.error(
                line,
                c.column,
                format!(
                    "no matching label for '{} {}' (found '{}' on line {})",
                    c.label,
                    c.keyword.name(),
                    site.kind.name(),
                    site.line + 1
                ),
            )),
            Some(site) => Ok(*site),
        }
    }

    /// Goes back to the line of `label` (a loop's head), counting the turn.
    fn back_to(&mut self, label: &Label, line: usize) -> Result<(), Diagnostic> {
        let limit = self.opts.limits.loop_iterations;
        let Some(site) = self.o.sites.get_mut(label) else {
            return Err(self.error(line, 1, format!("undefined O-word label {label}")));
        };
        site.turns += 1;
        if site.turns > limit {
            return Err(self.error(
                line,
                1,
                format!("loop {label} turned more than {limit} times: stopped here (a loop that never ends?)"),
            ));
        }
        self.pc = (site.file, site.line);
        Ok(())
    }

    /// `while [c]`: the head of a while loop, or the end of a do loop.
    fn while_line(&mut self, c: &Control, at: usize, line: usize) -> Result<(), Diagnostic> {
        self.check_or_save(c, at, line)?;
        self.o.skipping = None;
        let kind = self
            .o
            .sites
            .get(&c.label)
            .map_or(Keyword::While, |s| s.kind);
        if kind == Keyword::While {
            if self.o.test == 0.0 {
                self.skip_to(&c.label, line);
            }
            return Ok(());
        }
        if self.o.test != 0.0 && !self.o.doing_break {
            return self.back_to(&c.label, line);
        }
        self.o.doing_break = false;
        Ok(())
    }

    /// `repeat [n]`: counts its turns from the count read when the loop starts.
    fn repeat_line(&mut self, c: &Control, at: usize, line: usize) -> Result<(), Diagnostic> {
        self.check_or_save(c, at, line)?;
        self.o.skipping = None;
        let test = self.o.test;
        let Some(site) = self.o.sites.get_mut(&c.label) else {
            return Ok(());
        };
        if site.kind != Keyword::Repeat {
            return Ok(());
        }
        if site.repeat == -1 {
            site.repeat = round_to_int(test);
        }
        if site.repeat > 0 {
            site.repeat -= 1;
        } else {
            site.repeat = -1;
            self.skip_to(&c.label, line);
        }
        Ok(())
    }

    /// A `sub` line: the end of the search for a called subroutine, the start of a
    /// call, or (at the program's level) a definition to skip.
    fn sub_line(&mut self, c: &Control, at: usize, line: usize) -> Result<(), Diagnostic> {
        if self.o.skipping.is_some() {
            self.save_site(c, at, line)?;
            self.o.skipping = None;
        }
        self.o.skipping_to_sub = None;
        if self.frames.len() > 1 {
            return Ok(());
        }
        self.save_site(c, at, line)?;
        self.skip_to(&c.label, line);
        self.o.defining_sub = true;
        self.o.sub_name = Some(c.label.clone());
        Ok(())
    }

    /// `call`: enters a new frame and goes to the subroutine.
    fn call(&mut self, c: &Control, line: usize) -> Result<(), Diagnostic> {
        let args = c
            .args
            .iter()
            .map(|a| self.eval(a))
            .collect::<Result<Vec<_>, _>>()?;
        if self.frames.len() > MAX_CALL_DEPTH {
            return Err(self.error(
                line,
                c.column,
                format!(
                    "too many nested levels of subroutines: at most {MAX_CALL_DEPTH} calls deep"
                ),
            ));
        }
        self.o.skipping = None;
        let mut saved = Vec::with_capacity(SUB_PARAMETERS);
        for i in 1..=SUB_PARAMETERS {
            saved.push(self.machine.params.at(i));
            self.machine
                .params
                .set(i, args.get(i - 1).copied().unwrap_or(0.0));
        }
        self.frames.push(Frame {
            return_to: self.pc,
            saved,
            named: HashMap::new(),
            loops: Vec::new(),
            repeat: None,
            label: Some(c.label.clone()),
        });
        if let Some(site) = self.o.sites.get(&c.label) {
            self.pc = (site.file, site.line);
            return Ok(());
        }
        let stem = label_stem(&c.label);
        if let Some(file) = self.load_file(&format!("{stem}.ngc"), line)? {
            self.pc = (file, 0);
        }
        self.skip_to(&c.label, line);
        self.o.skipping_to_sub = Some(c.label.clone());
        Ok(())
    }

    /// The end of the text reached while looking for a subroutine or skipping.
    pub(crate) fn eof_while_skipping(&self) -> Diagnostic {
        let file = self.pc.0;
        let name = &self.sources[file].name;
        let line = self.o.skipping_from;
        match (&self.o.skipping_to_sub, &self.o.skipping) {
            (Some(label), _) => {
                let dirs = self.search_dirs();
                let list = if dirs.is_empty() {
                    "no search path".to_string()
                } else {
                    dirs.iter()
                        .map(|d| d.display().to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                let stem = label_stem(label);
                self.error(
                    line,
                    1,
                    format!(
                        "subroutine {label} not found: the end of {name} was reached looking \
                         for '{label} sub', and no file {stem}.ngc is in {list} (give the folder \
                         with --sub-path)"
                    ),
                )
            }
            (None, Some(label)) => self.error(
                line,
                1,
                format!("the end of {name} was reached looking for the end of {label}"),
            ),
            _ => self.error(line, 1, "the end of the program was reached while skipping"),
        }
    }

    /// `endsub` / `return`: back to the caller, or the end of a definition.
    fn sub_return(&mut self, c: &Control, line: usize) -> Result<(), Diagnostic> {
        if self.frames.len() < 2 && self.o.sub_name.is_none() {
            return Err(self.error(
                line,
                c.column,
                format!(
                    "'{} {}' outside a subroutine definition",
                    c.label,
                    c.keyword.name()
                ),
            ));
        }
        if self.o.skipping.is_some() && c.keyword == Keyword::EndSub {
            self.o.skipping = None;
        }
        if self.frames.len() < 2 {
            if c.keyword == Keyword::EndSub {
                if !self.o.defining_sub {
                    return Err(self.error(
                        line,
                        c.column,
                        "endsub outside a subroutine definition",
                    ));
                }
                self.o.skipping = None;
                self.o.defining_sub = false;
                self.o.sub_name = None;
            }
            return Ok(());
        }
        let frame = self.frames.pop().expect("checked above");
        for (k, v) in frame.saved.iter().enumerate() {
            self.machine.params.set(k + 1, *v);
        }
        self.pc = frame.return_to;
        self.o.sub_name = self.frames.last().and_then(|f| f.label.clone());
        Ok(())
    }

    /// The directories searched for subroutine files.
    pub(crate) fn search_dirs(&self) -> Vec<std::path::PathBuf> {
        let mut dirs = self.opts.sub_path.clone();
        if let Some(d) = &self.opts.program_dir {
            dirs.push(d.clone());
        }
        dirs
    }

    /// Loads `file_name` from the search path (once), returning its source index.
    pub(crate) fn load_file(
        &mut self,
        file_name: &str,
        line: usize,
    ) -> Result<Option<usize>, Diagnostic> {
        for dir in self.search_dirs() {
            let path = dir.join(file_name);
            let shown = path.display().to_string();
            if let Some(i) = self.sources.iter().position(|s| s.name == shown) {
                return Ok(Some(i));
            }
            if !path.is_file() {
                continue;
            }
            let text =
                swarf_io::read_input_text(&path).map_err(|e| self.error(line, 1, e.to_string()))?;
            crate::read::gcode::check_text(&text, &shown)
                .map_err(|e| self.error(line, 1, e.to_string()))?;
            self.sources.push(Source::new(shown, &text, self.syntax()));
            return Ok(Some(self.sources.len() - 1));
        }
        Ok(None)
    }
}

/// The file name stem of a subroutine's label (`o<name>`: name, `o100`: 100).
fn label_stem(label: &Label) -> String {
    match label {
        Label::Number(n) => n.to_string(),
        Label::Name(n) => n.to_string(),
        Label::Scoped(_, l) => label_stem(l),
    }
}

/// LinuxCNC's `round_to_int`.
fn round_to_int(v: f64) -> i64 {
    if !v.is_finite() {
        return 0;
    }
    (v + if v < 0.0 { -0.5 } else { 0.5 })
        .trunc()
        .clamp(-1e15, 1e15) as i64
}
