//! `lectern check`: Validate decks, scenes, shaders and problems.

/// Validate decks, scenes, shaders and problems.
#[derive(Debug, clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`lectern check` is not built yet")
}
