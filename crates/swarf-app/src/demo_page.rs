//! The demo's page (`index.html` in its output folder, [`swarf_report::html`]): each
//! section's console text as it was printed (its tables as tables), its wall time,
//! the pictures and reports of every verified program with its verification summary,
//! and links to the 3D views. Only files staged in the demo's output set are linked
//! ([`Outputs::is_staged`]), and the page's links are checked against the set again
//! before it is staged ([`stage_page`]), so the folder it is committed with holds
//! every file it names.
//!
//! Where two strategies give identical figures the page says why
//! ([`coinciding`]): on `wave` the surface's y depends only on v, so the
//! iso-parametric passes along u (v constant) lie in the iso-planar drive planes
//! y = const, and both strategies cut the same passes.

use crate::compare::{FiveAxisRow, Row};
use crate::error::{AppError, Result};
use crate::outputs::Outputs;
use std::io::Write;
use std::path::Path;
use std::time::Instant;
use swarf_report::html::{Block, Figure, Page, Section};
use swarf_sim::report::count;

/// A writer that prints to the console and keeps a copy for the page.
pub(crate) struct Tee<'a> {
    out: &'a mut dyn Write,
    copy: Vec<u8>,
}

impl Write for Tee<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.out.write(buf)?;
        self.copy.extend_from_slice(&buf[..n]);
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}

/// The demo's sections as they run: each printed, timed and kept for the page.
pub(crate) struct Sections<'a> {
    /// The console.
    pub text: &'a mut dyn Write,
    /// The sections done.
    pub done: Vec<Section>,
}

impl Sections<'_> {
    /// Runs the section `title`: `run` prints to the console (and the page) and gives
    /// the blocks the page shows after that text (a printed line that is one of its
    /// notes is shown as the note only); the section's wall time is printed after it.
    pub(crate) fn run(
        &mut self,
        title: &str,
        run: impl FnOnce(&mut dyn Write) -> Result<Vec<Block>>,
    ) -> Result<()> {
        let start = Instant::now();
        writeln!(self.text, "\n== {title}")?;
        let mut tee = Tee {
            out: &mut *self.text,
            copy: Vec::new(),
        };
        let blocks = run(&mut tee)?;
        let notes: Vec<&str> = blocks
            .iter()
            .filter_map(|b| match b {
                Block::Note(n) => Some(n.as_str()),
                _ => None,
            })
            .collect();
        let printed: String = String::from_utf8_lossy(&tee.copy)
            .lines()
            .filter(|l| !notes.contains(l))
            .map(|l| format!("{l}\n"))
            .collect();
        let seconds = start.elapsed().as_secs_f64();
        writeln!(self.text, "(section: {seconds:.1} s)")?;
        let mut all = vec![Block::Text(printed)];
        all.extend(blocks);
        self.done.push(Section {
            title: title.to_string(),
            seconds,
            blocks: all,
        });
        Ok(())
    }
}

/// The blocks of one verified program whose files are `{dir}/{stem}.*`: its
/// summary, its pictures and its links (those staged in `out`).
pub(crate) fn program_blocks(out: &Outputs, dir: &str, stem: &str, summary: &str) -> Vec<Block> {
    let path = |name: &str| format!("{dir}/{stem}.{name}");
    let figures: Vec<Figure> = [
        ("deviation.png", "deviation from the design"),
        ("toolpath.png", "tool path"),
    ]
    .into_iter()
    .filter(|(name, _)| out.is_staged(path(name)))
    .map(|(name, what)| Figure {
        src: path(name),
        caption: format!("{stem}: {what}"),
    })
    .collect();
    let links: Vec<(String, String)> = [
        ("view/index.html", "3D view"),
        ("view/view.json", "3D view data"),
        ("report.json", "verification report"),
        ("flagged.csv", "flagged cells"),
        ("ngc", "G-code"),
        ("cl", "APT CL"),
        ("plan.json", "plan summary"),
    ]
    .into_iter()
    .filter(|(name, _)| out.is_staged(path(name)))
    .map(|(name, label)| (path(name), format!("{stem} {label}")))
    .collect();
    let mut blocks = vec![Block::Note(format!("{stem}: {summary}"))];
    if !figures.is_empty() {
        blocks.push(Block::Figures(figures));
    }
    if !links.is_empty() {
        blocks.push(Block::Links(links));
    }
    blocks
}

/// The verification summary of a Table 1 row.
pub(crate) fn row_summary(r: &Row) -> String {
    let scallop = match r.scallop_mm {
        [Some(a), Some(b), Some(m)] => format!("scallop {a:.3}-{b:.3} mm (highest {m:.3})"),
        _ => "no scallop crests".into(),
    };
    let gouge = if r.gouge_points == 0 {
        "no gouge".to_string()
    } else {
        format!(
            "gouge {} ({}), deepest {:.3} mm",
            count(r.gouge_points, "cell"),
            count(r.gouge_regions, "region"),
            r.deepest_gouge_mm
        )
    };
    format!(
        "{gouge}; {scallop}; {} of material left above the limit (cells of {} mm){}",
        count(r.remaining_points, "cell"),
        r.cell_mm,
        if r.incomplete {
            "; the program stopped early"
        } else {
            ""
        }
    )
}

/// The verification summary of a five-axis row.
pub(crate) fn five_axis_summary(r: &FiveAxisRow) -> String {
    let dexel = if r.dexel_gouge_cells == 0 {
        "no gouge on the dexel stock".to_string()
    } else {
        format!(
            "gouge on the dexel stock {} ({}), deepest {:.3} mm",
            count(r.dexel_gouge_cells, "cell"),
            count(r.dexel_gouge_regions, "region"),
            r.dexel_deepest_mm
        )
    };
    format!(
        "{} of {} poses gouge by sectioning; {dexel}; planned in {:.1} s, verified in {:.1} s",
        r.gouging_poses, r.poses, r.planning_s, r.verify_s
    )
}

/// Notes on Table 1 rows of different strategies whose figures print the same, and
/// why they coincide on `part`.
pub(crate) fn coinciding(rows: &[Row], part: &str) -> Vec<String> {
    let figures = |r: &Row| {
        let table = crate::compare::markdown(std::slice::from_ref(r));
        let line = table.lines().nth(2).unwrap_or_default().to_string();
        line.split('|').skip(3).collect::<Vec<_>>().join("|")
    };
    let same = |a: &Row, b: &Row| a.strategy != b.strategy && figures(a) == figures(b);
    let mut notes = Vec::new();
    for (k, a) in rows.iter().enumerate() {
        for b in rows[k + 1..].iter().filter(|b| same(a, b)) {
            let pair = [a.strategy.as_str(), b.strategy.as_str()];
            let why = if part == "wave"
                && pair.contains(&"iso-parametric")
                && pair.contains(&"iso-planar")
            {
                "on wave the surface's y depends only on v, so each iso-parametric pass \
                 along u (v constant) lies in a plane y = const, the iso-planar drive \
                 planes (angle 0): both strategies space those planes by the same scallop \
                 rule and cut the same passes. This is the part, not a bug; on a part whose \
                 v-lines are not plane sections they differ."
            } else {
                "their passes coincide on this part."
            };
            notes.push(format!(
                "{} ({}) and {} ({}) give the same figures: {why}",
                a.job, a.strategy, b.job, b.strategy
            ));
        }
    }
    notes
}

/// The page of `sections`, checked: every relative link names a file staged in
/// `out` (relative to its folder); staged as `index.html`.
///
/// # Errors
/// A link to a file not in the set (a bug of the demo); the page cannot be staged.
pub(crate) fn stage_page(out: &mut Outputs, sections: Vec<Section>, total_s: f64) -> Result<()> {
    let page = Page {
        title: "swarf demo".into(),
        intro: vec![
            format!(
                "What swarf demo printed, section by section, with the pictures, \
                 verification summaries and 3D views it wrote; {total_s:.1} s in all. \
                 Every link is a file in this folder."
            ),
            "Deviation pictures: red below the design (gouge), blue above (material \
             left), grey within the tolerance; the colour scale runs from the 1st to \
             the 99th percentile, cells past it are magenta (below) or cyan (above)."
                .into(),
        ],
        sections,
    };
    let html = swarf_report::html::render(&page);
    let missing: Vec<String> = swarf_report::html::relative_links(&html)
        .into_iter()
        .filter(|l| !out.is_staged(Path::new(l)))
        .collect();
    if !missing.is_empty() {
        return Err(AppError::Message(format!(
            "index.html links to files the demo did not write: {}",
            missing.join(", ")
        )));
    }
    out.write("index.html", html.as_bytes())
}

#[cfg(test)]
mod tests;
