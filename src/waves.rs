//! The water surface as a sum of Gerstner waves (GPU Gems 1, ch. 1), evaluated on the CPU for
//! buoyancy and for keeping fish under water.
//!
//! **The WGSL twin in `shaders/water.wgsl` must use exactly these formulas** (world is y-up,
//! waves live in the xz plane). For a rest point `p0 = (x, z)` and time `t`, with `N` waves:
//!
//! ```text
//! k_i   = 2π / wavelength_i                 (wavenumber)
//! ω_i   = k_i · speed_i                      (angular frequency; crests move along D_i)
//! θ_i   = k_i (D_i · p0) − ω_i t             (D_i = normalised direction)
//! Q_i   = steepness_i / (k_i A_i N)          (GPU Gems: Σ Q_i k_i A_i ≤ 1 ⇒ no loops)
//! P(p0) = ( x + Σ Q_i A_i D_i.x cos θ_i,
//!           mean_level + Σ A_i sin θ_i,
//!           z + Σ Q_i A_i D_i.y cos θ_i )
//! ```
//!
//! The normal is the exact one, `∂P/∂z × ∂P/∂x` from the analytic tangents (for a single wave it
//! equals GPU Gems eq. 12; for several waves it also keeps the cross terms that eq. 12 drops).
//! Heights at a *world* point need the inverse of the horizontal displacement; [`WaveSum::height`]
//! finds the rest point by fixed-point iteration, a contraction because Σ Q_i k_i A_i < 1.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// One Gerstner wave. `direction` is in the xz plane (normalised on use).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GerstnerWave {
    pub direction: [f32; 2],
    /// metres
    pub wavelength: f32,
    /// metres
    pub amplitude: f32,
    /// 0 = sine wave, 1 = sharpest crest without loops (Q in GPU Gems)
    pub steepness: f32,
    /// metres per second (phase speed)
    pub speed: f32,
}

/// Per-wave constants, precomputed once per evaluation (all f64).
#[derive(Clone, Copy)]
struct Terms {
    dir: DVec2,
    k: f64,
    omega: f64,
    amp: f64,
    /// Q_i A_i: the horizontal amplitude
    q_amp: f64,
}

impl GerstnerWave {
    fn terms(&self, count: usize) -> Terms {
        let d = DVec2::new(self.direction[0] as f64, self.direction[1] as f64);
        let dir = d.try_normalize().unwrap_or(DVec2::X);
        let wavelength = (self.wavelength as f64).max(1e-6);
        let k = TAU / wavelength;
        let amp = if self.amplitude.is_finite() {
            self.amplitude as f64
        } else {
            0.0
        };
        let steep = (self.steepness as f64).clamp(0.0, 1.0);
        // Q_i A_i with Q_i = steepness / (k A N); a wave of zero amplitude moves nothing
        let q_amp = if amp == 0.0 {
            0.0
        } else {
            steep / (k * count.max(1) as f64)
        };
        let speed = if self.speed.is_finite() {
            self.speed as f64
        } else {
            0.0
        };
        Terms {
            dir,
            k,
            omega: k * speed,
            amp,
            q_amp,
        }
    }
}

/// The whole surface: a sum of Gerstner waves around a mean water level.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct WaveSum {
    pub waves: Vec<GerstnerWave>,
    /// metres, world y of the undisturbed surface
    pub mean_level: f32,
}

/// Fixed-point iterations used by [`WaveSum::height`]; the error shrinks by the factor
/// Σ Q_i k_i A_i (≤ mean steepness) per iteration.
pub const HEIGHT_ITERATIONS: usize = 8;

/// [`WaveSum::rest_point_under`] over precomputed terms: `p0 ← world_xz − D_h(p0)`, with only
/// the horizontal offsets (the cosines) summed.
fn rest_point(terms: &[Terms], world_xz: DVec2, t_secs: f64) -> DVec2 {
    let mut p0 = world_xz;
    if terms.is_empty() {
        return p0;
    }
    for _ in 0..HEIGHT_ITERATIONS {
        let (mut dx, mut dz) = (0.0, 0.0);
        for w in terms {
            let c = (w.k * w.dir.dot(p0) - w.omega * t_secs).cos();
            dx += w.q_amp * w.dir.x * c;
            dz += w.q_amp * w.dir.y * c;
        }
        p0 = world_xz - DVec2::new(dx, dz);
    }
    p0
}

impl WaveSum {
    pub fn new(waves: Vec<GerstnerWave>, mean_level: f32) -> Self {
        Self { waves, mean_level }
    }

    /// A flat surface at `level`.
    pub fn calm(level: f32) -> Self {
        Self {
            waves: Vec::new(),
            mean_level: level,
        }
    }

    fn terms(&self) -> impl Iterator<Item = Terms> + '_ {
        let n = self.waves.len();
        self.waves.iter().map(move |w| w.terms(n))
    }

    /// Offset of the surface point whose rest position is `rest_xz`, at time `t_secs`
    /// (x, y above the mean level, z).
    pub fn displacement(&self, rest_xz: DVec2, t_secs: f64) -> DVec3 {
        let mut d = DVec3::ZERO;
        for w in self.terms() {
            let theta = w.k * w.dir.dot(rest_xz) - w.omega * t_secs;
            let (s, c) = theta.sin_cos();
            d.x += w.q_amp * w.dir.x * c;
            d.y += w.amp * s;
            d.z += w.q_amp * w.dir.y * c;
        }
        d
    }

    /// World position of the surface point whose rest position is `rest_xz`.
    pub fn surface_point(&self, rest_xz: DVec2, t_secs: f64) -> DVec3 {
        let d = self.displacement(rest_xz, t_secs);
        DVec3::new(
            rest_xz.x + d.x,
            self.mean_level as f64 + d.y,
            rest_xz.y + d.z,
        )
    }

    /// Unit normal (y-up) at the surface point whose rest position is `rest_xz`:
    /// `∂P/∂z × ∂P/∂x` from the analytic tangents.
    pub fn normal(&self, rest_xz: DVec2, t_secs: f64) -> DVec3 {
        let mut dx = DVec3::X; // ∂P/∂x
        let mut dz = DVec3::Z; // ∂P/∂z
        for w in self.terms() {
            let theta = w.k * w.dir.dot(rest_xz) - w.omega * t_secs;
            let (s, c) = theta.sin_cos();
            // ∂θ/∂x = k D.x, ∂θ/∂z = k D.y
            let h = -w.q_amp * w.k * s; // derivative factor of the horizontal terms
            let v = w.amp * w.k * c; // derivative factor of the vertical term
            dx += DVec3::new(h * w.dir.x * w.dir.x, v * w.dir.x, h * w.dir.y * w.dir.x);
            dz += DVec3::new(h * w.dir.x * w.dir.y, v * w.dir.y, h * w.dir.y * w.dir.y);
        }
        dz.cross(dx).normalize_or(DVec3::Y)
    }

    /// The rest point whose displaced surface point lies above the world point `world_xz`:
    /// solves `p0 + D_h(p0) = world_xz` by fixed-point iteration `p0 ← world_xz − D_h(p0)`.
    pub fn rest_point_under(&self, world_xz: DVec2, t_secs: f64) -> DVec2 {
        let terms: Vec<Terms> = self.terms().collect();
        rest_point(&terms, world_xz, t_secs)
    }

    /// World y of the surface above (or below) the world point `world_xz` at time `t_secs`.
    pub fn height(&self, world_xz: DVec2, t_secs: f64) -> f64 {
        // (the floating bodies ask this at every volume sample, four times a step: the terms
        // once, and each wave's cosine alone in the iteration, its sine once after; the same
        // sums as `displacement`'s, in the same order)
        let terms: Vec<Terms> = self.terms().collect();
        let p0 = rest_point(&terms, world_xz, t_secs);
        let mut y = 0.0;
        for w in &terms {
            y += w.amp * (w.k * w.dir.dot(p0) - w.omega * t_secs).sin();
        }
        self.mean_level as f64 + y
    }

    /// Unit surface normal above the world point `world_xz`.
    pub fn normal_at(&self, world_xz: DVec2, t_secs: f64) -> DVec3 {
        self.normal(self.rest_point_under(world_xz, t_secs), t_secs)
    }

    /// The lowest the surface can ever be: the mean level minus every amplitude. Below this
    /// height a point is under water at all times and places.
    pub fn lowest_level(&self) -> f64 {
        self.mean_level as f64
            - self
                .waves
                .iter()
                .map(|w| (w.amplitude as f64).abs())
                .sum::<f64>()
    }

    /// The highest the surface can ever be.
    pub fn highest_level(&self) -> f64 {
        self.mean_level as f64
            + self
                .waves
                .iter()
                .map(|w| (w.amplitude as f64).abs())
                .sum::<f64>()
    }

    /// Σ Q_i k_i A_i: the contraction factor of the height iteration (< 1 means no loops).
    pub fn horizontal_steepness(&self) -> f64 {
        self.terms().map(|w| w.q_amp * w.k).sum()
    }
}

/// Standard gravity, m/s² (deep-water dispersion ω² = g k).
pub const GRAVITY: f64 = 9.81;

/// A wind sea as `count` Gerstner waves drawn from the JONSWAP frequency spectrum (Hasselmann
/// et al. 1973) with a directional spread about the wind, scaled to a significant wave height:
/// irregular crests and caustics instead of the lattice a few hand-placed waves make. Each wave
/// takes deep-water speed √(g / k); the draws are seeded, so the same file gives the same sea.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WaveSpectrum {
    /// how many waves (the shader sums at most `scene::model::MAX_WAVES` in all)
    pub count: u32,
    /// wavelength at the spectrum's peak, metres
    pub peak_wavelength: f32,
    /// H_s = 4 √m₀, metres (m₀: the variance of the surface height)
    pub significant_height: f32,
    /// the wind's direction in the xz plane (normalised on use)
    pub wind_direction: [f32; 2],
    /// standard deviation of the waves' directions about the wind, degrees
    pub spread_deg: f32,
    /// JONSWAP peak enhancement γ (1: Pierson–Moskowitz, 3.3: a young sea)
    pub peak_enhancement: f32,
    /// Gerstner steepness shared by the waves (0..=1; 1 is the sharpest without loops)
    pub steepness: f32,
    pub seed: u64,
}

impl Default for WaveSpectrum {
    fn default() -> Self {
        Self {
            count: 24,
            peak_wavelength: 8.0,
            significant_height: 0.3,
            wind_direction: [1.0, 0.3],
            spread_deg: 30.0,
            peak_enhancement: 3.3,
            steepness: 0.7,
            seed: 7,
        }
    }
}

impl WaveSpectrum {
    /// The JONSWAP density S(ω) up to its scale α g² (scaled to H_s in [`Self::waves`]).
    fn jonswap_shape(omega: f64, omega_peak: f64, gamma: f64) -> f64 {
        let sigma = if omega <= omega_peak { 0.07 } else { 0.09 };
        let r = (-((omega - omega_peak).powi(2)) / (2.0 * sigma * sigma * omega_peak * omega_peak))
            .exp();
        omega.powi(-5) * (-1.25 * (omega_peak / omega).powi(4)).exp() * gamma.powf(r)
    }

    /// The waves: frequencies in equal bands of ln ω from 0.7 to 4 ω_peak, one jittered draw per
    /// band, amplitude √(2 S(ω) Δω) (each wave carries its band's variance), direction the
    /// wind's turned by a normally distributed angle.
    pub fn waves(&self) -> Vec<GerstnerWave> {
        let n = self.count as usize;
        if n == 0 {
            return Vec::new();
        }
        let k_peak = TAU / (self.peak_wavelength as f64).max(0.01);
        let omega_peak = (GRAVITY * k_peak).sqrt();
        let (lo, hi) = ((0.7 * omega_peak).ln(), (4.0 * omega_peak).ln());
        let band = (hi - lo) / n as f64;
        let gamma = (self.peak_enhancement as f64).max(1.0);
        let wind = DVec2::new(self.wind_direction[0] as f64, self.wind_direction[1] as f64)
            .try_normalize()
            .unwrap_or(DVec2::X);
        let mut rng = crate::school::rng::SplitMix64::new(self.seed);
        let mut draws = Vec::with_capacity(n);
        for i in 0..n {
            let ln_omega = lo + band * (i as f64 + rng.next_f32() as f64);
            let omega = ln_omega.exp();
            let d_omega = omega * band; // dω = ω d(ln ω)
            let variance = Self::jonswap_shape(omega, omega_peak, gamma) * d_omega;
            // Box–Muller: a normal angle about the wind
            let (u1, u2) = (rng.next_f32().max(1e-7) as f64, rng.next_f32() as f64);
            let normal = (-2.0 * u1.ln()).sqrt() * (TAU * u2).cos();
            let angle = normal * (self.spread_deg as f64).to_radians();
            let dir = DVec2::from_angle(angle).rotate(wind);
            draws.push((omega, variance, dir));
        }
        // scale so that 4 √(Σ A²/2) = H_s
        let m0: f64 = draws.iter().map(|d| d.1).sum();
        let target_m0 = (self.significant_height as f64 / 4.0).powi(2);
        let scale = if m0 > 0.0 { target_m0 / m0 } else { 0.0 };
        draws
            .into_iter()
            .map(|(omega, variance, dir)| {
                let k = omega * omega / GRAVITY;
                GerstnerWave {
                    direction: [dir.x as f32, dir.y as f32],
                    wavelength: (TAU / k) as f32,
                    amplitude: (2.0 * variance * scale).sqrt() as f32,
                    steepness: self.steepness.clamp(0.0, 1.0),
                    speed: (omega / k) as f32,
                }
            })
            .collect()
    }
}
