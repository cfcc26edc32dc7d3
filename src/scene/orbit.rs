//! The orbit camera: yaw/pitch/distance around a target, driven by mouse drag and scroll.

use glam::Vec3;

use super::model::Camera;
use super::snapshot::CameraPose;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitCamera {
    pub target: Vec3,
    pub distance: f32,
    pub yaw_deg: f32,
    pub pitch_deg: f32,
    pub fov_deg: f32,
}

impl OrbitCamera {
    pub fn from_scene(c: &Camera) -> Self {
        Self {
            target: Vec3::from(c.target),
            distance: c.distance,
            yaw_deg: c.yaw_deg,
            pitch_deg: c.pitch_deg,
            fov_deg: c.fov_deg,
        }
    }

    pub fn pose(&self) -> CameraPose {
        let (yaw, pitch) = (self.yaw_deg.to_radians(), self.pitch_deg.to_radians());
        let dir_to_eye = Vec3::new(
            pitch.cos() * yaw.sin(),
            pitch.sin(),
            pitch.cos() * yaw.cos(),
        );
        CameraPose {
            eye: self.target + dir_to_eye * self.distance,
            target: self.target,
            fov_y_rad: self.fov_deg.to_radians(),
        }
    }

    /// Drag in points: 0.3 degrees per point.
    pub fn orbit(&mut self, dx: f32, dy: f32) {
        self.yaw_deg = (self.yaw_deg - 0.3 * dx).rem_euclid(360.0);
        self.pitch_deg = (self.pitch_deg + 0.3 * dy).clamp(-85.0, 85.0);
    }

    /// Positive `steps` zooms in; multiplicative so it feels the same near and far.
    pub fn zoom(&mut self, steps: f32) {
        self.distance = (self.distance * (-0.1 * steps).exp()).clamp(0.5, 200.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eye_is_distance_from_target_and_pitch_raises_it() {
        let mut c = OrbitCamera {
            target: Vec3::new(1.0, 2.0, 3.0),
            distance: 5.0,
            yaw_deg: 10.0,
            pitch_deg: 30.0,
            fov_deg: 50.0,
        };
        let p = c.pose();
        assert!(((p.eye - p.target).length() - 5.0).abs() < 1e-5);
        assert!((p.eye.y - (2.0 + 2.5)).abs() < 1e-5);
        c.zoom(1000.0);
        assert_eq!(c.distance, 0.5);
        c.orbit(0.0, 1e6);
        assert_eq!(c.pitch_deg, 85.0);
    }
}
