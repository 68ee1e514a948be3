//! Mutations of text (and any byte) inputs, as proptest strategies.
//!
//! A mutation edits what a user could plausibly hand swarf: a number replaced by an
//! extreme one (1e308, 5e-324, -0, nan, inf, 400 digits ...), a line or token
//! deleted, duplicated or swapped, the file cut short, binary garbage inserted, a
//! 100 KB token, an empty file. Positions are given as an index taken modulo the
//! count of numbers, lines or tokens the input has, or in thousandths of its length,
//! so every mutation applies to every input and shrinks toward its start.

use proptest::prelude::*;

/// Numbers that break arithmetic, parsers and allocations.
pub const EXTREMES: &[&str] = &[
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "5e-324",
    "-5e-324",
    "0",
    "-0",
    "0.0",
    "-0.0",
    "1e-200",
    "-1e-200",
    "1e30",
    "-1e30",
    "1e-30",
    "nan",
    "NaN",
    "-nan",
    "inf",
    "-inf",
    "+inf",
    "Infinity",
    "1e999",
    "-1e999",
    "1e-999",
    "-1",
    "-1000",
    "1e6",
    "1e9",
    "1e15",
    "2147483648",
    "4294967296",
    "9223372036854775807",
    "18446744073709551616",
    "0x10",
    "1_000",
    "1e",
    ".",
    "-",
    "",
];

/// A hostile number as text: an extreme, a long string of digits, a random f64
/// (any class, NaN and infinities included) or a plain one of another scale.
pub fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        8 => prop::sample::select(EXTREMES).prop_map(str::to_string),
        1 => Just("9".repeat(400)),
        1 => Just(format!("{}.5", "9".repeat(400))),
        1 => Just(format!("0.{}1", "0".repeat(400))),
        1 => Just(format!("-{}e-400", "1".repeat(400))),
        2 => any::<f64>().prop_map(|x| format!("{x:e}")),
        2 => (-40i32..40).prop_map(|e| format!("1e{e}")),
        1 => any::<u64>().prop_map(|n| n.to_string()),
    ]
}

/// One edit of an input.
#[derive(Debug, Clone)]
pub enum Mutation {
    /// Replace the `k`-th number (modulo how many there are) with `value`.
    Number { k: usize, value: String },
    /// Delete line `k`.
    DeleteLine { k: usize },
    /// Repeat line `k` `times` more times.
    DuplicateLine { k: usize, times: usize },
    /// Swap lines `a` and `b`.
    SwapLines { a: usize, b: usize },
    /// Delete token `k` (tokens: runs of bytes between blanks and `,;=[](){}"`).
    DeleteToken { k: usize },
    /// Repeat token `k` once.
    DuplicateToken { k: usize },
    /// Swap tokens `a` and `b`.
    SwapTokens { a: usize, b: usize },
    /// Keep the first `permille` thousandths of the input.
    Truncate { permille: u16 },
    /// Insert `bytes` at `permille` thousandths of the input.
    Garbage { permille: u16, bytes: Vec<u8> },
    /// Insert `len` copies of `byte` at `permille` thousandths of the input.
    LongToken { permille: u16, byte: u8, len: usize },
    /// Replace everything with nothing.
    Empty,
}

/// Bytes for a very long token: a digit, a letter, a sign or a separator.
const LONG_BYTES: &[u8] = b"9aX.-,#[( \n";

/// Any one mutation, weighted toward number replacement.
pub fn mutation() -> impl Strategy<Value = Mutation> {
    let k = 0usize..4096;
    let pm = 0u16..=1000;
    prop_oneof![
        12 => (k.clone(), number()).prop_map(|(k, value)| Mutation::Number { k, value }),
        2 => k.clone().prop_map(|k| Mutation::DeleteLine { k }),
        2 => (k.clone(), prop_oneof![3 => 1usize..3, 1 => Just(1000usize)])
            .prop_map(|(k, times)| Mutation::DuplicateLine { k, times }),
        2 => (k.clone(), k.clone()).prop_map(|(a, b)| Mutation::SwapLines { a, b }),
        2 => k.clone().prop_map(|k| Mutation::DeleteToken { k }),
        2 => k.clone().prop_map(|k| Mutation::DuplicateToken { k }),
        2 => (k.clone(), k).prop_map(|(a, b)| Mutation::SwapTokens { a, b }),
        2 => pm.clone().prop_map(|permille| Mutation::Truncate { permille }),
        2 => (pm.clone(), prop::collection::vec(any::<u8>(), 1..48))
            .prop_map(|(permille, bytes)| Mutation::Garbage { permille, bytes }),
        1 => (pm, prop::sample::select(LONG_BYTES))
            .prop_map(|(permille, byte)| Mutation::LongToken { permille, byte, len: 100_000 }),
        1 => Just(Mutation::Empty),
    ]
}

/// One to three mutations, applied in order.
pub fn mutations() -> impl Strategy<Value = Vec<Mutation>> {
    prop::collection::vec(mutation(), 1..=3)
}

/// `input` with every mutation applied in order.
pub fn apply_all(input: &[u8], ms: &[Mutation]) -> Vec<u8> {
    ms.iter().fold(input.to_vec(), |acc, m| apply(&acc, m))
}

/// `input` with `m` applied.
pub fn apply(input: &[u8], m: &Mutation) -> Vec<u8> {
    let at = |permille: u16| input.len() * usize::from(permille.min(1000)) / 1000;
    match m {
        Mutation::Number { k, value } => {
            let spans = number_spans(input);
            match spans.get(k % spans.len().max(1)) {
                Some(&(s, e)) => splice(input, s, e, value.as_bytes()),
                None => input.to_vec(),
            }
        }
        Mutation::DeleteLine { k } => edit_lines(input, |lines| {
            let k = k % lines.len();
            lines.remove(k);
        }),
        Mutation::DuplicateLine { k, times } => edit_lines(input, |lines| {
            let k = k % lines.len();
            let line = lines[k].clone();
            for _ in 0..*times {
                lines.insert(k, line.clone());
            }
        }),
        Mutation::SwapLines { a, b } => edit_lines(input, |lines| {
            let n = lines.len();
            lines.swap(a % n, b % n);
        }),
        Mutation::DeleteToken { k } => edit_token(input, *k, |_| Vec::new()),
        Mutation::DuplicateToken { k } => edit_token(input, *k, |t| [t, b" ", t].concat()),
        Mutation::SwapTokens { a, b } => swap_tokens(input, *a, *b),
        Mutation::Truncate { permille } => input[..at(*permille)].to_vec(),
        Mutation::Garbage { permille, bytes } => {
            let p = at(*permille);
            splice(input, p, p, bytes)
        }
        Mutation::LongToken {
            permille,
            byte,
            len,
        } => {
            let p = at(*permille);
            splice(input, p, p, &vec![*byte; *len])
        }
        Mutation::Empty => Vec::new(),
    }
}

fn splice(input: &[u8], start: usize, end: usize, with: &[u8]) -> Vec<u8> {
    [&input[..start], with, &input[end..]].concat()
}

/// Byte spans of the numbers in `input`: an optional sign, digits with an optional
/// point and fraction, an optional exponent.
pub fn number_spans(input: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < input.len() {
        let digit_at = |j: usize| input.get(j).is_some_and(u8::is_ascii_digit);
        let starts = digit_at(i) || (input[i] == b'.' && digit_at(i + 1));
        if !starts {
            i += 1;
            continue;
        }
        let mut s = i;
        if s > 0 && matches!(input[s - 1], b'-' | b'+') {
            s -= 1;
        }
        let mut e = i;
        while e < input.len() && (input[e].is_ascii_digit() || input[e] == b'.') {
            e += 1;
        }
        if e < input.len() && matches!(input[e], b'e' | b'E') {
            let mut x = e + 1;
            if x < input.len() && matches!(input[x], b'-' | b'+') {
                x += 1;
            }
            if digit_at(x) {
                while digit_at(x) {
                    x += 1;
                }
                e = x;
            }
        }
        spans.push((s, e));
        i = e;
    }
    spans
}

/// Applies `edit` to the lines of `input` (each with its line end), if it has any.
fn edit_lines(input: &[u8], edit: impl FnOnce(&mut Vec<Vec<u8>>)) -> Vec<u8> {
    let mut lines: Vec<Vec<u8>> = input
        .split_inclusive(|&b| b == b'\n')
        .map(<[u8]>::to_vec)
        .collect();
    if lines.is_empty() {
        return input.to_vec();
    }
    edit(&mut lines);
    lines.concat()
}

fn is_separator(b: u8) -> bool {
    b.is_ascii_whitespace() || b",;=[](){}\"".contains(&b)
}

/// Byte spans of the tokens of `input`.
pub fn token_spans(input: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < input.len() {
        if is_separator(input[i]) {
            i += 1;
            continue;
        }
        let s = i;
        while i < input.len() && !is_separator(input[i]) {
            i += 1;
        }
        spans.push((s, i));
    }
    spans
}

fn edit_token(input: &[u8], k: usize, with: impl FnOnce(&[u8]) -> Vec<u8>) -> Vec<u8> {
    let spans = token_spans(input);
    match spans.get(k % spans.len().max(1)) {
        Some(&(s, e)) => splice(input, s, e, &with(&input[s..e])),
        None => input.to_vec(),
    }
}

fn swap_tokens(input: &[u8], a: usize, b: usize) -> Vec<u8> {
    let spans = token_spans(input);
    if spans.is_empty() {
        return input.to_vec();
    }
    let (a, b) = (a % spans.len(), b % spans.len());
    let (first, second) = (spans[a.min(b)], spans[a.max(b)]);
    if first == second {
        return input.to_vec();
    }
    [
        &input[..first.0],
        &input[second.0..second.1],
        &input[first.1..second.0],
        &input[first.0..first.1],
        &input[second.1..],
    ]
    .concat()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(input: &str, m: Mutation) -> String {
        String::from_utf8(apply(input.as_bytes(), &m)).unwrap()
    }

    #[test]
    fn numbers_are_found_with_sign_point_and_exponent() {
        let s = b"X-3.5 Y.25 Z1e-3 G17 d=8,r=2.";
        let found: Vec<&[u8]> = number_spans(s).iter().map(|&(a, b)| &s[a..b]).collect();
        let want: [&[u8]; 6] = [b"-3.5", b".25", b"1e-3", b"17", b"8", b"2."];
        assert_eq!(found, want);
    }

    #[test]
    fn each_edit_does_what_it_names() {
        let n = |k, v: &str| Mutation::Number { k, value: v.into() };
        assert_eq!(text("a = 1\nb = 2\n", n(1, "nan")), "a = 1\nb = nan\n");
        assert_eq!(text("a = 1\nb = 2\n", n(3, "inf")), "a = 1\nb = inf\n");
        assert_eq!(text("no numbers", n(0, "1")), "no numbers");
        assert_eq!(text("1\n2\n3\n", Mutation::DeleteLine { k: 4 }), "1\n3\n");
        assert_eq!(
            text("1\n2\n", Mutation::DuplicateLine { k: 0, times: 2 }),
            "1\n1\n1\n2\n"
        );
        assert_eq!(text("1\n2\n", Mutation::SwapLines { a: 0, b: 1 }), "2\n1\n");
        assert_eq!(
            text("x = [1, 2]", Mutation::DeleteToken { k: 1 }),
            "x = [, 2]"
        );
        assert_eq!(text("G1 X2", Mutation::DuplicateToken { k: 1 }), "G1 X2 X2");
        assert_eq!(text("a b c", Mutation::SwapTokens { a: 2, b: 0 }), "c b a");
        assert_eq!(text("abcd", Mutation::Truncate { permille: 500 }), "ab");
        let long = apply(
            b"ab",
            &Mutation::LongToken {
                permille: 500,
                byte: b'9',
                len: 100_000,
            },
        );
        assert_eq!(long.len(), 100_002);
        assert!(long.starts_with(b"a9") && long.ends_with(b"9b"));
        assert!(apply(b"abc", &Mutation::Empty).is_empty());
        assert!(apply(b"", &Mutation::DeleteLine { k: 3 }).is_empty());
    }
}
