//! The simulation-loop widget as the deck writes it: the loop every frame runs for a rigid
//! body, drawn as a cycle, with the live numbers of one of the scene's floating bodies.

use serde::{Deserialize, Serialize};

use crate::rigid::Integrator;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimulationLoopSpec {
    /// The scene whose floating body is simulated, relative to the deck's folder.
    #[serde(default = "default_scene")]
    pub scene: String,
    /// Which floating body (0 = the first `Floating` object in the scene).
    #[serde(default)]
    pub body: usize,
    /// The integrator; `None` takes the scene's.
    #[serde(default)]
    pub integrator: Option<Integrator>,
    #[serde(default = "yes")]
    pub playing: bool,
}

pub fn default_scene() -> String {
    "../scenes/water.ron".into()
}

fn yes() -> bool {
    true
}

impl Default for SimulationLoopSpec {
    fn default() -> Self {
        Self {
            scene: default_scene(),
            body: 0,
            integrator: None,
            playing: true,
        }
    }
}
