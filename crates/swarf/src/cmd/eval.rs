//! `swarf eval PART --patch N --uv U,V`: exact evaluation of one patch as JSON, and
//! whether the point is on the face (inside its trimming loops, for a CAD part).

use anyhow::{Context, Result, bail};
use swarf_app::load_part;

/// Arguments of `swarf eval`.
#[derive(clap::Args)]
pub struct Args {
    #[arg(help = super::help::part("The part", super::help::Reads::Patches))]
    part: String,
    /// Patch index (0-based, in file order).
    #[arg(long, default_value_t = 0)]
    patch: usize,
    /// Parameters `U,V` inside the patch's knot range.
    #[arg(long, allow_hyphen_values = true)]
    uv: String,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let part = load_part(&args.part)?;
    let patch = swarf_app::model::patch_at(&part, args.patch)
        .map_err(|m| anyhow::anyhow!("--patch: {m}"))?;
    let [u, v] = parse_pair(&args.uv, "--uv")?;
    let [[u0, u1], [v0, v1]] = patch.domain();
    if !(u0..=u1).contains(&u) || !(v0..=v1).contains(&v) {
        bail!(
            "--uv: ({u}, {v}) is outside the patch's domain u in [{u0}, {u1}], v in [{v0}, {v1}]"
        );
    }
    let d = patch.derivs(u, v);
    let Some(normal) = d.normal() else {
        bail!("--uv: the patch is degenerate at ({u}, {v}) (du x dv = 0): no normal or curvature");
    };
    let c = d.curvature();
    let arr = |x: swarf_geom::Vec3| [x.x, x.y, x.z];
    let values = (
        arr(d.point.coords),
        [arr(d.du), arr(d.dv), arr(normal)],
        c.map(|c| (c.k1, c.k2, arr(c.dir1), arr(c.dir2))),
    );
    swarf_io::json::check_finite(&values).map_err(|e| anyhow::anyhow!("at ({u}, {v}): {e}"))?;
    let out = serde_json::json!({
        "point": arr(d.point.coords),
        "du": arr(d.du),
        "dv": arr(d.dv),
        "normal": arr(normal),
        "k1": c.map(|c| c.k1),
        "k2": c.map(|c| c.k2),
        "dir1": c.map(|c| arr(c.dir1)),
        "dir2": c.map(|c| arr(c.dir2)),
        "on_face": part.face_contains(args.patch, u, v),
    });
    println!("{}", serde_json::to_string(&out)?);
    Ok(())
}

/// Parses `U,V` into two numbers.
pub fn parse_pair(text: &str, what: &str) -> Result<[f64; 2]> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 2 {
        bail!("{what}: expected two numbers separated by a comma, found {text:?}");
    }
    let mut out = [0.0; 2];
    for (o, p) in out.iter_mut().zip(&parts) {
        *o = p
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .with_context(|| format!("{what}: {p:?} is not a finite number"))?;
    }
    Ok(out)
}
