//! `lectern solve`: Integrate an ODE problem file.

/// Integrate an ODE problem file.
#[derive(Debug, clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`lectern solve` is not built yet")
}
