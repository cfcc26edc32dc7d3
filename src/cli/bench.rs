//! `lectern bench`: Work-precision report of the integrators.

/// Work-precision report of the integrators.
#[derive(Debug, clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`lectern bench` is not built yet")
}
