//! ASCII STL: whitespace-separated tokens, keywords in any case.
//!
//! ```text
//! solid [name]
//!   facet [normal nx ny nz]
//!     outer loop
//!       vertex x y z      (three times)
//!     endloop
//!   endfacet              (any number of facets)
//! endsolid [name]         (then optionally another solid)
//! ```
//!
//! Read one line at a time into a reused buffer; tokens are byte ranges of it, so
//! nothing is allocated per token. Coordinates are parsed as `f64` (no rounding to
//! `f32`) and welded on exact equality.

use super::builder_for;
use crate::error::{At, IoError, excerpt};
use std::io::BufRead;
use std::ops::Range;
use swarf_geom::{MeshBuilder, Point3, TriMesh};

/// Longest quote of a bad token in an error, characters.
const EXCERPT: usize = 40;

/// Reads every solid of an ASCII STL.
pub(super) fn read(reader: impl BufRead, file: &str) -> Result<TriMesh, IoError> {
    let mut t = Tokens {
        reader,
        file,
        buf: Vec::new(),
        pos: 0,
        line: 0,
    };
    let mut builder = builder_for(0);
    let mut facets = 0usize;
    t.expect(b"solid", "at the start of an ASCII STL", None)?;
    t.skip_name(b"facet");
    loop {
        let (tok, _) = t.need("`facet` or `endsolid`", None)?;
        if t.is(&tok, b"endsolid") {
            t.skip_name(b"solid");
            match t.next()? {
                None => return Ok(builder.finish()),
                Some(tok) if t.is(&tok, b"solid") => t.skip_name(b"facet"),
                Some(tok) => return Err(t.unexpected(&tok, "`solid` or the end of the file")),
            }
        } else if t.is(&tok, b"facet") {
            facets += 1;
            facet(&mut t, &mut builder, facets)?;
        } else {
            return Err(t.unexpected(&tok, "`facet` or `endsolid`"));
        }
    }
}

/// The rest of facet number `n` (1-based) after its `facet` keyword.
fn facet<R: BufRead>(
    t: &mut Tokens<'_, R>,
    builder: &mut MeshBuilder,
    n: usize,
) -> Result<(), IoError> {
    let (tok, _) = t.need("`normal` or `outer`", Some(n))?;
    if t.is(&tok, b"normal") {
        for _ in 0..3 {
            t.number("a normal component", n)?;
        }
        t.expect(b"outer", "", Some(n))?;
    } else if !t.is(&tok, b"outer") {
        return Err(t.unexpected(&tok, "`normal` or `outer`"));
    }
    t.expect(b"loop", "", Some(n))?;
    let mut corners = [Point3::origin(); 3];
    for c in &mut corners {
        t.expect(b"vertex", "", Some(n))?;
        *c = Point3::new(t.number("x", n)?, t.number("y", n)?, t.number("z", n)?);
    }
    t.expect(
        b"endloop",
        "(facets are triangles: three vertices)",
        Some(n),
    )?;
    t.expect(b"endfacet", "", Some(n))?;
    let line = t.line;
    builder
        .push_triangle(corners)
        .map_err(|e| IoError::format(t.file, At::Line(line), e.to_string()))
}

/// Token stream over lines.
struct Tokens<'f, R> {
    reader: R,
    file: &'f str,
    buf: Vec<u8>,
    pos: usize,
    /// 1-based number of the line in `buf` (0 before the first).
    line: usize,
}

impl<R: BufRead> Tokens<'_, R> {
    /// The next token on the current line, without reading another line.
    fn next_in_line(&mut self) -> Option<Range<usize>> {
        let buf = &self.buf;
        let start = self.pos
            + buf[self.pos..]
                .iter()
                .take_while(|b| b.is_ascii_whitespace())
                .count();
        let end = start
            + buf[start..]
                .iter()
                .take_while(|b| !b.is_ascii_whitespace())
                .count();
        self.pos = end;
        (start < end).then_some(start..end)
    }

    /// The next token's byte range in `buf`, reading lines as needed; `None` at the end.
    fn next(&mut self) -> Result<Option<Range<usize>>, IoError> {
        loop {
            if let Some(tok) = self.next_in_line() {
                return Ok(Some(tok));
            }
            self.buf.clear();
            self.pos = 0;
            let n = self.reader.read_until(b'\n', &mut self.buf).map_err(|e| {
                IoError::format(
                    self.file,
                    At::Line(self.line + 1),
                    format!("cannot read: {e}"),
                )
            })?;
            if n == 0 {
                return Ok(None);
            }
            self.line += 1;
        }
    }

    /// Skips a solid's name: the tokens after `solid` or `endsolid` on the same
    /// line, up to keyword `stop` or `endsolid` (so that a file on one line reads).
    fn skip_name(&mut self, stop: &[u8]) {
        loop {
            let before = self.pos;
            match self.next_in_line() {
                Some(tok) if !self.is(&tok, stop) && !self.is(&tok, b"endsolid") => {}
                Some(_) => {
                    self.pos = before;
                    return;
                }
                None => return,
            }
        }
    }

    fn is(&self, tok: &Range<usize>, word: &[u8]) -> bool {
        self.buf[tok.clone()].eq_ignore_ascii_case(word)
    }

    /// The next token, or an error saying the file ended where `what` was expected.
    fn need(&mut self, what: &str, facet: Option<usize>) -> Result<(Range<usize>, usize), IoError> {
        match self.next()? {
            Some(tok) => Ok((tok, self.line)),
            None => {
                let inside = facet.map_or(String::new(), |n| format!(" inside facet {n}"));
                Err(IoError::format(
                    self.file,
                    At::Line(self.line.max(1)),
                    format!("file ends{inside}; expected {what}"),
                ))
            }
        }
    }

    /// Consumes keyword `word` or fails, adding `note` to the message.
    fn expect(&mut self, word: &[u8], note: &str, facet: Option<usize>) -> Result<(), IoError> {
        let what = format!(
            "`{}`{}{note}",
            String::from_utf8_lossy(word),
            if note.is_empty() { "" } else { " " }
        );
        let (tok, _) = self.need(&what, facet)?;
        if self.is(&tok, word) {
            Ok(())
        } else {
            Err(self.unexpected(&tok, &what))
        }
    }

    fn number(&mut self, what: &str, facet: usize) -> Result<f64, IoError> {
        let expected = format!("a number ({what})");
        let (tok, _) = self.need(&expected, Some(facet))?;
        std::str::from_utf8(&self.buf[tok.clone()])
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .ok_or_else(|| self.unexpected(&tok, &expected))
    }

    fn unexpected(&self, tok: &Range<usize>, expected: &str) -> IoError {
        let found = excerpt(&String::from_utf8_lossy(&self.buf[tok.clone()]), EXCERPT);
        IoError::format(
            self.file,
            At::Line(self.line),
            format!("expected {expected}, found `{found}`"),
        )
    }
}
