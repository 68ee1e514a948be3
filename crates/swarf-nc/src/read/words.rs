//! Sorting a lexed block's words before execution: G and M codes looked up in the
//! code table ([`crate::read::codes`]), refused or warned about there; two codes of
//! one modal group, or one letter twice, refused as LinuxCNC does; letters swarf
//! cannot simulate (U/V/W axes, `E`) refused and unused ones warned about.
//!
//! Rotary axis words (`A`, `B`, `C`) need the machine's kinematics
//! ([`crate::read::kinematics`]): without them they are refused with a pointer to
//! `swarf verify --machine`; with them, a letter the machine does not have is refused
//! naming the machine's letters, and rotary words on an arc (G2/G3) are refused.

use crate::read::codes::{Action, Effect, Group, g_code, m_code};
use crate::read::warnings::Warnings;
use swarf_toolpath::program::Diagnostic;

/// One word with its value evaluated: a letter and a number, with the column of
/// the letter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Word {
    /// Upper-case letter (or `@`, `^`).
    pub letter: char,
    /// The value (program units).
    pub value: f64,
    /// Whether the number was written with a decimal point (or was an expression).
    pub has_point: bool,
    /// 1-based column of the letter.
    pub column: usize,
}

/// A block's words sorted out.
#[derive(Debug, Default)]
pub struct Words {
    /// G codes: code x 10, group, action, word.
    pub g: Vec<(u32, Group, Action, Word)>,
    /// M codes that do something: group, action, word.
    pub m: Vec<(Group, Action, Word)>,
    letters: [Option<Word>; LETTERS],
}

impl Words {
    /// Sorts the words of a block (on `line`); harmless unsupported codes go to
    /// `warnings`.
    ///
    /// # Errors
    /// At the offending word: an unknown or refused G code, a refused M code, two codes
    /// of one modal group, a letter given twice.
    /// `lenient_m`: an unknown M code is a warning (the Fanuc dialect: machines add
    /// their own) rather than an error (LinuxCNC refuses it).
    pub fn sort(
        block: &[Word],
        line: usize,
        lenient_m: bool,
        warnings: &mut Warnings,
    ) -> Result<Words, Diagnostic> {
        let mut words = Words::default();
        for &w in block {
            match w.letter {
                'G' => words.g_word(w, line, warnings)?,
                'M' => words.m_word(w, line, lenient_m, warnings)?,
                letter => {
                    let slot = &mut words.letters[letter_index(letter)];
                    if slot.is_some() {
                        return Err(Diagnostic::new(
                            line,
                            w.column,
                            format!("multiple {letter} words in one block"),
                        ));
                    }
                    *slot = Some(w);
                }
            }
        }
        Ok(words)
    }

    fn g_word(&mut self, w: Word, line: usize, warnings: &mut Warnings) -> Result<(), Diagnostic> {
        let err = |message: String| Err(Diagnostic::new(line, w.column, message));
        let code10 = (w.value * 10.0).round();
        if w.value < 0.0 || (w.value * 10.0 - code10).abs() > 1e-6 {
            return err(format!("G{}: not a G code", w.value));
        }
        let code10 = code10 as u32;
        let name = g_name(code10);
        let (group, action) = match g_code(code10) {
            None => return err(format!("unknown G code {name}")),
            Some((_, Effect::Refuse(why))) => return err(format!("{name}: {why}")),
            Some((group, Effect::Warn(why))) => {
                warnings.push(Diagnostic::new(line, w.column, format!("{name}: {why}")));
                (group, Action::Nothing)
            }
            Some((group, Effect::Run(action))) => (group, action),
        };
        if let Some(other) = self.g.iter().find(|g| g.1 == group) {
            return err(format!(
                "two G codes from the same modal group in one block: {} and {name}",
                g_name(other.0)
            ));
        }
        self.g.push((code10, group, action, w));
        Ok(())
    }

    fn m_word(
        &mut self,
        w: Word,
        line: usize,
        lenient: bool,
        warnings: &mut Warnings,
    ) -> Result<(), Diagnostic> {
        let err = |message: String| Err(Diagnostic::new(line, w.column, message));
        if w.value < 0.0 || w.value.fract() != 0.0 || w.value > f64::from(u32::MAX) {
            return err(format!("M{}: not an M code", w.value));
        }
        let m = w.value as u32;
        let (group, action) = match m_code(m) {
            None if lenient => {
                let message = format!("unknown M code M{m} ignored: M codes do not move the axes");
                warnings.push(Diagnostic::new(line, w.column, message));
                return Ok(());
            }
            None => {
                return err(format!(
                    "unknown M code M{m}: LinuxCNC refuses M codes it does not know (a user M \
                     code M100-M199 needs its program in the machine's configuration)"
                ));
            }
            Some((_, Effect::Refuse(why))) => return err(format!("M{m}: {why}")),
            Some((_, Effect::Warn(why))) => {
                warnings.push(Diagnostic::new(line, w.column, format!("M{m}: {why}")));
                return Ok(());
            }
            Some((group, Effect::Run(action))) => (group, action),
        };
        let exclusive = matches!(group, Group::Stop | Group::ToolChange | Group::Spindle);
        if exclusive && self.m.iter().any(|o| o.0 == group) {
            return err(format!(
                "two M codes from the same modal group in one block (M{m})"
            ));
        }
        self.m.push((group, action, w));
        Ok(())
    }

    /// The word with `letter` (upper case), if the block has one.
    pub fn get(&self, letter: char) -> Option<Word> {
        self.letters[letter_index(letter)]
    }

    /// The first axis word of the block (`X Y Z`, and the machine's rotary letters).
    pub fn axis_word(&self, rotary: Option<[char; 2]>) -> Option<Word> {
        let [a, b] = rotary.unwrap_or(['X'; 2]);
        ['X', 'Y', 'Z', a, b]
            .into_iter()
            .filter_map(|l| self.get(l))
            .min_by_key(|w| w.column)
    }

    /// The G word doing `action`, if any.
    pub fn has_g(&self, action: Action) -> Option<Word> {
        self.g.iter().find(|g| g.2 == action).map(|g| g.3)
    }

    /// The motion-group G code of the block, if any: its action and word.
    pub fn motion_code(&self) -> Option<(Action, Word)> {
        self.g
            .iter()
            .find(|g| g.1 == Group::Motion)
            .map(|g| (g.2, g.3))
    }

    /// Refuses letters swarf cannot simulate or that nothing in the block uses, and
    /// warns about harmless unused ones; `mode`: the motion mode the block runs in;
    /// `rotary`: the machine's rotary axis letters when the reader has its kinematics.
    ///
    /// # Errors
    /// At the word: A/B/C without kinematics, a rotary letter the machine does not
    /// have, rotary words on an arc, U/V/W, E, I/J/K/R outside an arc, a cycle or G10,
    /// D without G41/G42.
    pub fn check_letters(
        &self,
        mode: Option<Action>,
        rotary: Option<[char; 2]>,
        line: usize,
        warnings: &mut Warnings,
    ) -> Result<(), Diagnostic> {
        let is_arc = matches!(mode, Some(Action::ArcCw | Action::ArcCcw));
        let cycle = match mode {
            Some(Action::Cycle(n)) => Some(n),
            _ => None,
        };
        let g10 = self.has_g(Action::SetData).is_some();
        let uses_p = is_arc
            || g10
            || self.has_g(Action::Dwell).is_some()
            || self.g.iter().any(|g| g.0 == 640)
            || matches!(cycle, Some(74 | 82 | 84 | 86 | 88 | 89));
        let uses_q = matches!(cycle, Some(73 | 83))
            || self.g.iter().any(|g| g.0 == 640)
            || self.m.iter().any(|m| m.1 == Action::SetTool);
        let comp = self.g.iter().any(|g| matches!(g.2, Action::Comp { .. }));
        for w in self.letters.iter().flatten() {
            let err = |message: String| Err(Diagnostic::new(line, w.column, message));
            let mut warn =
                |message: String| warnings.push(Diagnostic::new(line, w.column, message));
            let l = w.letter;
            match l {
                'A' | 'B' | 'C' => rotary_word(l, is_arc, rotary).or_else(err)?,
                'U' | 'V' | 'W' => {
                    return err(format!("{l} axis word: only X, Y and Z axes are supported"));
                }
                'E' => return err("E word is not supported".to_string()),
                'I' | 'J' | 'K' if !(is_arc || cycle == Some(87) || g10) => {
                    return err(format!("{l} word with no G2, G3 or G87 to use it"));
                }
                'R' if !(is_arc || cycle.is_some() || g10) => {
                    return err(format!(
                        "{l} word with no G2, G3, canned cycle or G10 to use it"
                    ));
                }
                'D' if !comp => return err("D word with no G41 or G42 to use it".into()),
                'P' if !uses_p => {
                    warn("P word ignored: no G2/G3, G4, G10, G64 or dwelling cycle uses it".into())
                }
                'Q' if !uses_q => warn("Q word ignored: no G73, G83, G64 or M61 uses it".into()),
                'L' if !(cycle.is_some() || g10) => {
                    warn("L word ignored: no canned cycle or G10 uses it".into())
                }
                'H' if self.has_g(Action::LengthOffset).is_none() => {
                    warn("H word without G43 ignored".into())
                }
                _ => {}
            }
        }
        Ok(())
    }
}

/// Whether the rotary word `l` can be simulated (see the module docs).
fn rotary_word(l: char, is_arc: bool, rotary: Option<[char; 2]>) -> Result<(), String> {
    match rotary {
        None => Err(format!(
            "rotary axis word {l}: five-axis programs need the machine's kinematics: give a \
             machine file (swarf verify --machine FILE)"
        )),
        Some([a, b]) if l != a && l != b => Err(format!(
            "rotary axis word {l}: the machine's rotary axes are {a} and {b}"
        )),
        Some(_) if is_arc => Err(format!(
            "rotary axis word {l} on an arc (G2/G3): arcs with rotary motion are not supported"
        )),
        Some(_) => Ok(()),
    }
}

/// Word letters: A to Z, then `@` and `^` (LinuxCNC's polar words).
const LETTERS: usize = 28;

fn letter_index(letter: char) -> usize {
    match letter {
        '@' => 26,
        '^' => 27,
        l => (l as usize).saturating_sub('A' as usize).min(25),
    }
}

/// `G90.1` for 901.
pub fn g_name(code10: u32) -> String {
    if code10.is_multiple_of(10) {
        format!("G{}", code10 / 10)
    } else {
        format!("G{}.{}", code10 / 10, code10 % 10)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Space-separated plain words.
    fn plain(text: &str) -> Vec<Word> {
        let mut column = 1;
        let mut out = Vec::new();
        for token in text.split(' ') {
            out.push(Word {
                letter: token.chars().next().unwrap(),
                value: token[1..].parse().unwrap(),
                has_point: token.contains('.'),
                column,
            });
            column += token.len() + 1;
        }
        out
    }

    fn sort(text: &str) -> (Result<Words, Diagnostic>, Vec<Diagnostic>) {
        let mut warnings = Warnings::default();
        let words = Words::sort(&plain(text), 7, true, &mut warnings);
        (words, warnings.finish())
    }

    #[test]
    fn codes_and_letters_are_sorted() {
        let (words, warnings) = sort("G17 G90.1 G1 X1 F100 M3 M8 M7 M123");
        let words = words.unwrap();
        assert_eq!(
            words.g.iter().map(|g| g.0).collect::<Vec<_>>(),
            vec![170, 901, 10]
        );
        assert_eq!(words.motion_code().map(|m| m.0), Some(Action::Linear));
        assert_eq!(words.get('X').map(|w| w.value), Some(1.0));
        assert_eq!(words.m.len(), 3);
        assert_eq!(warnings.len(), 1);
        assert_eq!((warnings[0].line, warnings[0].column), (7, 31));
        assert_eq!(g_name(901), "G90.1");
    }

    #[test]
    fn conflicts_and_bad_codes() {
        let column = |text: &str| sort(text).0.unwrap_err().column;
        assert_eq!(column("G0 X1 G1"), 7);
        assert_eq!(column("G17 G18"), 5);
        assert_eq!(column("M3 M5"), 4);
        assert_eq!(column("X1 Y2 X3"), 7);
        assert_eq!(column("G1.25"), 1);
        assert_eq!(column("G90.2"), 1);
        assert_eq!(column("M1.5"), 1);
        assert!(sort("M7 M8").0.is_ok(), "coolant codes may share a block");
    }

    #[test]
    fn letters_checked_for_the_mode() {
        let check = |text: &str, mode: Option<Action>| {
            let (words, _) = sort(text);
            let mut warnings = Warnings::default();
            let result = words.unwrap().check_letters(mode, None, 7, &mut warnings);
            (result.err().map(|d| d.column), warnings.finish().len())
        };
        let arc = Some(Action::ArcCw);
        assert_eq!(check("X1 I2", None), (Some(4), 0));
        assert_eq!(check("X1 I2 P2", arc), (None, 0));
        assert_eq!(check("X1 P2", None), (None, 1));
        assert_eq!(check("G4 P2", None), (None, 0));
        assert_eq!(check("X1 W2", None), (Some(4), 0));
        assert_eq!(check("G43 H1 D2", None), (Some(8), 0));
        assert_eq!(check("G41 D2", None), (None, 0));
        assert_eq!(check("X1 Y2 R3 Q1", Some(Action::Cycle(83))), (None, 0));
        assert_eq!(check("X1 Y2 R3 Q1", Some(Action::Cycle(81))), (None, 1));
        assert_eq!(check("X1 Y2 I3", Some(Action::Cycle(87))), (None, 0));
    }

    #[test]
    fn rotary_letters_need_and_match_the_machine() {
        let check = |text: &str, is_arc: bool, rotary: Option<[char; 2]>| {
            let (words, _) = sort(text);
            let mut warnings = Warnings::default();
            let mode = if is_arc { Some(Action::ArcCw) } else { None };
            words
                .unwrap()
                .check_letters(mode, rotary, 7, &mut warnings)
                .map_err(|d| (d.column, d.message))
        };
        let e = check("X1 A2", false, None).unwrap_err();
        assert_eq!(e.0, 4);
        assert!(e.1.contains("--machine"), "{}", e.1);
        assert!(check("X1 A2 C3", false, Some(['A', 'C'])).is_ok());
        let e = check("X1 B2", false, Some(['A', 'C'])).unwrap_err();
        assert_eq!(e.0, 4);
        assert!(
            e.1.contains("B: the machine's rotary axes are A and C"),
            "{}",
            e.1
        );
        let e = check("X1 I1 C2", true, Some(['A', 'C'])).unwrap_err();
        assert_eq!(e.0, 7);
        assert!(e.1.contains("on an arc"), "{}", e.1);
        assert!(check("X1 I1", true, Some(['A', 'C'])).is_ok());
    }
}
