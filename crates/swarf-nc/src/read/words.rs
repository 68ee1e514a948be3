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
use crate::read::lexer::{Block, Word};
use crate::read::program::Diagnostic;
use crate::read::warnings::Warnings;

/// A block's words sorted out.
#[derive(Debug, Default)]
pub struct Words {
    /// G codes: code x 10, group, action, word.
    pub g: Vec<(u32, Group, Action, Word)>,
    /// M codes that do something: group, action, word.
    pub m: Vec<(Group, Action, Word)>,
    letters: [Option<Word>; 26],
}

impl Words {
    /// Sorts `block` (on `line`); harmless unsupported codes go to `warnings`.
    ///
    /// # Errors
    /// At the offending word: an unknown or refused G code, a refused M code, two codes
    /// of one modal group, a letter given twice.
    pub fn sort(block: &Block, line: usize, warnings: &mut Warnings) -> Result<Words, Diagnostic> {
        let mut words = Words::default();
        for &w in &block.words {
            match w.letter {
                'G' => words.g_word(w, line, warnings)?,
                'M' => words.m_word(w, line, warnings)?,
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

    fn m_word(&mut self, w: Word, line: usize, warnings: &mut Warnings) -> Result<(), Diagnostic> {
        let err = |message: String| Err(Diagnostic::new(line, w.column, message));
        if w.value < 0.0 || w.value.fract() != 0.0 || w.value > f64::from(u32::MAX) {
            return err(format!("M{}: not an M code", w.value));
        }
        let m = w.value as u32;
        let (group, action) = match m_code(m) {
            None => {
                let message = format!("unknown M code M{m} ignored: M codes do not move the axes");
                warnings.push(Diagnostic::new(line, w.column, message));
                return Ok(());
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

    /// Refuses letters swarf cannot simulate and warns about unused ones; `is_arc`:
    /// the block runs in G2/G3 mode (so I, J, K, R and P have a use); `rotary`: the
    /// machine's rotary axis letters when the reader has its kinematics.
    ///
    /// # Errors
    /// At the word: A/B/C without kinematics, a rotary letter the machine does not
    /// have, rotary words on an arc, U/V/W, E, and I/J/K/R outside arc mode.
    pub fn check_letters(
        &self,
        is_arc: bool,
        rotary: Option<[char; 2]>,
        line: usize,
        warnings: &mut Warnings,
    ) -> Result<(), Diagnostic> {
        let dwell_or_blend =
            self.has_g(Action::Dwell).is_some() || self.g.iter().any(|g| g.0 == 640);
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
                'I' | 'J' | 'K' | 'R' if !is_arc => {
                    return err(format!("{l} word with no G2 or G3 to use it"));
                }
                'P' if !(is_arc || dwell_or_blend) => {
                    warn("P word ignored: no G2/G3, G4 or G64 uses it".into())
                }
                'Q' | 'L' | 'D' => warn(format!("{l} word ignored")),
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

fn letter_index(letter: char) -> usize {
    (letter as usize).saturating_sub('A' as usize).min(25)
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
    use crate::read::lexer::lex_line;

    fn sort(text: &str) -> (Result<Words, Diagnostic>, Vec<Diagnostic>) {
        let mut warnings = Warnings::default();
        let block = lex_line(text, 7).unwrap();
        let words = Words::sort(&block, 7, &mut warnings);
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
        let check = |text: &str, is_arc: bool| {
            let (words, _) = sort(text);
            let mut warnings = Warnings::default();
            let result = words.unwrap().check_letters(is_arc, None, 7, &mut warnings);
            (result.err().map(|d| d.column), warnings.finish().len())
        };
        assert_eq!(check("X1 I2", false), (Some(4), 0));
        assert_eq!(check("X1 I2 P2", true), (None, 0));
        assert_eq!(check("X1 P2", false), (None, 1));
        assert_eq!(check("G4 P2", false), (None, 0));
        assert_eq!(check("X1 W2", false), (Some(4), 0));
        assert_eq!(check("G43 H1 D2", false), (None, 1));
    }

    #[test]
    fn rotary_letters_need_and_match_the_machine() {
        let check = |text: &str, is_arc: bool, rotary: Option<[char; 2]>| {
            let (words, _) = sort(text);
            let mut warnings = Warnings::default();
            words
                .unwrap()
                .check_letters(is_arc, rotary, 7, &mut warnings)
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
