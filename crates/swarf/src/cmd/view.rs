//! `swarf view (--job JOB.toml | --part P --program PROG [--tool SPEC]) -o DIR
//! [--serve]`: the 3D view of a verified program ([`swarf_app::view`]): GLB files of
//! the design, tool path, cutter and simulated stock, `view.json`, the verification's
//! report and pictures, and the viewer page (embedded in swarf). `--serve`
//! serves the folder on 127.0.0.1 until Ctrl-C (or `--serve-for` seconds).

use crate::progress::Bars;
use anyhow::{Context, Result, bail};
use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use swarf_app::view::{ViewRequest, ViewSource, view_request};
use swarf_report::gltf::StockMeshOptions;

/// Arguments of `swarf view`.
#[derive(clap::Args)]
#[command(
    mut_arg("tol", |a| super::help::note(a, "(default: the job's tolerance with --job, else the one the program states, else 0.01)")),
    mut_arg("scallop", |a| super::help::note(a, "(default: the job's scallop with --job, else the one the program states, else 0)")),
    mut_arg("rapid", |a| super::help::note(a, "(default: the job's rapid rate with --job)")),
    mut_arg("floor", |a| super::help::note(a, "(no floor check without it)")),
)]
pub struct Args {
    /// Job file: plan it, verify its program and show both.
    #[arg(long, conflicts_with_all = ["part", "program", "tool", "machine"], required_unless_present = "program")]
    job: Option<PathBuf>,
    #[arg(long, requires = "program", help = format!(
        "{}; with --program",
        super::help::part("Design part", super::help::Reads::Model)
    ))]
    part: Option<String>,
    /// NC program (G-code, APT CL or pose CSV), with --part.
    #[arg(long, requires = "part")]
    program: Option<PathBuf>,
    /// Tool spec, e.g. ball:d=8 (default: the program's CUTTER record).
    #[arg(long)]
    tool: Option<String>,
    /// Machine file or builtin:NAME for five-axis G-code.
    #[arg(long)]
    machine: Option<String>,
    /// The simulation's settings, as `swarf verify` takes them.
    #[command(flatten)]
    sim: super::verify::SimArgs,
    /// Most vertices of the stock mesh (decimated above it; its height error is stated).
    #[arg(long, default_value_t = 250_000)]
    max_vertices: usize,
    /// Output folder (written as one set).
    #[arg(short = 'o', long = "out")]
    out: PathBuf,
    /// Serve the folder on 127.0.0.1 after writing it.
    #[arg(long)]
    serve: bool,
    /// Port to serve on (0: any free port).
    #[arg(long, default_value_t = 8017, requires = "serve")]
    port: u16,
    /// Stop serving after this many seconds (default: until Ctrl-C).
    #[arg(long, requires = "serve")]
    serve_for: Option<u64>,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    if !(1000..=50_000_000).contains(&args.max_vertices) {
        bail!(
            "--max-vertices: expected 1000 to 50000000 vertices, found {}",
            args.max_vertices
        );
    }
    let sim = args.sim.settings()?;
    let source = match (&args.job, &args.part, &args.program) {
        (Some(job), _, _) => ViewSource::Job(job),
        (None, Some(part), Some(program)) => ViewSource::Program {
            part,
            program,
            tool: args.tool.as_deref(),
            machine: args.machine.as_deref(),
        },
        _ => bail!("give --job JOB.toml, or --part PART with --program PROGRAM"),
    };
    let req = ViewRequest {
        source,
        sim: &sim,
        stock: StockMeshOptions {
            max_vertices: args.max_vertices,
        },
        out: &args.out,
    };
    let viewed = view_request(&req, &Bars::default())?;
    print!("{}", viewed.summary);
    let s = &viewed.written.stock;
    println!(
        "stock mesh: {} vertices, {} triangles, every {} cell(s), height error <= {:.4} mm",
        s.vertices, s.triangles, s.stride, s.height_error
    );
    for n in &viewed.notes {
        eprintln!("{n}");
    }
    println!("view written to {}", args.out.display());
    if args.serve {
        serve(
            &args.out,
            args.port,
            args.serve_for.map(Duration::from_secs),
        )?;
    }
    Ok(())
}

/// Largest request head read, bytes.
const MAX_REQUEST: usize = 8192;

/// Serves the files under `root` on 127.0.0.1:`port` (GET only, no listing), until
/// `time` has passed (or forever).
fn serve(root: &Path, port: u16, time: Option<Duration>) -> Result<()> {
    let listener = TcpListener::bind(("127.0.0.1", port))
        .with_context(|| format!("--port {port}: cannot listen on 127.0.0.1"))?;
    let addr = listener.local_addr()?;
    println!(
        "serving {} at http://{addr}/ (Ctrl-C stops)",
        root.display()
    );
    std::io::stdout().flush()?;
    let start = Instant::now();
    listener.set_nonblocking(time.is_some())?;
    loop {
        if time.is_some_and(|t| start.elapsed() >= t) {
            return Ok(());
        }
        match listener.accept() {
            Ok((stream, _)) => {
                if let Err(e) = answer(root, stream) {
                    eprintln!("serve: {e}");
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                std::thread::sleep(Duration::from_millis(20))
            }
            Err(e) => return Err(e).context("serve: accepting a connection"),
        }
    }
}

/// The content type of a served file.
fn content_type(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("json") => "application/json",
        Some("glb") => "model/gltf-binary",
        Some("png") => "image/png",
        _ => "application/octet-stream",
    }
}

/// Reads a request head up to its blank line (it may come in several pieces), the
/// end of the stream, or [`MAX_REQUEST`] bytes, whichever is first.
fn read_head(stream: &mut impl Read) -> std::io::Result<Vec<u8>> {
    let mut head = Vec::new();
    let mut piece = [0; 1024];
    while head.len() < MAX_REQUEST && !head.windows(4).any(|w| w == b"\r\n\r\n") {
        let n = stream.read(&mut piece)?;
        if n == 0 {
            break;
        }
        head.extend_from_slice(&piece[..n]);
    }
    Ok(head)
}

/// Answers one request.
fn answer(root: &Path, mut stream: TcpStream) -> std::io::Result<()> {
    stream.set_nonblocking(false)?;
    stream.set_read_timeout(Some(Duration::from_secs(5)))?;
    let head = read_head(&mut stream)?;
    let head = String::from_utf8_lossy(&head);
    let target = head
        .lines()
        .next()
        .and_then(|l| l.strip_prefix("GET "))
        .and_then(|l| l.split(' ').next());
    let rel = target.map(|t| {
        t.split(['?', '#'])
            .next()
            .unwrap_or("")
            .trim_start_matches('/')
    });
    let rel = rel.map(|r| if r.is_empty() { "index.html" } else { r });
    let safe = rel.filter(|r| {
        !r.split('/')
            .any(|c| c == ".." || c.is_empty() || c.contains('\\'))
    });
    let file = safe.map(|r| root.join(r)).filter(|p| p.is_file());
    let (status, kind, body) = match file {
        Some(p) => ("200 OK", content_type(&p), std::fs::read(&p)?),
        None if target.is_none() => (
            "405 Method Not Allowed",
            "text/plain",
            b"GET only\n".to_vec(),
        ),
        None => ("404 Not Found", "text/plain", b"not found\n".to_vec()),
    };
    write!(
        stream,
        "HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
        body.len()
    )?;
    stream.write_all(&body)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stream that hands out its bytes a few at a time, as a socket may.
    struct Pieces<'a>(&'a [u8]);

    impl Read for Pieces<'_> {
        fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
            let n = self.0.len().min(buf.len()).min(4);
            buf[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    #[test]
    fn a_request_head_in_pieces_is_read_whole() {
        let request = b"GET /stock.glb HTTP/1.1\r\nHost: x\r\n\r\n";
        let head = read_head(&mut Pieces(request)).unwrap();
        assert_eq!(head, request);
    }

    #[test]
    fn a_head_without_its_blank_line_stops_at_the_end_or_the_limit() {
        assert_eq!(read_head(&mut Pieces(b"GET /")).unwrap(), b"GET /");
        let endless = vec![b'a'; 3 * MAX_REQUEST];
        let head = read_head(&mut Pieces(&endless)).unwrap();
        assert!(head.len() >= MAX_REQUEST && head.len() < MAX_REQUEST + 4);
    }
}
