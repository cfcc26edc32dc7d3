//! The lecture's exercise: orient a fish along a path, once with the Frenet frame and once with
//! the parallel-transport frame the school uses (ERRATA 5). The data the exercise slide draws;
//! the transported frames come from [`transport`], the very step the school ships.
//!
//! Frenet: forward = T, up = B = T × N with N the direction the path turns towards. N is
//! undefined where the path is straight, and it jumps to the other side where the curvature
//! changes sign, so the Frenet fish rolls upside down at an inflection. Parallel transport
//! rotates the previous frame by the smallest rotation taking the old tangent to the new one
//! (axis t_old × t_new, angle acos(t_old · t_new)): q_new = normalize(q(R) · q_old).

use glam::{Mat3, Quat, Vec3};
use serde::{Deserialize, Serialize};
use std::f32::consts::PI;

use super::{FISH_FORWARD, FISH_UP, transport, upright_frame};

/// The paths the exercise slide offers.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum PathShape {
    /// A straight run, then a wave that turns left, right and left again in the horizontal
    /// plane: the Frenet frame is undefined on the straight part and flips at each inflection.
    #[default]
    StraightThenS,
    /// A helix about the vertical axis: constant curvature and torsion, no flip, but the Frenet
    /// frame twists with the torsion while the transported one does not.
    Helix,
    /// A straight run into a vertical loop and out again: Frenet puts the fish on its side
    /// inside the loop, transport takes it round like a roller coaster.
    Loop,
}

impl PathShape {
    pub const ALL: [PathShape; 3] = [PathShape::StraightThenS, PathShape::Helix, PathShape::Loop];

    pub fn label(self) -> &'static str {
        match self {
            PathShape::StraightThenS => "straight, then S-curve",
            PathShape::Helix => "helix",
            PathShape::Loop => "loop",
        }
    }

    /// The path at parameter `u` ∈ [0, 1], in metres (y up).
    pub fn point(self, u: f32) -> Vec3 {
        match self {
            PathShape::StraightThenS => {
                // 4 m straight along +x, then z = A (1 − cos πs) for s ∈ [0, 2]: the tangent is
                // continuous at the join and the curvature ∝ cos πs changes sign at s = ½, 3/2
                let x = 12.0 * u;
                if x <= 4.0 {
                    Vec3::new(x, 0.0, 0.0)
                } else {
                    let s = (x - 4.0) / 4.0;
                    Vec3::new(x, 0.0, 1.8 * (1.0 - (PI * s).cos()))
                }
            }
            PathShape::Helix => {
                let theta = 3.0 * 2.0 * PI * u;
                Vec3::new(2.0 * theta.cos(), 0.5 * theta, 2.0 * theta.sin())
            }
            PathShape::Loop => {
                // 3 m in, a circle of radius 1.5 m in the x–y plane (shifted sideways by 0.6 m
                // over the turn so the path does not cross itself), 3 m out
                let len_in = 3.0;
                let r = 1.5;
                let circle = 2.0 * PI * r;
                let total = 2.0 * len_in + circle;
                let s = u * total;
                if s <= len_in {
                    Vec3::new(s, 0.0, 0.0)
                } else if s <= len_in + circle {
                    let a = (s - len_in) / r;
                    let side = 0.6 * (s - len_in) / circle;
                    Vec3::new(len_in + r * a.sin(), r * (1.0 - a.cos()), side)
                } else {
                    Vec3::new(s - circle, 0.0, 0.6)
                }
            }
        }
    }

    /// `n` points along the path (at least 3).
    pub fn sample(self, n: usize) -> Vec<Vec3> {
        let n = n.max(3);
        (0..n)
            .map(|i| self.point(i as f32 / (n - 1) as f32))
            .collect()
    }
}

/// Both frames at one point of the path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameSample {
    pub position: Vec3,
    pub tangent: Vec3,
    /// Unsigned curvature (1/m) from the discrete turning angle.
    pub curvature_per_m: f32,
    /// The Frenet orientation (forward = T, up = B); `None` where the path is straight and N
    /// has no direction.
    pub frenet: Option<Quat>,
    /// The parallel-transported orientation, started upright.
    pub transported: Quat,
}

impl FrameSample {
    pub fn frenet_up(&self) -> Option<Vec3> {
        self.frenet.map(|q| q * FISH_UP)
    }

    pub fn transported_up(&self) -> Vec3 {
        self.transported * FISH_UP
    }
}

/// Below this curvature (1/m) the Frenet normal is taken as undefined.
pub const STRAIGHT_CURVATURE_PER_M: f32 = 1e-3;

/// Both frames at every point of `points` (tangents by central differences, one-sided at the
/// ends). The transported frame starts upright and then takes one [`transport`] step per point.
pub fn frames_along(points: &[Vec3]) -> Vec<FrameSample> {
    let n = points.len();
    if n < 2 {
        return Vec::new();
    }
    let tangent = |i: usize| {
        let (a, b) = (points[i.saturating_sub(1)], points[(i + 1).min(n - 1)]);
        (b - a).try_normalize().unwrap_or(FISH_FORWARD)
    };
    let tangents: Vec<Vec3> = (0..n).map(tangent).collect();
    let mut q = upright_frame(tangents[0]);
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let t = tangents[i];
        if i > 0 {
            q = transport(q, t);
        }
        // N from the change of the tangent over the neighbouring segments, per metre of path
        let (prev, next) = (tangents[i.saturating_sub(1)], tangents[(i + 1).min(n - 1)]);
        let ds = (points[(i + 1).min(n - 1)] - points[i.saturating_sub(1)]).length();
        let dt = next - prev;
        let normal_part = dt - t * t.dot(dt);
        let curvature = if ds > 0.0 {
            normal_part.length() / ds
        } else {
            0.0
        };
        let frenet = (curvature > STRAIGHT_CURVATURE_PER_M).then(|| {
            let normal = normal_part.normalize();
            let binormal = t.cross(normal);
            // columns: images of the fish's (forward = x, up = y, x × y = z)
            Quat::from_mat3(&Mat3::from_cols(t, binormal, t.cross(binormal))).normalize()
        });
        out.push(FrameSample {
            position: points[i],
            tangent: t,
            curvature_per_m: curvature,
            frenet,
            transported: q,
        });
    }
    out
}

/// One transport step spelled out for the slide: the rotation R taking the old heading to the
/// new one (axis, angle, as a quaternion) and q_new = normalize(q(R) · q_old).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransportStep {
    pub heading_old: Vec3,
    pub heading_new: Vec3,
    /// The unit axis t_old × t_new; `None` where the path runs straight (the headings are
    /// parallel, the cross product vanishes and R is the identity: no axis is defined).
    pub axis: Option<Vec3>,
    pub angle_rad: f32,
    pub q_rotation: Quat,
    pub q_old: Quat,
    pub q_new: Quat,
}

/// The step from `q_old` to the new unit heading `heading_new`, with its parts. `q_new` is what
/// the school's [`transport`] computes (the test checks they agree).
pub fn transport_step(q_old: Quat, heading_new: Vec3) -> TransportStep {
    let heading_old = q_old * FISH_FORWARD;
    let h = heading_new.normalize_or(heading_old);
    let cross = heading_old.cross(h);
    // parallel headings (|sin| below f32 noise, ~0.006°): no rotation and no axis; acos of a
    // dot product a rounding short of 1 would read as a few hundredths of a degree
    let straight = cross.length() < 1e-4 && heading_old.dot(h) > 0.0;
    let angle_rad = if straight {
        0.0
    } else {
        heading_old.dot(h).clamp(-1.0, 1.0).acos()
    };
    let axis = if straight {
        None
    } else {
        cross.try_normalize()
    };
    let q_rotation = axis.map_or(Quat::IDENTITY, |a| Quat::from_axis_angle(a, angle_rad));
    TransportStep {
        heading_old,
        heading_new: h,
        axis,
        angle_rad,
        q_rotation,
        q_old,
        q_new: transport(q_old, h),
    }
}

/// Indices where an up vector turns by more than 90° between neighbouring defined samples.
pub fn flips(ups: impl IntoIterator<Item = Option<Vec3>>) -> Vec<usize> {
    let mut prev: Option<Vec3> = None;
    let mut out = Vec::new();
    for (i, up) in ups.into_iter().enumerate() {
        if let Some(u) = up {
            if prev.is_some_and(|p| p.dot(u) < 0.0) {
                out.push(i);
            }
            prev = Some(u);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frenet_flips_on_the_s_curve_and_transport_does_not() {
        let f = frames_along(&PathShape::StraightThenS.sample(400));
        // undefined on the straight part
        assert!(f[10].frenet.is_none() && f[100].frenet.is_none());
        let frenet_flips = flips(f.iter().map(FrameSample::frenet_up));
        assert_eq!(
            frenet_flips.len(),
            2,
            "one flip per inflection: {frenet_flips:?}"
        );
        assert!(flips(f.iter().map(|s| Some(s.transported_up()))).is_empty());
        // a planar path in the horizontal plane: the transported fish stays exactly upright
        for s in &f {
            assert!(s.transported_up().dot(Vec3::Y) > 1.0 - 1e-4, "{s:?}");
            assert!((s.transported * FISH_FORWARD).dot(s.tangent) > 1.0 - 1e-5);
        }
    }

    #[test]
    fn frenet_lies_on_its_side_in_the_loop_and_transport_goes_round() {
        let f = frames_along(&PathShape::Loop.sample(800));
        let mid = &f[400]; // half way round: at the top of the loop
        assert!(mid.position.y > 2.5, "{mid:?}");
        let frenet_up = mid.frenet_up().unwrap();
        assert!(
            frenet_up.y.abs() < 0.3,
            "Frenet's up is sideways in a vertical loop"
        );
        // transported: upside down at the top of the loop (the back towards the centre)
        assert!(mid.transported_up().y < -0.9, "{}", mid.transported_up());
        // and upright again after it
        assert!(f[799].transported_up().y > 0.9);
        assert!(flips(f.iter().map(|s| Some(s.transported_up()))).is_empty());
    }

    #[test]
    fn on_a_helix_neither_flips_and_curvature_is_the_helix_curvature() {
        let f = frames_along(&PathShape::Helix.sample(3000));
        assert!(flips(f.iter().map(FrameSample::frenet_up)).is_empty());
        assert!(flips(f.iter().map(|s| Some(s.transported_up()))).is_empty());
        // radius a = 2, rise b = 0.5 per radian: κ = a / (a² + b²)
        let kappa = 2.0 / (4.0 + 0.25);
        assert!(
            (f[1500].curvature_per_m - kappa).abs() < 1e-2 * kappa,
            "{}",
            f[1500].curvature_per_m
        );
    }

    #[test]
    fn the_spelled_out_step_is_the_schools_step() {
        let q_old = upright_frame(Vec3::new(1.0, 0.2, 0.3));
        let new = Vec3::new(0.6, 0.5, -0.4).normalize();
        let s = transport_step(q_old, new);
        let by_parts = (s.q_rotation * s.q_old).normalize();
        assert!(
            by_parts.dot(s.q_new).abs() > 1.0 - 1e-6,
            "{by_parts} vs {}",
            s.q_new
        );
        assert!((s.q_new * FISH_FORWARD).dot(new) > 1.0 - 1e-5);
        assert!((s.angle_rad - s.heading_old.dot(new).acos()).abs() < 1e-6);
    }
}
