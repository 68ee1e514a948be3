//! Memory and time of reading a large binary STL, and of indexing it.
//!
//! ```text
//! cargo run --release -p swarf-io --example stl_10m -- write /tmp/big.stl 10000000
//! /usr/bin/time -v target/release/examples/stl_10m read /tmp/big.stl
//! /usr/bin/time -v target/release/examples/stl_10m index /tmp/big.stl
//! ```
//!
//! `write` streams a heightfield (z = 10 sin(x/10) cos(y/10), 0.3 mm grid, two
//! triangles a square) straight to the file without building a mesh; `read` reads it
//! with `read_stl`; `index` also builds the `XyIndex`. Compare the peak resident set
//! size that `/usr/bin/time -v` reports with the 500 MB file size.

use std::path::Path;
use std::time::Instant;
use swarf_geom::XyIndex;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    match args.get(1..) {
        Some([mode, path, n]) if mode == "write" => write(Path::new(path), n.parse()?),
        Some([mode, path]) if mode == "read" || mode == "index" => {
            read(Path::new(path), mode == "index")
        }
        _ => Err("usage: stl_10m write PATH TRIANGLES | read PATH | index PATH".into()),
    }
}

fn write(path: &Path, triangles: u64) -> Result<(), Box<dyn std::error::Error>> {
    let side = ((triangles / 2) as f64).sqrt().ceil() as u64;
    let p = |i: u64, j: u64| {
        let (x, y) = (i as f64 * 0.3, j as f64 * 0.3);
        [
            x as f32,
            y as f32,
            ((x / 10.0).sin() * (y / 10.0).cos() * 10.0) as f32,
        ]
    };
    swarf_io::write_atomic_with(path, |w| {
        let mut header = [b' '; 84];
        header[80..].copy_from_slice(&(triangles as u32).to_le_bytes());
        w.write_all(&header)?;
        let mut done = 0;
        'rows: for j in 0..side {
            for i in 0..side {
                for t in [
                    [p(i, j), p(i + 1, j), p(i + 1, j + 1)],
                    [p(i, j), p(i + 1, j + 1), p(i, j + 1)],
                ] {
                    if done == triangles {
                        break 'rows;
                    }
                    w.write_all(&[0u8; 12])?;
                    for c in t.iter().flatten() {
                        w.write_all(&c.to_le_bytes())?;
                    }
                    w.write_all(&[0u8; 2])?;
                    done += 1;
                }
            }
        }
        Ok(())
    })?;
    Ok(())
}

fn read(path: &Path, index: bool) -> Result<(), Box<dyn std::error::Error>> {
    let t = Instant::now();
    let mesh = swarf_io::read_stl(path)?;
    let secs = t.elapsed().as_secs_f64();
    let bytes = mesh.vertices.capacity() * 24 + mesh.triangles.capacity() * 12;
    println!(
        "read {} triangles, {} vertices in {secs:.2} s ({:.1} M triangles/s); mesh holds {:.0} MB",
        mesh.len(),
        mesh.vertices.len(),
        mesh.len() as f64 / secs / 1e6,
        bytes as f64 / 1e6
    );
    if index {
        let t = Instant::now();
        let xy = XyIndex::build(&mesh);
        let secs = t.elapsed().as_secs_f64();
        println!(
            "XyIndex built in {secs:.2} s: {:.0} MB, {:.1} bytes a triangle",
            xy.memory_bytes() as f64 / 1e6,
            xy.memory_bytes() as f64 / mesh.len() as f64
        );
        let mut out = Vec::new();
        let b = xy.bounds();
        let t = Instant::now();
        let queries = 100_000;
        let mut hits = 0;
        for k in 0..queries {
            let f = (k as f64 * 0.618_034) % 1.0;
            let g = (k as f64 * 0.414_214) % 1.0;
            let c = [
                b.min.x + f * (b.max.x - b.min.x),
                b.min.y + g * (b.max.y - b.min.y),
            ];
            xy.query_disc(c, 4.5, &mut out);
            hits += out.len();
        }
        let secs = t.elapsed().as_secs_f64();
        println!(
            "{queries} query_disc (r = 4.5 mm): {:.2} us each, {:.0} hits each",
            secs / queries as f64 * 1e6,
            hits as f64 / queries as f64
        );
    }
    Ok(())
}
