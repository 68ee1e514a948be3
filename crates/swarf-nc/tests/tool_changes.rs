//! Every tool change is followed by that tool's length offset, in every built-in
//! post: a program of three tools (T1, T2, T4) read back by swarf's reader with a
//! tool table of three different lengths gives back the tip points written (with the
//! length of a tool that is not in force the tip would be off by the difference), and
//! LinuxCNC's `rs274 -g -t` shows `USE_TOOL_LENGTH_OFFSET` of each tool's length after
//! each `CHANGE_TOOL` (skipped when rs274 is absent, unless
//! `SWARF_REQUIRE_REFERENCES=1`). grbl, which has no tool change, refuses the program
//! by name and writes a one-tool program without a change.

use swarf_geom::Point3;
use swarf_nc::read::{GcodeReadOptions, Program, ToolTable, parse_gcode};
use swarf_nc::{GcodeOptions, NcError, Post, ToolSection, write_gcode_sections};
use swarf_testkit::rs274::{length_after_changes, run_rs274_precise};
use swarf_tool::Pose;
use swarf_toolpath::{Feeds, Move, MoveKind};

/// The tools and their lengths in the table, inches (rs274's machine units).
const TOOLS: [(u32, f64); 3] = [(1, 2.0), (2, 3.5), (4, 4.75)];

fn table_text() -> String {
    TOOLS
        .iter()
        .map(|(t, l)| format!("T{t} P{t} Z{l} D0.25 ;tool {t}\n"))
        .collect()
}

/// A few moves of each tool, at points that differ between tools.
fn moves(tool: u32) -> Vec<Move> {
    let z0 = 10.0 + f64::from(tool);
    let at = |x: f64, y: f64, z: f64, kind: MoveKind| Move {
        to: Pose::vertical(Point3::new(x, y, z)),
        kind,
        feed: 800.0,
        pass: Some(0),
    };
    vec![
        at(1.0, 2.0, z0, MoveKind::Rapid),
        at(1.0, 2.0, -1.5, MoveKind::Feed),
        at(20.0 + f64::from(tool), 2.0, -1.25, MoveKind::Feed),
        at(20.0 + f64::from(tool), 2.0, z0, MoveKind::Rapid),
    ]
}

fn write(post: &str, tools: &[u32]) -> Result<String, NcError> {
    let feeds = Feeds::default();
    let moves: Vec<Vec<Move>> = tools.iter().map(|&t| moves(t)).collect();
    let sections: Vec<ToolSection<'_>> = tools
        .iter()
        .zip(&moves)
        .map(|(&t, m)| ToolSection {
            moves: m,
            feeds: &feeds,
            tool_number: t,
            comments: &[],
        })
        .collect();
    let opts = GcodeOptions {
        post: Post::builtin(post).unwrap(),
        ..GcodeOptions::default()
    };
    write_gcode_sections(&sections, &opts)
}

fn read(post: &str, text: &str, table: &ToolTable) -> Program {
    let opts = GcodeReadOptions {
        language: Post::builtin(post).unwrap().reader(),
        tool_table: Some(table),
        machine_inch: true,
        ..GcodeReadOptions::default()
    };
    parse_gcode(text, &format!("{post}.nc"), &opts).unwrap()
}

/// The largest distance of the motions' ends from the points written, mm.
fn worst_tip_error(p: &Program) -> f64 {
    let want: Vec<Point3> = TOOLS
        .iter()
        .flat_map(|&(t, _)| moves(t))
        .map(|m| m.to.cl)
        .collect();
    assert_eq!(p.motions.len(), want.len());
    p.motions
        .iter()
        .zip(&want)
        .map(|(m, w)| (m.end.cl - w).abs().max())
        .fold(0.0, f64::max)
}

#[test]
fn every_post_offsets_each_tool_by_its_own_length() {
    let table = ToolTable::parse(&table_text(), "tool.tbl").unwrap();
    let numbers = TOOLS.map(|(t, _)| t);
    for post in ["linuxcnc", "fanuc", "mach3", "heidenhain"] {
        let text = write(post, &numbers).unwrap();
        let p = read(post, &text, &table);
        assert!(p.warnings.is_empty(), "{post}: {:?}\n{text}", p.warnings);
        assert_eq!(
            p.tools.iter().map(|t| t.number).collect::<Vec<_>>(),
            numbers,
            "{post}"
        );
        let e = worst_tip_error(&p);
        assert!(e < 1e-4, "{post}: tips off by {e} mm\n{text}");
        if post != "heidenhain" {
            // The oracle tells: without the offsets the tips sit a tool length low.
            let bare: String = text
                .lines()
                .filter(|l| !l.contains("G43"))
                .collect::<Vec<_>>()
                .join("\n");
            let e = worst_tip_error(&read(post, &bare, &table));
            assert!(e > 2.0 * 25.4 - 1e-6, "{post}: without G43 off by only {e}");
        }
    }
}

#[test]
fn rs274_puts_each_tools_length_in_force_after_its_change() {
    let dir = std::env::temp_dir().join(format!("swarf-tool-changes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tool.tbl"), table_text()).unwrap();
    for post in ["linuxcnc", "mach3"] {
        let text = write(post, &TOOLS.map(|(t, _)| t)).unwrap();
        let name = format!("{post}.ngc");
        std::fs::write(dir.join(&name), &text).unwrap();
        let Some(out) = run_rs274_precise(&dir, &name, "tool.tbl") else {
            return;
        };
        assert!(out.contains("--- exit 0"), "{post}: rs274 failed:\n{out}");
        let got = length_after_changes(&out);
        let want: Vec<(u32, Option<f64>)> =
            TOOLS.iter().map(|&(t, l)| (t, Some(l * 25.4))).collect();
        assert_eq!(got.len(), want.len(), "{post}: {got:?}\n{out}");
        for (g, w) in got.iter().zip(&want) {
            assert_eq!(g.0, w.0, "{post}: {got:?}");
            let (gz, wz) = (g.1.unwrap_or(f64::NAN), w.1.unwrap());
            assert!(
                (gz - wz).abs() < 1e-6,
                "{post}: T{}: {gz} vs {wz}\n{out}",
                g.0
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn grbl_refuses_several_tools_by_name_and_writes_one_without_a_change() {
    let e = write("grbl", &[1, 2, 4]).unwrap_err().to_string();
    assert_eq!(
        e,
        "post grbl: tool.change: 3-axis program with 3 tools (T1, T2, T4): the control has \
         no tool change; write one program per tool"
    );
    let one = write("grbl", &[2]).unwrap();
    for word in ["M6", "M0", "G43", "T2"] {
        assert!(!one.contains(word), "{word} in\n{one}");
    }
    assert!(one.contains("S"), "{one}");
    // The same tool twice is still one tool.
    assert!(write("grbl", &[2, 2]).is_ok());
}
