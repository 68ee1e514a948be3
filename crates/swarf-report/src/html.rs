//! The report page: one self-contained HTML file (`index.html` of `swarf demo`) that
//! a browser opens from disk: inline CSS, no script, nothing fetched from a network.
//! It holds what a run printed, section by section with the wall time each took, its
//! Markdown tables as HTML tables, its pictures (relative `<img>` links to the PNGs
//! beside the page), and links to the other files (3D views, reports, programs).
//!
//! Every link is relative to the page's folder; [`relative_links`] lists them again
//! from the page text, so that whoever writes the page can check each names a file
//! it writes with it.

use std::fmt::Write;

/// A report page.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Page {
    /// Title (the `<title>` and the heading).
    pub title: String,
    /// Paragraphs under the heading.
    pub intro: Vec<String>,
    /// The sections, in order.
    pub sections: Vec<Section>,
}

/// One section of a page.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Section {
    /// Heading.
    pub title: String,
    /// Wall time the section took, s.
    pub seconds: f64,
    /// What it shows, in order.
    pub blocks: Vec<Block>,
}

/// A piece of a section.
#[derive(Debug, Clone, PartialEq)]
pub enum Block {
    /// Console text: runs of lines starting with `|` are Markdown tables and become
    /// tables, the other lines are kept as they were printed (a run longer than
    /// [`FOLD_LINES`] folded under a summary line, which a reader opens).
    Text(String),
    /// A paragraph that explains what is shown.
    Note(String),
    /// Pictures side by side.
    Figures(Vec<Figure>),
    /// Links, one line: `(relative path, label)`.
    Links(Vec<(String, String)>),
}

/// A picture with its caption.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Path of the PNG relative to the page.
    pub src: String,
    /// Caption (also the `alt` text).
    pub caption: String,
}

/// Console runs longer than this many lines are folded (`<details>`, no script).
pub const FOLD_LINES: usize = 12;

/// The page's style sheet.
const STYLE: &str = "body{font:15px/1.45 system-ui,sans-serif;margin:2em auto;max-width:1200px;\
padding:0 1em;color:#1b1b1b;background:#fff}h1{font-size:1.7em}h2{margin-top:2em;\
border-bottom:2px solid #ccd;padding-bottom:.2em}h2 .t{float:right;font-weight:normal;\
font-size:.7em;color:#555}table{border-collapse:collapse;margin:.8em 0;font-size:13px}\
td,th{border:1px solid #bbc;padding:.25em .5em;text-align:left;vertical-align:top}\
th{background:#eef}tr:nth-child(even) td{background:#f7f7fb}pre{background:#f4f4f4;\
padding:.6em;overflow-x:auto;font-size:12.5px}.note{background:#fff8e0;border-left:4px \
solid #e0b000;padding:.5em .8em}.figs{display:flex;flex-wrap:wrap;gap:1em}figure{margin:0;\
flex:1 1 420px;max-width:560px}figure img{width:100%;border:1px solid #ccc}figcaption{\
font-size:13px;color:#333}.links a{margin-right:1.2em}summary{cursor:pointer;color:#335}";

/// The page as HTML text.
pub fn render(page: &Page) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<h1>{}</h1>\n",
        esc(&page.title),
        esc(&page.title)
    );
    for p in &page.intro {
        let _ = writeln!(h, "<p>{}</p>", esc(p));
    }
    contents(&mut h, page);
    for (k, s) in page.sections.iter().enumerate() {
        let _ = writeln!(
            h,
            "<section id=\"s{}\">\n<h2>{} <span class=\"t\">{:.1} s</span></h2>",
            k + 1,
            esc(&s.title),
            s.seconds
        );
        for b in &s.blocks {
            block(&mut h, b);
        }
        h.push_str("</section>\n");
    }
    h.push_str("</body>\n</html>\n");
    h
}

/// The table of sections with their times.
fn contents(h: &mut String, page: &Page) {
    h.push_str("<table>\n<tr><th>section</th><th>wall time</th></tr>\n");
    for (k, s) in page.sections.iter().enumerate() {
        let _ = writeln!(
            h,
            "<tr><td><a href=\"#s{}\">{}</a></td><td>{:.1} s</td></tr>",
            k + 1,
            esc(&s.title),
            s.seconds
        );
    }
    let total: f64 = page.sections.iter().map(|s| s.seconds).sum();
    let _ = writeln!(h, "<tr><th>all</th><th>{total:.1} s</th></tr>\n</table>");
}

/// One block of a section.
fn block(h: &mut String, b: &Block) {
    match b {
        Block::Text(text) => console(h, text),
        Block::Note(text) => {
            let _ = writeln!(h, "<p class=\"note\">{}</p>", esc(text));
        }
        Block::Figures(figs) => {
            h.push_str("<div class=\"figs\">\n");
            for f in figs {
                let _ = writeln!(
                    h,
                    "<figure><a href=\"{src}\"><img src=\"{src}\" alt=\"{alt}\"></a>\
                     <figcaption>{alt}</figcaption></figure>",
                    src = href(&f.src),
                    alt = esc(&f.caption)
                );
            }
            h.push_str("</div>\n");
        }
        Block::Links(links) => {
            h.push_str("<p class=\"links\">");
            for (path, label) in links {
                let _ = write!(h, "<a href=\"{}\">{}</a> ", href(path), esc(label));
            }
            h.push_str("</p>\n");
        }
    }
}

/// Console text: Markdown tables as tables, other runs of lines preformatted.
fn console(h: &mut String, text: &str) {
    let mut lines = text.lines().peekable();
    while lines.peek().is_some() {
        let is_row = |l: &&str| l.trim_start().starts_with('|');
        let mut run = Vec::new();
        let table = lines.peek().is_some_and(is_row);
        while let Some(l) = lines.next_if(|l| is_row(l) == table) {
            run.push(l);
        }
        if table {
            markdown_table(h, &run);
        } else {
            let body = run.join("\n");
            let body = body.trim_matches('\n');
            if body.trim().is_empty() {
                continue;
            }
            let n = body.lines().count();
            if n > FOLD_LINES {
                let _ = writeln!(
                    h,
                    "<details><summary>console output, {n} lines</summary><pre>{}</pre></details>",
                    esc(body)
                );
            } else {
                let _ = writeln!(h, "<pre>{}</pre>", esc(body));
            }
        }
    }
}

/// A Markdown table (its first row the header; separator rows left out).
fn markdown_table(h: &mut String, rows: &[&str]) {
    h.push_str("<table>\n");
    for (k, row) in rows.iter().enumerate() {
        let cells: Vec<&str> = row
            .trim()
            .trim_start_matches('|')
            .trim_end_matches('|')
            .split('|')
            .map(str::trim)
            .collect();
        if cells
            .iter()
            .all(|c| !c.is_empty() && c.chars().all(|ch| matches!(ch, '-' | ':')))
        {
            continue;
        }
        let tag = if k == 0 { "th" } else { "td" };
        h.push_str("<tr>");
        for c in cells {
            let _ = write!(h, "<{tag}>{}</{tag}>", esc(c));
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");
}

/// `s` with the characters HTML gives a meaning escaped.
pub fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(ch),
        }
    }
    out
}

/// A relative path as an attribute value: the characters a URL gives a meaning
/// (and spaces) percent-encoded, then HTML-escaped.
fn href(path: &str) -> String {
    let mut out = String::new();
    for ch in path.chars() {
        match ch {
            ' ' | '#' | '?' | '%' | '"' | '<' | '>' => {
                let mut buf = [0; 4];
                for b in ch.encode_utf8(&mut buf).bytes() {
                    let _ = write!(out, "%{b:02X}");
                }
            }
            _ => out.push(ch),
        }
    }
    esc(&out)
}

/// The relative paths the page links to (`href` and `src` values that name no
/// scheme, no absolute path and no anchor), decoded: the `href`s, then the `src`s.
///
/// # Example
/// ```
/// use swarf_report::html::relative_links;
/// let h = r##"<a href="#s1">x</a><img src="a/b%20c.png"><a href="https://x">y</a>"##;
/// assert_eq!(relative_links(h), ["a/b c.png"]);
/// ```
pub fn relative_links(html: &str) -> Vec<String> {
    let mut out = Vec::new();
    for attr in ["href=\"", "src=\""] {
        let mut rest = html;
        while let Some(k) = rest.find(attr) {
            rest = &rest[k + attr.len()..];
            let Some(end) = rest.find('"') else { break };
            let value = unescape(&rest[..end]);
            rest = &rest[end..];
            let scheme = value.split_once(':').is_some_and(|(s, _)| !s.contains('/'));
            if !(value.is_empty() || scheme || value.starts_with(['/', '#'])) {
                out.push(decode(&value));
            }
        }
    }
    out
}

/// An attribute value with the escapes of [`esc`] undone.
fn unescape(s: &str) -> String {
    s.replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}

/// A percent-encoded path decoded (invalid escapes kept as they are).
fn decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut k = 0;
    while k < b.len() {
        let hex = b
            .get(k + 1..k + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (b[k], hex) {
            (b'%', Some(v)) => {
                out.push(v);
                k += 3;
            }
            (c, _) => {
                out.push(c);
                k += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests;
