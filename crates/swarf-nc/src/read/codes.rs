//! The G and M codes the G-code reader knows, as a table: each code's modal group and
//! what swarf does with it (as CAMotics keeps G-code semantics in a table of codes).
//!
//! Three outcomes: a code swarf simulates or that cannot move the tool (`Run`), a code
//! that is read but not simulated and cannot change the tool's path (`Warn`: the
//! reader records a warning), and a code that would change the path in a way swarf
//! does not simulate (`Refuse`: reading stops with an error). An unknown G code is
//! refused; an unknown M code is a warning, because M codes switch machine functions
//! and do not move the axes (subprogram calls `M98`/`M99` excepted, which are
//! refused). Groups follow the RS274/NGC modal groups: two codes of one group in one
//! block are an error, as in LinuxCNC.

/// RS274/NGC modal groups (and the non-modal group 0), for the one-per-block check.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Group {
    /// G0 G1 G2 G3 G80 and the other motion codes (group 1).
    Motion,
    /// G17 G18 G19 (group 2).
    Plane,
    /// G90 G91 (group 3).
    Distance,
    /// G90.1 G91.1 (group 4).
    ArcDistance,
    /// G93 G94 G95 (group 5).
    FeedMode,
    /// G20 G21 (group 6).
    Units,
    /// G40 G41 G42 (group 7).
    CutterComp,
    /// G43 G49 (group 8).
    ToolLength,
    /// G98 G99 (group 10).
    ReturnMode,
    /// G54 ... G59.3 (group 12).
    CoordSystem,
    /// G61 G61.1 G64 (group 13).
    PathControl,
    /// G96 G97 (group 14).
    SpindleMode,
    /// G4 G10 G28 G30 G52 G53 G92 ... (group 0, non-modal).
    NonModal,
    /// G7 G8 (lathe diameter mode, group 15).
    Lathe,
    /// M0 M1 M2 M30 M60 (M group 4).
    Stop,
    /// M6 M61 (M group 6).
    ToolChange,
    /// M3 M4 M5 (M group 7).
    Spindle,
    /// M7 M8 M9: several may share a block.
    Coolant,
    /// Other M codes: several may share a block.
    OtherM,
}

/// What a code does in swarf's model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// Straight rapid (G0).
    Rapid,
    /// Straight feed (G1).
    Linear,
    /// Clockwise arc (G2).
    ArcCw,
    /// Counter-clockwise arc (G3).
    ArcCcw,
    /// A canned cycle: G73, G74, G81 ... G89 (the number).
    Cycle(u8),
    /// Cancel the motion mode (G80): axis words are then an error.
    CancelMotion,
    /// Arc plane XY (G17).
    PlaneXy,
    /// Arc plane XZ (G18).
    PlaneXz,
    /// Arc plane YZ (G19).
    PlaneYz,
    /// Absolute coordinates (G90).
    Absolute,
    /// Incremental coordinates (G91).
    Incremental,
    /// Arc centres absolute (G90.1).
    ArcAbsolute,
    /// Arc centres relative to the start (G91.1).
    ArcIncremental,
    /// Inches (G20).
    Inch,
    /// Millimetres (G21).
    Mm,
    /// Inverse-time feed (G93): `F` on each feed block is 1 / its time in minutes.
    InverseTime,
    /// Units-per-minute feed (G94); sets the feed rate to 0, as LinuxCNC does.
    UnitsPerMinute,
    /// Cutter radius compensation off (G40).
    CompOff,
    /// Cutter radius compensation: left (G41, G41.1) or right (G42, G42.1) of the
    /// path; `diameter`: the D word is the tool diameter (G41.1, G42.1), not a tool
    /// number.
    Comp {
        /// Left of the path (G41).
        left: bool,
        /// D is a diameter.
        diameter: bool,
    },
    /// Tool length offset from the tool table (G43).
    LengthOffset,
    /// Tool length offset cancelled (G49).
    LengthOffsetOff,
    /// Tool length offset from the block's axis words (G43.1).
    LengthOffsetGiven,
    /// Tool length offset plus tool H's (G43.2).
    LengthOffsetAdd,
    /// Coordinate system 1 (G54) to 9 (G59.3).
    CoordSystem(u8),
    /// Canned cycles retract to the initial level (G98).
    RetractOldZ,
    /// Canned cycles retract to R (G99).
    RetractR,
    /// G10: coordinate systems (L2, L20) and the tool table (L1, L10, L11).
    SetData,
    /// Move to the stored position #5161 (G28) or #5181 (G30) through the axes given.
    Home {
        /// G30 rather than G28.
        second: bool,
    },
    /// Store the current position as G28's (G28.1) or G30's (G30.1).
    SaveHome {
        /// G30.1 rather than G28.1.
        second: bool,
    },
    /// Axis offsets: G52 (local), G92 (so that the point has these coordinates).
    AxisOffset {
        /// G52 rather than G92.
        local: bool,
    },
    /// G92.1 (reset and zero the parameters), G92.2 (suspend).
    AxisOffsetOff {
        /// G92.1: also zero #5211-#5219.
        zero_params: bool,
    },
    /// G92.3: restore the offsets from #5211-#5219.
    AxisOffsetRestore,
    /// Move in machine coordinates (G53).
    MachineCoords,
    /// Dwell (G4), no motion.
    Dwell,
    /// Program stop (M0, M1): reading goes on.
    Pause,
    /// Program end (M2, M30): reading stops.
    End,
    /// Tool change (M6).
    ToolChange,
    /// Set the loaded tool without a change (M61 Q).
    SetTool,
    /// Spindle on clockwise (M3), counter-clockwise (M4), stopped (M5).
    Spindle(SpindleTurn),
    /// Nothing to simulate: a mode swarf's model already assumes, or a machine
    /// function that does not move the tool.
    Nothing,
}

/// How the spindle turns (for the cycles that need it turning).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpindleTurn {
    /// M5, and at the start.
    #[default]
    Stopped,
    /// M3.
    Clockwise,
    /// M4.
    CounterClockwise,
}

/// The outcome of looking a code up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Effect {
    /// Simulated, or harmless without a warning.
    Run(Action),
    /// Read, not simulated, harmless: a warning with this text.
    Warn(&'static str),
    /// Not simulated and could change the tool path: an error with this text.
    Refuse(&'static str),
}

/// The G code `code10` (ten times the number: G90.1 is 901).
pub fn g_code(code10: u32) -> Option<(Group, Effect)> {
    use Action as A;
    use Effect::{Refuse, Run};
    use Group as Gr;
    let entry = match code10 {
        0 => (Gr::Motion, Run(A::Rapid)),
        10 => (Gr::Motion, Run(A::Linear)),
        20 => (Gr::Motion, Run(A::ArcCw)),
        30 => (Gr::Motion, Run(A::ArcCcw)),
        800 => (Gr::Motion, Run(A::CancelMotion)),
        50..=53 => (
            Gr::Motion,
            Refuse("spline moves (G5, G5.1, G5.2) are not supported"),
        ),
        330 | 331 | 760 => (Gr::Motion, Refuse("threading moves are not supported")),
        700 | 710 | 711 | 712 | 720 | 721 | 722 => (
            Gr::Motion,
            Refuse("lathe roughing and finishing cycles (G70-G72) are not supported"),
        ),
        382..=385 => (Gr::Motion, Refuse("probing moves (G38) are not supported")),
        730 | 740 | 810..=890 if code10.is_multiple_of(10) => {
            (Gr::Motion, Run(A::Cycle((code10 / 10) as u8)))
        }
        170 => (Gr::Plane, Run(A::PlaneXy)),
        180 => (Gr::Plane, Run(A::PlaneXz)),
        190 => (Gr::Plane, Run(A::PlaneYz)),
        171 | 181 | 191 => (
            Gr::Plane,
            Refuse("UVW planes (G17.1, G18.1, G19.1) are not supported"),
        ),
        900 => (Gr::Distance, Run(A::Absolute)),
        910 => (Gr::Distance, Run(A::Incremental)),
        901 => (Gr::ArcDistance, Run(A::ArcAbsolute)),
        911 => (Gr::ArcDistance, Run(A::ArcIncremental)),
        930 => (Gr::FeedMode, Run(A::InverseTime)),
        940 => (Gr::FeedMode, Run(A::UnitsPerMinute)),
        950 => (
            Gr::FeedMode,
            Refuse("feed per revolution (G95) is not supported"),
        ),
        200 => (Gr::Units, Run(A::Inch)),
        210 => (Gr::Units, Run(A::Mm)),
        400 => (Gr::CutterComp, Run(A::CompOff)),
        410 | 411 | 420 | 421 => (
            Gr::CutterComp,
            Run(A::Comp {
                left: code10 < 420,
                diameter: code10 % 10 == 1,
            }),
        ),
        430 => (Gr::ToolLength, Run(A::LengthOffset)),
        490 => (Gr::ToolLength, Run(A::LengthOffsetOff)),
        431 => (Gr::ToolLength, Run(A::LengthOffsetGiven)),
        432 => (Gr::ToolLength, Run(A::LengthOffsetAdd)),
        _ => return other_g_code(code10),
    };
    Some(entry)
}

/// The G codes of [`g_code`] outside the motion, plane, distance, feed, units and
/// compensation groups.
fn other_g_code(code10: u32) -> Option<(Group, Effect)> {
    use Action as A;
    use Effect::{Refuse, Run, Warn};
    use Group as Gr;
    let entry = match code10 {
        980 => (Gr::ReturnMode, Run(A::RetractOldZ)),
        990 => (Gr::ReturnMode, Run(A::RetractR)),
        540 | 550 | 560 | 570 | 580 | 590 => (
            Gr::CoordSystem,
            Run(A::CoordSystem((code10 / 10 - 53) as u8)),
        ),
        591..=593 => (
            Gr::CoordSystem,
            Run(A::CoordSystem((code10 - 591 + 7) as u8)),
        ),
        610 | 611 => (Gr::PathControl, Run(A::Nothing)),
        640 => (
            Gr::PathControl,
            Warn(
                "G64 path blending: the control may round corners (up to the P tolerance); swarf simulates the exact path",
            ),
        ),
        960 => (
            Gr::SpindleMode,
            Warn("constant surface speed (G96) ignored: the spindle is not simulated"),
        ),
        970 => (Gr::SpindleMode, Run(A::Nothing)),
        40 => (Gr::NonModal, Run(A::Dwell)),
        100 => (Gr::NonModal, Run(A::SetData)),
        280 | 300 => (
            Gr::NonModal,
            Run(A::Home {
                second: code10 == 300,
            }),
        ),
        281 | 301 => (
            Gr::NonModal,
            Run(A::SaveHome {
                second: code10 == 301,
            }),
        ),
        520 => (Gr::NonModal, Run(A::AxisOffset { local: true })),
        530 => (Gr::NonModal, Run(A::MachineCoords)),
        920 => (Gr::NonModal, Run(A::AxisOffset { local: false })),
        921 | 922 => (
            Gr::NonModal,
            Run(A::AxisOffsetOff {
                zero_params: code10 == 921,
            }),
        ),
        923 => (Gr::NonModal, Run(A::AxisOffsetRestore)),
        70 | 80 => (
            Gr::Lathe,
            Refuse("lathe diameter/radius modes (G7/G8) are not supported"),
        ),
        _ => return None,
    };
    Some(entry)
}

/// The M code `m`. Unknown M codes are `None`; the reader warns about them.
pub fn m_code(m: u32) -> Option<(Group, Effect)> {
    use Action as A;
    use Effect::{Refuse, Run, Warn};
    use Group as Gr;
    let entry = match m {
        0 | 1 => (Gr::Stop, Run(A::Pause)),
        2 | 30 => (Gr::Stop, Run(A::End)),
        60 => (Gr::Stop, Warn("M60 pallet change ignored")),
        6 => (Gr::ToolChange, Run(A::ToolChange)),
        61 => (Gr::ToolChange, Run(A::SetTool)),
        3 => (Gr::Spindle, Run(A::Spindle(SpindleTurn::Clockwise))),
        4 => (Gr::Spindle, Run(A::Spindle(SpindleTurn::CounterClockwise))),
        5 => (Gr::Spindle, Run(A::Spindle(SpindleTurn::Stopped))),
        7..=9 => (Gr::Coolant, Run(A::Nothing)),
        19 => (Gr::OtherM, Warn("spindle orientation (M19) ignored")),
        48..=53 => (
            Gr::OtherM,
            Warn("override switches ignored: times assume 100% feed"),
        ),
        62..=68 => (Gr::OtherM, Warn("digital/analog output M codes ignored")),
        70 | 71 => (Gr::OtherM, Warn("M70/M71 ignored (saving modal state)")),
        72 | 73 => (
            Gr::OtherM,
            Refuse("restoring modal state (M72/M73) is not supported"),
        ),
        98 | 99 => (
            Gr::OtherM,
            Refuse(
                "subprogram calls and returns (M98/M99) belong to the Fanuc dialect: read the program with --dialect fanuc",
            ),
        ),
        _ => return None,
    };
    Some(entry)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn motion_codes_and_refusals() {
        assert_eq!(
            g_code(20),
            Some((Group::Motion, Effect::Run(Action::ArcCw)))
        );
        assert_eq!(
            g_code(901),
            Some((Group::ArcDistance, Effect::Run(Action::ArcAbsolute)))
        );
        assert_eq!(
            g_code(930),
            Some((Group::FeedMode, Effect::Run(Action::InverseTime)))
        );
        assert_eq!(
            g_code(830),
            Some((Group::Motion, Effect::Run(Action::Cycle(83))))
        );
        assert_eq!(
            g_code(592),
            Some((Group::CoordSystem, Effect::Run(Action::CoordSystem(8))))
        );
        assert_eq!(
            g_code(540),
            Some((Group::CoordSystem, Effect::Run(Action::CoordSystem(1))))
        );
        for refused in [950, 50, 382, 331] {
            assert!(
                matches!(g_code(refused), Some((_, Effect::Refuse(_)))),
                "G{refused}"
            );
        }
        for unknown in [120, 150, 680, 902, 11, 815] {
            assert_eq!(g_code(unknown), None, "G{}", f64::from(unknown) / 10.0);
        }
    }

    #[test]
    fn m_codes() {
        assert_eq!(m_code(30), Some((Group::Stop, Effect::Run(Action::End))));
        assert!(matches!(m_code(98), Some((_, Effect::Refuse(_)))));
        assert_eq!(m_code(150), None);
        assert_eq!(m_code(555), None);
    }
}
