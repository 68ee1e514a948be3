//! ISO 10303-21 exchange structure: the `HEADER` and `DATA` sections, entity
//! instances `#id = NAME(args);` and complex instances `#id = (A(..) B(..));`, with
//! the line of each instance kept for error messages.
//!
//! A hand-written scanner over bytes (ISO 10303-21 section 6: tokens are keywords,
//! `#n` references, integers and reals, `'strings'` with `''` escapes, `.ENUMS.`,
//! `$`, `*`, and `/* comments */`). Lists nest up to [`MAX_DEPTH`]; the parser
//! recurses only that deep, so no input can exhaust the stack.

use super::{MAX_DEPTH, MAX_ENTITIES};
use std::collections::HashMap;

/// A parameter value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// `#n`.
    Ref(u64),
    /// An integer or real.
    Num(f64),
    /// `'text'`.
    Str(String),
    /// `.NAME.` (booleans are `.T.` / `.F.`).
    Enum(String),
    /// `( ... )`.
    List(Vec<Value>),
    /// `NAME(value)`, a typed parameter such as `LENGTH_MEASURE(25.4)`.
    Typed(String, Vec<Value>),
    /// `$`: no value.
    Null,
    /// `*`: derived.
    Derived,
}

/// One entity instance: its partial records (one for a simple instance) and line.
#[derive(Debug, Clone)]
pub struct Instance {
    /// `(NAME, args)` for each partial record, in file order.
    pub parts: Vec<(String, Vec<Value>)>,
    /// 1-based line of the `#id`.
    pub line: usize,
}

/// Where parsing failed: line and message.
#[derive(Debug)]
pub struct SyntaxError {
    /// 1-based line.
    pub line: usize,
    /// What was found and expected.
    pub message: String,
}

struct Scanner<'a> {
    s: &'a [u8],
    i: usize,
    line: usize,
}

type Res<T> = Result<T, SyntaxError>;

impl<'a> Scanner<'a> {
    fn err<T>(&self, message: impl Into<String>) -> Res<T> {
        Err(SyntaxError {
            line: self.line,
            message: message.into(),
        })
    }

    /// Skips white space and comments.
    fn skip(&mut self) -> Res<()> {
        loop {
            match self.s.get(self.i) {
                Some(b'\n') => {
                    self.line += 1;
                    self.i += 1;
                }
                Some(c) if c.is_ascii_whitespace() => self.i += 1,
                Some(b'/') if self.s.get(self.i + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.i += 2;
                    loop {
                        match self.s.get(self.i) {
                            None => {
                                return Err(SyntaxError {
                                    line: start,
                                    message: "comment '/*' is never closed".into(),
                                });
                            }
                            Some(b'*') if self.s.get(self.i + 1) == Some(&b'/') => {
                                self.i += 2;
                                break;
                            }
                            Some(b'\n') => {
                                self.line += 1;
                                self.i += 1;
                            }
                            _ => self.i += 1,
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    fn peek(&mut self) -> Res<Option<u8>> {
        self.skip()?;
        Ok(self.s.get(self.i).copied())
    }

    fn expect(&mut self, c: u8) -> Res<()> {
        match self.peek()? {
            Some(x) if x == c => {
                self.i += 1;
                Ok(())
            }
            Some(x) => self.err(format!("expected '{}', found '{}'", c as char, x as char)),
            None => self.err(format!(
                "expected '{}', found the end of the file",
                c as char
            )),
        }
    }

    fn keyword(&mut self) -> Res<String> {
        self.skip()?;
        let st = self.i;
        while let Some(c) = self.s.get(self.i) {
            if c.is_ascii_alphanumeric() || *c == b'_' || *c == b'-' || (*c == b'!' && self.i == st)
            {
                self.i += 1;
            } else {
                break;
            }
        }
        if st == self.i {
            return self.err("expected a keyword (entity name)");
        }
        Ok(String::from_utf8_lossy(&self.s[st..self.i]).to_ascii_uppercase())
    }

    fn digits(&mut self) -> &'a [u8] {
        let st = self.i;
        while self.s.get(self.i).is_some_and(u8::is_ascii_digit) {
            self.i += 1;
        }
        &self.s[st..self.i]
    }

    fn reference(&mut self) -> Res<u64> {
        self.expect(b'#')?;
        let d = self.digits();
        std::str::from_utf8(d)
            .ok()
            .and_then(|t| t.parse().ok())
            .map_or_else(|| self.err("expected an instance number after '#'"), Ok)
    }

    fn number(&mut self) -> Res<f64> {
        let st = self.i;
        if matches!(self.s.get(self.i), Some(b'+' | b'-')) {
            self.i += 1;
        }
        while let Some(c) = self.s.get(self.i) {
            let exp_sign =
                matches!(c, b'+' | b'-') && matches!(self.s.get(self.i - 1), Some(b'E' | b'e'));
            if c.is_ascii_digit() || matches!(c, b'.' | b'E' | b'e') || exp_sign {
                self.i += 1;
            } else {
                break;
            }
        }
        let t = std::str::from_utf8(&self.s[st..self.i]).unwrap_or("");
        let t2 = t.replace(".E", ".0E").replace(".e", ".0e");
        match t2.trim_end_matches('.').parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => self.err(format!("expected a finite number, found {t:?}")),
        }
    }

    fn string(&mut self) -> Res<String> {
        self.expect(b'\'')?;
        let mut out = Vec::new();
        loop {
            match self.s.get(self.i) {
                None => return self.err("string is never closed"),
                Some(b'\'') if self.s.get(self.i + 1) == Some(&b'\'') => {
                    out.push(b'\'');
                    self.i += 2;
                }
                Some(b'\'') => {
                    self.i += 1;
                    return Ok(String::from_utf8_lossy(&out).into_owned());
                }
                Some(c) => {
                    if *c == b'\n' {
                        self.line += 1;
                    }
                    out.push(*c);
                    self.i += 1;
                }
            }
        }
    }

    fn value(&mut self, depth: usize) -> Res<Value> {
        if depth > MAX_DEPTH {
            return self.err(format!("lists nested deeper than {MAX_DEPTH}"));
        }
        match self.peek()? {
            Some(b'#') => Ok(Value::Ref(self.reference()?)),
            Some(b'\'') => Ok(Value::Str(self.string()?)),
            Some(b'$') => {
                self.i += 1;
                Ok(Value::Null)
            }
            Some(b'*') => {
                self.i += 1;
                Ok(Value::Derived)
            }
            Some(b'.') => {
                self.i += 1;
                let k = self.keyword()?;
                self.expect(b'.')?;
                Ok(Value::Enum(k))
            }
            Some(b'(') => Ok(Value::List(self.list(depth + 1)?)),
            Some(b'"') => {
                self.i += 1;
                while self.s.get(self.i).is_some_and(|c| *c != b'"') {
                    self.i += 1;
                }
                self.expect(b'"')?;
                Ok(Value::Null)
            }
            Some(c) if c.is_ascii_digit() || c == b'-' || c == b'+' => {
                Ok(Value::Num(self.number()?))
            }
            Some(c) if c.is_ascii_alphabetic() => {
                let k = self.keyword()?;
                Ok(Value::Typed(k, self.list(depth + 1)?))
            }
            Some(c) => self.err(format!("unexpected character '{}'", c as char)),
            None => self.err("the file ends inside an entity"),
        }
    }

    /// `( v, v, ... )`.
    fn list(&mut self, depth: usize) -> Res<Vec<Value>> {
        self.expect(b'(')?;
        let mut out = Vec::new();
        if self.peek()? == Some(b')') {
            self.i += 1;
            return Ok(out);
        }
        loop {
            out.push(self.value(depth)?);
            match self.peek()? {
                Some(b',') => self.i += 1,
                Some(b')') => {
                    self.i += 1;
                    return Ok(out);
                }
                _ => return self.err("expected ',' or ')' in a parameter list"),
            }
        }
    }

    /// After `#id =`: `NAME(args)` or `(A(args) B(args) ...)`, then `;`.
    fn instance(&mut self) -> Res<Vec<(String, Vec<Value>)>> {
        let mut parts = Vec::new();
        if self.peek()? == Some(b'(') {
            self.i += 1;
            while self.peek()? != Some(b')') {
                let k = self.keyword()?;
                parts.push((k, self.list(1)?));
            }
            self.i += 1;
            if parts.is_empty() {
                return self.err("empty complex entity instance");
            }
        } else {
            let k = self.keyword()?;
            parts.push((k, self.list(1)?));
        }
        self.expect(b';')?;
        Ok(parts)
    }
}

/// The parsed file: instances by id, and the header's schema names.
#[derive(Debug)]
pub struct Exchange {
    /// Instances by `#id`.
    pub instances: HashMap<u64, Instance>,
    /// Ids in file order.
    pub order: Vec<u64>,
    /// `FILE_SCHEMA` names.
    pub schemas: Vec<String>,
}

/// Parses an exchange structure.
pub fn parse(text: &str) -> Result<Exchange, SyntaxError> {
    let mut sc = Scanner {
        s: text.as_bytes(),
        i: 0,
        line: 1,
    };
    if sc.keyword().ok().as_deref() != Some("ISO-10303-21") {
        return sc.err("not a STEP file: expected 'ISO-10303-21;' at the start");
    }
    sc.expect(b';')?;
    if sc.keyword()? != "HEADER" {
        return sc.err("expected 'HEADER;'");
    }
    sc.expect(b';')?;
    let mut schemas = Vec::new();
    loop {
        let k = sc.keyword()?;
        if k == "ENDSEC" {
            sc.expect(b';')?;
            break;
        }
        let args = sc.list(1)?;
        sc.expect(b';')?;
        if let ("FILE_SCHEMA", Some(Value::List(v))) = (k.as_str(), args.first()) {
            schemas.extend(v.iter().filter_map(|x| match x {
                Value::Str(s) => Some(s.clone()),
                _ => None,
            }));
        }
    }
    let mut ex = Exchange {
        instances: HashMap::new(),
        order: Vec::new(),
        schemas,
    };
    loop {
        match sc.keyword()?.as_str() {
            "DATA" => {
                if sc.peek()? == Some(b'(') {
                    sc.list(1)?;
                }
                sc.expect(b';')?;
                data(&mut sc, &mut ex)?;
            }
            "END-ISO-10303-21" => return Ok(ex),
            k => {
                return sc.err(format!(
                    "expected 'DATA;' or 'END-ISO-10303-21;', found {k:?}"
                ));
            }
        }
    }
}

fn data(sc: &mut Scanner<'_>, ex: &mut Exchange) -> Res<()> {
    loop {
        if sc.peek()? != Some(b'#') {
            let k = sc.keyword()?;
            if k != "ENDSEC" {
                return sc.err(format!("expected '#id = ...' or 'ENDSEC;', found {k:?}"));
            }
            return sc.expect(b';');
        }
        let line = sc.line;
        let id = sc.reference()?;
        sc.expect(b'=')?;
        let parts = sc.instance()?;
        if ex.instances.len() >= MAX_ENTITIES {
            return sc.err(format!("more than {MAX_ENTITIES} entity instances"));
        }
        if ex.instances.insert(id, Instance { parts, line }).is_some() {
            return Err(SyntaxError {
                line,
                message: format!("#{id} is defined twice"),
            });
        }
        ex.order.push(id);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AP214'));\nENDSEC;\nDATA;\n";

    #[test]
    fn simple_and_complex_instances_with_lines() {
        let t = format!(
            "{HEAD}#1 = CARTESIAN_POINT('a''b',(1.,-2.5E-01,3));\n/* c\n */#2 = ( A() B(#1,.T.,$,*,LENGTH_MEASURE(2.)) );\nENDSEC;\nEND-ISO-10303-21;\n"
        );
        let ex = parse(&t).unwrap();
        assert_eq!(ex.schemas, vec!["AP214"]);
        let p = &ex.instances[&1];
        assert_eq!(p.line, 6);
        assert_eq!(p.parts[0].1[0], Value::Str("a'b".into()));
        assert_eq!(
            p.parts[0].1[1],
            Value::List(vec![Value::Num(1.0), Value::Num(-0.25), Value::Num(3.0)])
        );
        let c = &ex.instances[&2];
        assert_eq!(c.line, 8);
        assert_eq!(c.parts.len(), 2);
        assert_eq!(
            c.parts[1].1[4],
            Value::Typed("LENGTH_MEASURE".into(), vec![Value::Num(2.0)])
        );
    }

    #[test]
    fn errors_name_the_line() {
        assert!(
            parse("solid x\n")
                .unwrap_err()
                .message
                .contains("not a STEP file")
        );
        let e = parse(&format!("{HEAD}#1 = A(1,2;\n")).unwrap_err();
        assert_eq!(e.line, 6);
        let e = parse(&format!(
            "{HEAD}#1 = A(1.0.0);\nENDSEC;\nEND-ISO-10303-21;\n"
        ))
        .unwrap_err();
        assert!(e.message.contains("number"), "{}", e.message);
        let deep = format!("{HEAD}#1 = A({}{});", "(".repeat(1000), ")".repeat(1000));
        assert!(parse(&deep).unwrap_err().message.contains("nested"));
        let dup = format!("{HEAD}#1 = A();\n#1 = B();\nENDSEC;\nEND-ISO-10303-21;\n");
        assert!(parse(&dup).unwrap_err().message.contains("twice"));
    }
}
