//! LinuxCNC's O-word control flow (`interp_o_word.cc`): subroutines, loops and
//! conditions, run by jumping within the indexed program texts
//! ([`crate::read::source`]).
//!
//! - `sub ... endsub` is skipped where the flow meets it (and so defined); `call [a]
//!   [b] ...` runs it with `#1-#30` set to the arguments (missing ones 0) and the
//!   caller's restored on return; named parameters without `_` are local to a call.
//!   A subroutine is looked for, in order: defined earlier in the flow; in a file
//!   `name.ngc` on the search path; ahead in the current file. `return [v]` and
//!   `endsub [v]` set `#<_value>` and `#<_value_returned>`.
//! - `while [c] ... endwhile`, `do ... while [c]`, `repeat [n] ... endrepeat` (n rounded),
//!   with `break` and `continue` (not in `repeat`: LinuxCNC refuses them there).
//! - `if [c] ... elseif [c] ... else ... endif`.
//!
//! As in LinuxCNC, a subroutine found by looking ahead must not be reached later by
//! the flow ("found in illegal location"), and one label is defined once.

use crate::read::flow::{Frame, LoopCtx, LoopKind, MAX_CALL_DEPTH, Runner};
use crate::read::program::Diagnostic;
use crate::read::source::Source;
use crate::read::statement::{Control, Keyword, Label};
use std::collections::HashMap;

/// Subroutine arguments: `#1` to `#30`.
pub const SUB_PARAMETERS: usize = 30;

/// Largest subroutine file read, bytes.
pub const MAX_SUB_FILE: u64 = 256 << 20;

impl Runner<'_> {
    /// Runs an O-word statement on `line` (1-based) of the current source.
    pub(crate) fn control(&mut self, c: Control, line: usize) -> Result<(), Diagnostic> {
        let at = line - 1;
        match c.keyword {
            Keyword::Sub => self.define_sub(&c, at, line),
            Keyword::EndSub | Keyword::Return => self.sub_return(&c, line),
            Keyword::Call => self.call(&c, line),
            Keyword::Do => {
                self.push_loop(&c.label, LoopKind::Do, at, 0, line)?;
                Ok(())
            }
            Keyword::While => self.while_statement(&c, at, line),
            Keyword::EndWhile => {
                let start = self.find_loop(&c, line, &[LoopKind::While])?.start;
                self.pc.1 = start;
                Ok(())
            }
            Keyword::Repeat => {
                let count = self.eval(&c.args[0])?;
                let n = count.round();
                if n <= 0.0 {
                    return self.skip_past(&c.label, at, Keyword::EndRepeat, line);
                }
                self.push_loop(&c.label, LoopKind::Repeat, at, n as i64, line)
            }
            Keyword::EndRepeat => {
                let limit = self.opts.limits.loop_iterations;
                let ctx = self.find_loop(&c, line, &[LoopKind::Repeat])?;
                ctx.remaining -= 1;
                ctx.turns += 1;
                if ctx.turns > limit {
                    return Err(self.loop_limit(&c.label, line));
                }
                if ctx.remaining > 0 {
                    let start = ctx.start;
                    self.pc.1 = start + 1;
                } else {
                    self.frame().loops.pop();
                }
                Ok(())
            }
            Keyword::Break | Keyword::Continue => self.break_continue(&c, line),
            Keyword::If => {
                if self.eval(&c.args[0])? != 0.0 {
                    return Ok(());
                }
                self.next_branch(&c.label, at, line)
            }
            Keyword::ElseIf | Keyword::Else => self.skip_past(&c.label, at, Keyword::EndIf, line),
            Keyword::EndIf => Ok(()),
        }
    }

    fn loop_limit(&self, label: &Label, line: usize) -> Diagnostic {
        self.error(
            line,
            1,
            format!(
                "loop {label} turned more than {} times: stopped here (a loop that never ends?)",
                self.opts.limits.loop_iterations
            ),
        )
    }

    fn push_loop(&mut self, label: &Label, kind: LoopKind, start: usize, remaining: i64, line: usize) -> Result<(), Diagnostic> {
        let limit = self.opts.limits.loop_iterations;
        let frame = self.frame();
        if let Some(top) = frame.loops.last_mut().filter(|l| l.label == *label && l.start == start) {
            top.turns += 1;
            if top.turns > limit {
                return Err(self.loop_limit(label, line));
            }
            return Ok(());
        }
        frame.loops.push(LoopCtx {
            label: label.clone(),
            kind,
            start,
            remaining,
            turns: 0,
        });
        Ok(())
    }

    /// The innermost loop of this frame with the statement's label, of one of `kinds`.
    fn find_loop(&mut self, c: &Control, line: usize, kinds: &[LoopKind]) -> Result<&mut LoopCtx, Diagnostic> {
        let label = c.label.clone();
        let keyword = c.keyword.name();
        let found = self
            .frame()
            .loops
            .iter()
            .rposition(|l| l.label == label && kinds.contains(&l.kind));
        match found {
            Some(k) => {
                let frame = self.frame();
                frame.loops.truncate(k + 1);
                Ok(&mut frame.loops[k])
            }
            None => Err(self.error(
                line,
                c.column,
                format!("'{label} {keyword}' without a matching loop"),
            )),
        }
    }

    /// `while [c]`: the head of a while loop, or the tail of a do loop.
    fn while_statement(&mut self, c: &Control, at: usize, line: usize) -> Result<(), Diagnostic> {
        let limit = self.opts.limits.loop_iterations;
        let holds = self.eval(&c.args[0])? != 0.0;
        let tail = self
            .frame()
            .loops
            .last()
            .is_some_and(|l| l.label == c.label && l.kind == LoopKind::Do);
        if tail {
            let frame = self.frame();
            let ctx = frame.loops.last_mut().expect("checked above");
            if !holds {
                frame.loops.pop();
                return Ok(());
            }
            ctx.turns += 1;
            let start = ctx.start;
            if ctx.turns > limit {
                return Err(self.loop_limit(&c.label, line));
            }
            self.pc.1 = start + 1;
            return Ok(());
        }
        if holds {
            return self.push_loop(&c.label, LoopKind::While, at, 0, line);
        }
        if self
            .frame()
            .loops
            .last()
            .is_some_and(|l| l.label == c.label && l.start == at)
        {
            self.frame().loops.pop();
        }
        self.skip_past(&c.label, at, Keyword::EndWhile, line)
    }

    fn break_continue(&mut self, c: &Control, line: usize) -> Result<(), Diagnostic> {
        let in_repeat = self
            .frame()
            .loops
            .iter()
            .rev()
            .find(|l| l.label == c.label)
            .is_some_and(|l| l.kind == LoopKind::Repeat);
        if in_repeat {
            return Err(self.error(
                line,
                c.column,
                format!("'{} {}' inside a repeat loop: LinuxCNC allows it in while and do loops only", c.label, c.keyword.name()),
            ));
        }
        let ctx = self.find_loop(c, line, &[LoopKind::While, LoopKind::Do])?.clone();
        let file = self.pc.0;
        let end = match ctx.kind {
            LoopKind::Do => self.sources[file].next(&c.label, ctx.start, &[Keyword::While]),
            _ => self.sources[file].next(&c.label, ctx.start, &[Keyword::EndWhile]),
        };
        let Some((end, _)) = end else {
            return Err(self.error(line, c.column, format!("loop {} has no end", c.label)));
        };
        if c.keyword == Keyword::Break {
            self.frame().loops.pop();
            self.pc.1 = end + 1;
        } else if ctx.kind == LoopKind::Do {
            self.pc.1 = end;
        } else {
            self.pc.1 = ctx.start;
        }
        Ok(())
    }

    /// Jumps past the next `keyword` with `label` after line index `at`.
    fn skip_past(&mut self, label: &Label, at: usize, keyword: Keyword, line: usize) -> Result<(), Diagnostic> {
        let file = self.pc.0;
        match self.sources[file].next(label, at, &[keyword]) {
            Some((i, _)) => {
                self.pc.1 = i + 1;
                Ok(())
            }
            None => Err(self.error(
                line,
                1,
                format!("{label}: no matching '{label} {}' in {}", keyword.name(), self.sources[file].name),
            )),
        }
    }

    /// After a false `if` or `elseif`: the next branch whose condition holds.
    fn next_branch(&mut self, label: &Label, at: usize, line: usize) -> Result<(), Diagnostic> {
        let file = self.pc.0;
        let mut from = at;
        loop {
            let next = self.sources[file].next(label, from, &[Keyword::ElseIf, Keyword::Else, Keyword::EndIf]);
            let Some((i, keyword)) = next else {
                return Err(self.error(line, 1, format!("{label}: if without endif")));
            };
            if keyword != Keyword::ElseIf {
                self.pc.1 = i + 1;
                return Ok(());
            }
            let text = self.sources[file].line(i).unwrap_or("").to_string();
            let lexed = crate::read::lexer::lex_line(&text, i + 1, self.syntax()).map_err(|d| self.place(d))?;
            if let crate::read::lexer::Statement::Control(c) = lexed.statement {
                self.pc.1 = i + 1;
                if self.eval(&c.args[0])? != 0.0 {
                    return Ok(());
                }
            }
            from = i;
        }
    }

    /// `sub` met by the flow: defined, and skipped to after its `endsub`.
    fn define_sub(&mut self, c: &Control, at: usize, line: usize) -> Result<(), Diagnostic> {
        let file = self.pc.0;
        match self.subs.get(&c.label) {
            Some(&(f, i)) if (f, i) == (file, at) => {
                return Err(self.error(
                    line,
                    c.column,
                    format!("sub {} found in illegal location: it was called before the flow reached it", c.label),
                ));
            }
            Some(&(f, _)) => {
                return Err(self.error(
                    line,
                    c.column,
                    format!("redefining sub {}: already defined in {}", c.label, self.sources[f].name),
                ));
            }
            None => {}
        }
        self.subs.insert(c.label.clone(), (file, at));
        self.skip_past(&c.label, at, Keyword::EndSub, line)
    }

    /// `call`: finds the subroutine and enters it.
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
                format!("too many nested levels of subroutines: at most {MAX_CALL_DEPTH} calls deep"),
            ));
        }
        let (file, start) = self.find_sub(c, line)?;
        let mut saved = Vec::with_capacity(SUB_PARAMETERS);
        for i in 1..=SUB_PARAMETERS {
            saved.push(self.machine.params.at(i));
            self.machine.params.set(i, args.get(i - 1).copied().unwrap_or(0.0));
        }
        self.frames.push(Frame {
            return_to: self.pc,
            saved,
            named: HashMap::new(),
            loops: Vec::new(),
            repeat: None,
            label: Some(c.label.clone()),
        });
        self.pc = (file, start + 1);
        Ok(())
    }

    /// Where subroutine `c.label` starts: (source, line index of its `sub`).
    fn find_sub(&mut self, c: &Control, line: usize) -> Result<(usize, usize), Diagnostic> {
        if let Some(&found) = self.subs.get(&c.label) {
            return Ok(found);
        }
        let stem = match &c.label {
            Label::Number(n) => n.to_string(),
            Label::Name(n) => n.to_string(),
        };
        if let Some(file) = self.load_file(&format!("{stem}.ngc"), line)? {
            let Some((i, _)) = self.sources[file].next(&c.label, 0, &[Keyword::Sub]).or_else(|| {
                self.sources[file]
                    .owords(&c.label)
                    .iter()
                    .find(|(_, k)| *k == Keyword::Sub)
                    .copied()
            }) else {
                return Err(self.error(
                    line,
                    c.column,
                    format!("{} does not define sub {}", self.sources[file].name, c.label),
                ));
            };
            self.subs.insert(c.label.clone(), (file, i));
            return Ok((file, i));
        }
        let here = self.pc.0;
        if let Some((i, _)) = self.sources[here].next(&c.label, self.pc.1.saturating_sub(1), &[Keyword::Sub]) {
            self.subs.insert(c.label.clone(), (here, i));
            return Ok((here, i));
        }
        let dirs = self.search_dirs();
        let list = if dirs.is_empty() {
            "no search path".to_string()
        } else {
            dirs.iter().map(|d| d.display().to_string()).collect::<Vec<_>>().join(", ")
        };
        Err(self.error(
            line,
            c.column,
            format!(
                "subroutine {} not found: not defined in {} and no file {stem}.ngc in {list} \
                 (give the folder with --sub-path)",
                c.label, self.sources[here].name
            ),
        ))
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
    pub(crate) fn load_file(&mut self, file_name: &str, line: usize) -> Result<Option<usize>, Diagnostic> {
        for dir in self.search_dirs() {
            let path = dir.join(file_name);
            let shown = path.display().to_string();
            if let Some(i) = self.sources.iter().position(|s| s.name == shown) {
                return Ok(Some(i));
            }
            if !path.is_file() {
                continue;
            }
            let text = read_limited(&path).map_err(|m| self.error(line, 1, format!("{shown}: {m}")))?;
            crate::read::gcode::check_text(&text, &shown).map_err(|e| self.error(line, 1, e.to_string()))?;
            self.sources.push(Source::new(shown, &text, self.syntax()));
            return Ok(Some(self.sources.len() - 1));
        }
        Ok(None)
    }

    /// `endsub` / `return`: back to the caller.
    fn sub_return(&mut self, c: &Control, line: usize) -> Result<(), Diagnostic> {
        if self.frames.len() < 2 {
            return Err(self.error(
                line,
                c.column,
                format!("'{} {}' outside a subroutine", c.label, c.keyword.name()),
            ));
        }
        self.value = match c.args.first() {
            Some(e) => (self.eval(e)?, true),
            None => (0.0, false),
        };
        let frame = self.frames.pop().expect("checked above");
        for (k, v) in frame.saved.iter().enumerate() {
            self.machine.params.set(k + 1, *v);
        }
        self.pc = frame.return_to;
        Ok(())
    }
}

/// A subroutine file's text, refusing files larger than [`MAX_SUB_FILE`].
pub(crate) fn read_limited(path: &std::path::Path) -> Result<String, String> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read: {e}"))?;
    let mut bytes = Vec::new();
    file.take(MAX_SUB_FILE + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read: {e}"))?;
    if bytes.len() as u64 > MAX_SUB_FILE {
        return Err(format!("larger than {MAX_SUB_FILE} bytes"));
    }
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}
