//! `lectern present`: Present a deck in a window.

/// Present a deck in a window.
#[derive(Debug, Default, clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`lectern present` is not built yet")
}
