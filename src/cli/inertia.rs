//! `lectern inertia`: Mass properties of a closed triangle mesh.

/// Mass properties of a closed triangle mesh.
#[derive(Debug, clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`lectern inertia` is not built yet")
}
