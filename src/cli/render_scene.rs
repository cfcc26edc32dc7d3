//! `lectern render-scene`: Render the water scene to PNG frames, headless.

/// Render the water scene to PNG frames, headless.
#[derive(Debug, clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`lectern render-scene` is not built yet")
}
