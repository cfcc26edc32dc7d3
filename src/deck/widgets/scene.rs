//! The water scene on a slide, as the deck writes it: which scene file, which view (the final
//! image or one of the renderer's debug views), which techniques are on, where the camera is
//! and at what simulation time the picture is taken. Pure data; `crate::widgets::scene` draws it
//! with the scene renderer.

use serde::{Deserialize, Serialize};

/// What the widget shows: the final image or one of the renderer's debug views
/// (`crate::render::DebugView`, named here without the renderer so the deck model stays free of
/// wgpu).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum SceneView {
    #[default]
    Final,
    ShadowMap,
    Normals,
    EnvCube,
    /// The caustics' focusing map (white where the waves focus the sun).
    CausticsMap,
}

impl SceneView {
    pub const ALL: [SceneView; 5] = [
        Self::Final,
        Self::ShadowMap,
        Self::Normals,
        Self::EnvCube,
        Self::CausticsMap,
    ];

    pub fn index(self) -> usize {
        Self::ALL.iter().position(|v| *v == self).unwrap_or(0)
    }

    /// The view at `index` (clamped), for the presenter's slider.
    pub fn from_index(index: usize) -> Self {
        Self::ALL[index.min(Self::ALL.len() - 1)]
    }
}

/// The techniques the lecturer switches on and off. Each `None` keeps the renderer's default
/// (on); `Some(b)` sets it. A technique added to the renderer gets its field here, in
/// [`SceneToggles::ALL_IDS`] and in the widget's `toggles_mut`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SceneToggles {
    pub env_map: Option<bool>,
    pub normal_maps: Option<bool>,
    pub shadows: Option<bool>,
    /// Cook–Torrance GGX; false = Lambert only
    pub brdf: Option<bool>,
    pub fresnel: Option<bool>,
    /// GPU Gems 1, ch. 2: the sun focused by the waves onto the seabed, rocks and fish
    pub caustics: Option<bool>,
}

impl SceneToggles {
    /// The field names, in the order the presenter shows them.
    pub const ALL_IDS: [&'static str; 6] = [
        "env_map",
        "normal_maps",
        "shadows",
        "brdf",
        "fresnel",
        "caustics",
    ];
}

/// The orbit camera; each `None` keeps the scene file's value.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SceneCameraSpec {
    /// turn about the vertical axis, degrees
    pub yaw_deg: Option<f64>,
    /// elevation above the horizontal, degrees
    pub pitch_deg: Option<f64>,
    /// metres from the camera's target
    pub distance: Option<f64>,
    /// the point the camera orbits, world metres (below the water level: a view from under
    /// water, through no waves)
    pub target: Option<[f64; 3]>,
}

/// How far from the origin a slide may put the camera's target, metres.
pub const TARGET_RANGE_M: (f64, f64) = (-100.0, 100.0);

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    /// The scene file, relative to the deck's folder.
    #[serde(default = "default_scene")]
    pub scene: String,
    #[serde(default)]
    pub view: SceneView,
    #[serde(default)]
    pub toggles: SceneToggles,
    #[serde(default)]
    pub camera: SceneCameraSpec,
    /// The simulation time shown, seconds (the scene is stepped from t = 0 to it, so exports
    /// and snapshots show the same frame); while `playing`, the time the slide starts at.
    #[serde(default)]
    pub time_s: f64,
    /// The fraction of the height the slide leaves for its widgets (1 = all of it).
    #[serde(default = "default_height")]
    pub height: f64,
    /// Whether the window animates the scene (exports always show `time_s`).
    #[serde(default)]
    pub playing: bool,
}

pub fn default_scene() -> String {
    "../scenes/water.ron".into()
}

fn default_height() -> f64 {
    1.0
}

/// The ranges `lectern check` holds the deck's values to (and the presenter's sliders span).
pub const YAW_RANGE_DEG: (f64, f64) = (-360.0, 360.0);
pub const PITCH_RANGE_DEG: (f64, f64) = (-85.0, 85.0);
pub const DISTANCE_RANGE_M: (f64, f64) = (0.5, 200.0);
/// The scene is stepped from t = 0 to `time_s` when the slide is first shown (every fish, at the
/// scene's fixed step): 10 s is 600 steps of the whole school, about seconds of CPU.
pub const TIME_RANGE_S: (f64, f64) = (0.0, 10.0);
pub const HEIGHT_RANGE: (f64, f64) = (0.1, 1.0);

impl SceneSpec {
    /// Values outside their ranges, as (field path inside the spec, message).
    pub fn range_problems(&self) -> Vec<(String, String)> {
        let mut out = Vec::new();
        let mut check = |at: &str, v: Option<f64>, (lo, hi): (f64, f64), what: &str| {
            if let Some(v) = v
                && !(v.is_finite() && (lo..=hi).contains(&v))
            {
                out.push((at.to_owned(), format!("{what} {v} is outside {lo}..={hi}")));
            }
        };
        check(
            "camera.yaw_deg",
            self.camera.yaw_deg,
            YAW_RANGE_DEG,
            "camera yaw",
        );
        check(
            "camera.pitch_deg",
            self.camera.pitch_deg,
            PITCH_RANGE_DEG,
            "camera pitch",
        );
        check(
            "camera.distance",
            self.camera.distance,
            DISTANCE_RANGE_M,
            "camera distance (m)",
        );
        for (k, v) in self.camera.target.iter().flatten().enumerate() {
            check(
                &format!("camera.target[{k}]"),
                Some(*v),
                TARGET_RANGE_M,
                "camera target (m)",
            );
        }
        check("time_s", Some(self.time_s), TIME_RANGE_S, "time_s");
        check("height", Some(self.height), HEIGHT_RANGE, "height");
        out
    }
}

impl Default for SceneSpec {
    fn default() -> Self {
        Self {
            scene: default_scene(),
            view: SceneView::default(),
            toggles: SceneToggles::default(),
            camera: SceneCameraSpec::default(),
            time_s: 0.0,
            height: default_height(),
            playing: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_issue_example_parses_with_bare_bools() {
        let spec: SceneSpec = ron::Options::default()
            .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
            .from_str(
                "(view: ShadowMap, toggles: (shadows: true, normal_maps: false), \
                 camera: (yaw_deg: 20.0, pitch_deg: 35.0, distance: 10.0), height: 0.6)",
            )
            .unwrap();
        assert_eq!(spec.view, SceneView::ShadowMap);
        assert_eq!(spec.toggles.shadows, Some(true));
        assert_eq!(spec.toggles.normal_maps, Some(false));
        assert_eq!(spec.toggles.brdf, None);
        assert_eq!(spec.camera.distance, Some(10.0));
        assert_eq!(spec.scene, "../scenes/water.ron");
        assert!(spec.range_problems().is_empty());
    }

    #[test]
    fn out_of_range_values_are_named() {
        let spec = SceneSpec {
            camera: SceneCameraSpec {
                pitch_deg: Some(120.0),
                ..Default::default()
            },
            time_s: f64::NAN,
            ..Default::default()
        };
        let at: Vec<String> = spec.range_problems().into_iter().map(|p| p.0).collect();
        assert_eq!(at, ["camera.pitch_deg", "time_s"]);
    }
}
