//! `lectern inertia`: mass, centre of mass and inertia tensor of a closed triangle mesh (OBJ),
//! exactly (Mirtich 1996) or from an N³ point lattice.

use crate::rigid::{TriMesh, mass};
use anyhow::Context;
use std::path::PathBuf;

/// Mass properties of a closed triangle mesh.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The mesh, a closed and consistently oriented OBJ.
    pub mesh: PathBuf,
    /// Density in kg/m³ (mass = volume × density).
    #[arg(long, default_value_t = 1.0)]
    pub density: f64,
    /// Approximate with the inside cell centres of an N×N×N lattice instead of exactly.
    #[arg(long)]
    pub points: Option<usize>,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    if !(args.density.is_finite() && args.density > 0.0) {
        anyhow::bail!("--density must be a positive number, got {}", args.density);
    }
    if let Some(n) = args.points {
        if !(1..=2000).contains(&n) {
            anyhow::bail!("--points must be between 1 and 2000, got {n}");
        }
    }
    let mesh = TriMesh::load_obj(&args.mesh).map_err(|d| anyhow::anyhow!("{d}"))?;
    mesh.check_closed()
        .map_err(|m| anyhow::anyhow!("{}: {m}", args.mesh.display()))
        .context("mass properties need a closed mesh")?;
    let (method, props) = match args.points {
        None => ("mirtich".to_string(), mass::mirtich(&mesh)),
        Some(n) => (
            format!("point-lattice {n}^3"),
            mass::point_lattice(&mesh, n),
        ),
    };
    if props.mass <= 0.0 {
        anyhow::bail!(
            "{}: the enclosed volume is {} (not positive): are the faces oriented inwards?",
            args.mesh.display(),
            props.mass
        );
    }
    let p = props.with_density(args.density);
    let rows: Vec<[f64; 3]> = (0..3).map(|r| p.inertia.row(r).to_array()).collect();
    if args.json {
        let v = serde_json::json!({
            "mesh": args.mesh.display().to_string(),
            "method": method,
            "density": args.density,
            "volume": props.mass,
            "mass": p.mass,
            "center_of_mass": p.center.to_array(),
            "inertia_about_center": rows,
            "inertia_convention": "I = ∫(|r|²·1 − r rᵀ) dm; off-diagonals are −∫xy dm",
        });
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        println!(
            "mesh:    {} ({} triangles)",
            args.mesh.display(),
            mesh.triangles.len()
        );
        println!("method:  {method}");
        println!("volume:  {:.9}", props.mass);
        println!("mass:    {:.9}", p.mass);
        println!(
            "centre:  [{:.9}, {:.9}, {:.9}]",
            p.center.x, p.center.y, p.center.z
        );
        println!("inertia about the centre (off-diagonals = −∫xy dm):");
        for r in rows {
            println!("  [{:>16.9} {:>16.9} {:>16.9}]", r[0], r[1], r[2]);
        }
    }
    Ok(())
}
