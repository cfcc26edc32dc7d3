//! Scene mode's teaching panel: technique toggles, debug views, quality, time, floating
//! bodies, fish, materials and waves. Sliders edit the simulation's copy of the scene (the
//! file's last good version stays in the [`crate::reload::LiveFile`]).

use crate::render::DebugView;
use crate::rigid::Integrator;
use crate::scene::{self, Quality};

use super::scene_mode::{SceneMode, mean};

impl SceneMode {
    /// The teaching panel: technique toggles, debug views, material and wave sliders, fish
    /// count, time control, frame-time readout.
    pub fn controls_ui(&mut self, ui: &mut egui::Ui) {
        // which backend draws (the GL fallback looks the same; its frame times do not)
        ui.label(egui::RichText::new(self.host.backend_line()).small().weak());
        let s = &mut self.settings;
        ui.heading("Techniques");
        ui.checkbox(&mut s.env_map, "environment map (sky reflections)");
        ui.checkbox(&mut s.normal_maps, "normal maps");
        ui.checkbox(&mut s.shadows, "shadow map (PCF)");
        ui.checkbox(&mut s.brdf, "Cook–Torrance BRDF (off: Lambert)");
        ui.checkbox(&mut s.fresnel, "Fresnel (Schlick)");
        ui.checkbox(&mut s.caustics, "caustics (GPU Gems 1 ch. 2)");
        ui.add(egui::Slider::new(&mut s.exposure, 0.1..=4.0).text("exposure"));
        ui.separator();
        ui.label("Debug view");
        ui.horizontal_wrapped(|ui| {
            for v in DebugView::ALL {
                ui.selectable_value(&mut s.debug_view, v, v.label());
            }
        });
        ui.separator();
        ui.heading("Time");
        ui.horizontal(|ui| {
            let label = if self.paused { "▶ play" } else { "⏸ pause" };
            if ui.button(label).clicked() {
                self.paused = !self.paused;
            }
            if ui
                .add_enabled(self.paused, egui::Button::new("step"))
                .clicked()
            {
                self.step_once = true;
            }
            ui.label(format!("t = {:.2} s", self.sim.time_secs()));
        });
        ui.checkbox(&mut self.show_frame_time, "frame-time readout");
        self.quality_ui(ui);
        if ui.button("reset camera").clicked() {
            self.sim.camera = scene::OrbitCamera::from_scene(&self.sim.scene.camera);
        }
        ui.separator();
        self.bodies_ui(ui);
        ui.separator();
        self.fish_ui(ui);
        let sc = &mut self.sim.scene;
        ui.separator();
        ui.heading("Material");
        if !sc.materials.is_empty() {
            self.selected_material = self.selected_material.min(sc.materials.len() - 1);
            egui::ComboBox::from_label("material")
                .selected_text(sc.materials[self.selected_material].name.clone())
                .show_ui(ui, |ui| {
                    for (i, m) in sc.materials.iter().enumerate() {
                        ui.selectable_value(&mut self.selected_material, i, m.name.clone());
                    }
                });
            let m = &mut sc.materials[self.selected_material];
            ui.add(egui::Slider::new(&mut m.metallic, 0.0..=1.0).text("metallic"));
            ui.add(egui::Slider::new(&mut m.roughness, 0.0..=1.0).text("roughness"));
            ui.add(egui::Slider::new(&mut m.reflectance, 0.0..=1.0).text("reflectance"));
            ui.add(egui::Slider::new(&mut m.normal_strength, 0.0..=3.0).text("normal strength"));
            ui.horizontal(|ui| {
                ui.label("base colour");
                ui.color_edit_button_rgb(&mut m.base_color);
            });
        }
        ui.separator();
        ui.heading("Waves");
        ui.add(egui::Slider::new(&mut sc.water.resolution, 8..=512).text("grid vertices per side"));
        for (i, w) in sc.water.waves.iter_mut().enumerate() {
            ui.collapsing(format!("wave {}", i + 1), |ui| {
                ui.add(egui::Slider::new(&mut w.amplitude, 0.0..=0.5).text("amplitude (m)"));
                ui.add(egui::Slider::new(&mut w.wavelength, 0.2..=30.0).text("wavelength (m)"));
                ui.add(egui::Slider::new(&mut w.steepness, 0.0..=1.0).text("steepness Q"));
                ui.add(egui::Slider::new(&mut w.speed, 0.0..=10.0).text("speed (m/s)"));
            });
        }
        if let Some(sp) = &mut sc.water.spectrum {
            ui.collapsing("wind sea (JONSWAP)", |ui| {
                ui.add(egui::Slider::new(&mut sp.significant_height, 0.0..=1.5).text("H_s (m)"));
                ui.add(
                    egui::Slider::new(&mut sp.peak_wavelength, 1.0..=40.0)
                        .text("peak wavelength (m)"),
                );
                ui.add(egui::Slider::new(&mut sp.spread_deg, 0.0..=90.0).text("spread (°)"));
                ui.add(egui::Slider::new(&mut sp.steepness, 0.0..=1.0).text("steepness Q"));
            });
        }
        let errors = self.errors();
        if !errors.is_empty() {
            ui.separator();
            for e in errors {
                ui.colored_label(egui::Color32::from_rgb(220, 80, 60), e);
            }
        }
    }

    /// Rigid bodies: the integrator switch, the step h, drag, and energy / |L| per body.
    fn bodies_ui(&mut self, ui: &mut egui::Ui) {
        ui.heading("Floating bodies");
        let m = &mut self.sim.scene.simulation;
        ui.horizontal_wrapped(|ui| {
            for method in Integrator::ALL {
                ui.selectable_value(&mut m.integrator, method, method.name());
            }
        });
        ui.add(
            egui::Slider::new(&mut m.body_h_secs, 0.002..=0.25)
                .logarithmic(true)
                .text("step h (s)"),
        );
        ui.add(egui::Slider::new(&mut m.linear_drag_per_sec, 0.0..=5.0).text("drag (1/s)"));
        ui.add(
            egui::Slider::new(&mut m.angular_drag_per_sec, 0.0..=5.0).text("angular drag (1/s)"),
        );
        let names: Vec<String> = self
            .sim
            .scene
            .objects
            .iter()
            .map(|o| match o {
                scene::Object::Floating { shape, .. } => match shape {
                    scene::Shape::Box { .. } => "box",
                    scene::Shape::Sphere { .. } => "sphere",
                    scene::Shape::Capsule { .. } => "capsule",
                }
                .to_string(),
                _ => String::new(),
            })
            .collect();
        egui::Grid::new("body readouts")
            .striped(true)
            .show(ui, |ui| {
                for h in [
                    "body",
                    "M (kg)",
                    "E_kin (J)",
                    "M g y (J)",
                    "|L| (kg m²/s)",
                    "resets",
                ] {
                    ui.label(h);
                }
                ui.end_row();
                for r in self.sim.readouts() {
                    ui.label(names.get(r.object_index).cloned().unwrap_or_default());
                    ui.monospace(format!("{:.1}", r.mass_kg));
                    ui.monospace(format!("{:.2}", r.kinetic_j));
                    ui.monospace(format!("{:.2}", r.potential_j));
                    ui.monospace(format!("{:.3}", r.angular_momentum));
                    ui.monospace(format!("{}", r.resets));
                    ui.end_row();
                }
            });
        if ui.button("restart simulation").clicked() {
            self.sim.restart();
        }
    }

    /// The school: count (live; the instance buffer grows), flee point, steering weights.
    fn fish_ui(&mut self, ui: &mut egui::Ui) {
        ui.heading("Fish");
        let p = &mut self.sim.scene.school;
        ui.add(
            egui::Slider::new(&mut p.count, 0..=scene::model::MAX_FISH)
                .logarithmic(true)
                .text("count"),
        );
        ui.add(egui::Slider::new(&mut p.separation_weight, 0.0..=5.0).text("separation"));
        ui.add(egui::Slider::new(&mut p.alignment_weight, 0.0..=5.0).text("alignment"));
        ui.add(egui::Slider::new(&mut p.cohesion_weight, 0.0..=5.0).text("cohesion"));
        ui.add(
            egui::Slider::new(&mut p.goal_weight, 0.0..=3.0)
                .text("pull to the school's centre (1/s²)"),
        );
        ui.add(egui::Slider::new(&mut p.schools, 1..=crate::school::MAX_SCHOOLS).text("schools"));
        ui.add(egui::Slider::new(&mut p.flee_radius, 0.0..=10.0).text("flee radius (m)"));
        let w = self.sim.scene.simulation.school_half_width;
        let mut on = self.sim.flee_point.is_some();
        ui.checkbox(&mut on, "flee point (click on the water to move it)");
        if on {
            let mid = 0.5 * (self.sim.scene.water.level - self.sim.scene.seabed_depth());
            let f = self
                .sim
                .flee_point
                .get_or_insert(glam::Vec3::new(0.0, mid, 0.0));
            ui.add(egui::Slider::new(&mut f.x, -w..=w).text("flee x (m)"));
            ui.add(egui::Slider::new(&mut f.z, -w..=w).text("flee z (m)"));
        } else {
            self.sim.flee_point = None;
        }
    }

    /// The quality in use: automatic (budget, the rung and what it means) or fixed by the file.
    fn quality_ui(&mut self, ui: &mut egui::Ui) {
        let info = self.host.renderer.frame_info();
        let rung = self.quality.settings();
        let what = match self.quality.mode() {
            Quality::Auto { budget_ms } => format!(
                "quality: auto, budget {budget_ms:.0} ms (step {} of {})",
                self.quality.rung() + 1,
                scene::quality::LADDER.len()
            ),
            Quality::Fixed { .. } => "quality: fixed by the scene file".to_owned(),
        };
        ui.label(what);
        ui.monospace(format!(
            "render {}×{} px ({:.0} %), fish detail {:.2}\nfish drawn full/medium/coarse/far: {}/{}/{}/{}\n\
             shadow edges {}, school stepped every {}, water and seabed grids {}, water normal \
             {} · frame {:.0} ms",
            info.render_size.0,
            info.render_size.1,
            rung.render_scale * 100.0,
            rung.fish_detail,
            info.fish_per_lod[0],
            info.fish_per_lod[1],
            info.fish_per_lod[2],
            info.fish_per_lod[3],
            if rung.soft_shadows {
                "3×3 PCF"
            } else {
                "1 bilinear tap"
            },
            match rung.school_every {
                1 => "step".to_owned(),
                n => format!("{n} steps"),
            },
            if rung.coarse_grids {
                "every other vertex"
            } else {
                "full"
            },
            match rung.water_normals.pixel_waves() {
                n if n as usize >= scene::model::MAX_WAVES => "all waves per pixel".to_owned(),
                n => format!("{n} short waves per pixel"),
            },
            mean(&self.interval_ms),
        ));
    }
}
