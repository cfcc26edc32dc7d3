//! The deck's one colour map: each role (a built-in method, RK5, the notes' RK4 typo, a deck's
//! own tableau, the exact solution) has one named colour on every slide and in both themes, so a
//! slide can say "the vermillion line" and mean the same method everywhere.
//!
//! Hues from Okabe & Ito (2008, "Color Universal Design") and Paul Tol's qualitative schemes
//! (bright, vibrant, muted; <https://personal.sron.nl/~pault/>), each darkened or lightened just
//! enough to reach 3:1 (WCAG 2.1 non-text contrast) against both themes' backgrounds and plot
//! panels, so one colour serves both themes. Which hue went to which role was chosen by search
//! (the script is described in `docs/slides.md`): the methods that share a bundled slide stay
//! at least [`MIN_DELTA_E_ON_A_SLIDE`] apart in CIEDE2000 for normal vision and
//! [`MIN_DELTA_E_ON_A_SLIDE_DICHROMAT`] for protanope and deuteranope vision (simulated with
//! Machado et al. 2009); all roles at least [`MIN_DELTA_E_ANY`] apart.

use egui::Color32;

use crate::ode::Method;

/// A colour with the name slides use for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Hue {
    pub name: &'static str,
    pub color: Color32,
}

const fn hue(name: &'static str, r: u8, g: u8, b: u8) -> Hue {
    Hue {
        name,
        color: Color32::from_rgb(r, g, b),
    }
}

// Okabe–Ito
pub const VERMILLION: Hue = hue("vermillion", 0xD5, 0x5E, 0x00);
pub const BLUE: Hue = hue("blue", 0x00, 0x72, 0xB2);
pub const BLUISH_GREEN: Hue = hue("bluish green", 0x00, 0x9C, 0x72);
pub const PINK: Hue = hue("pink", 0xBE, 0x71, 0x9C);
pub const SKY_BLUE: Hue = hue("sky blue", 0x45, 0x91, 0xBB);
pub const AMBER: Hue = hue("amber", 0xB8, 0x7E, 0x00);
pub const OLIVE: Hue = hue("olive", 0x93, 0x8C, 0x29);
// Paul Tol
pub const RASPBERRY: Hue = hue("raspberry", 0xB0, 0x43, 0x81);
pub const ORCHID: Hue = hue("orchid", 0xBB, 0x5C, 0x92);
pub const VIOLET: Hue = hue("violet", 0x99, 0x66, 0xFF);
pub const SAND: Hue = hue("sand", 0x85, 0x7A, 0x47);
pub const GREY: Hue = hue("grey", 0x70, 0x70, 0x70);
pub const TEAL: Hue = hue("teal", 0x3D, 0x97, 0x88);
pub const WINE: Hue = hue("wine", 0xA2, 0x51, 0x79);
pub const STEEL_BLUE: Hue = hue("steel blue", 0x60, 0x8F, 0xA8);
pub const KHAKI: Hue = hue("khaki", 0x96, 0x89, 0x51);
pub const LEAF_GREEN: Hue = hue("leaf green", 0x22, 0x88, 0x33);
pub const BRICK: Hue = hue("brick", 0xCC, 0x33, 0x11);
pub const FOREST_GREEN: Hue = hue("forest green", 0x19, 0x7C, 0x3A);
// implicit Euler and implicit midpoint share the stiff slides (28, 29) with Euler, RK4 and
// radau5: chosen by a search over a 16-level sRGB grid for the largest smallest ΔE to those
// three under all three visions (13.2; Tol's magenta #EE3377 was 5.6 from RK4 for a
// deuteranope, slate blue #4477AA 6.2 from radau5's cyan), ≥ 6 from every other role, ≥ 3:1
pub const FUCHSIA: Hue = hue("fuchsia", 0xEE, 0x11, 0x99);
pub const PINE: Hue = hue("pine", 0x33, 0x77, 0x77);
pub const INDIGO: Hue = hue("indigo", 0x6E, 0x62, 0xAA);
pub const PURPLE: Hue = hue("purple", 0xAA, 0x44, 0x99);
pub const OCHRE: Hue = hue("ochre", 0x9C, 0x6B, 0x30);
// darkened from 0x1F9FC4 (2.93:1 on the light panel) to reach 3:1 on both themes
pub const CYAN: Hue = hue("cyan", 0x1C, 0x8F, 0xB0);

/// What a colour stands for on a slide.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    Method(Method),
    /// Dormand–Prince's fifth-order formula run at a fixed step (work-precision's "RK5").
    Rk5,
    /// The notes' RK4 with the k₄ typo (`tableaux/rk4-typo.ron`).
    Rk4Typo,
    /// The n-th (0-based) other tableau file of a widget's `methods:` list.
    Tableau(usize),
}

/// Deck tableaux other than the typo take these in order (then repeat).
pub const TABLEAU_HUES: [Hue; 3] = [INDIGO, AMBER, PURPLE];

/// The colour of `role`, the same on every slide.
pub fn hue_of(role: Role) -> Hue {
    match role {
        Role::Method(m) => method_hue(m),
        Role::Rk5 => ORCHID,
        Role::Rk4Typo => PINK,
        Role::Tableau(i) => TABLEAU_HUES[i % TABLEAU_HUES.len()],
    }
}

/// The colour of a built-in method.
pub fn method_hue(m: Method) -> Hue {
    match m {
        Method::Euler => VERMILLION,
        Method::Midpoint => BLUE,
        Method::Heun => WINE,
        Method::Rk4 => BLUISH_GREEN,
        Method::SymplecticEuler => RASPBERRY,
        Method::Verlet => OLIVE,
        Method::ImplicitEuler => FUCHSIA,
        Method::ImplicitMidpoint => PINE,
        Method::Dopri5 => KHAKI,
        Method::Tsit5 => VIOLET,
        Method::Vern6 => LEAF_GREEN,
        Method::Vern7 => BRICK,
        Method::Vern8 => FOREST_GREEN,
        Method::Vern9 => SAND,
        Method::Dop853 => GREY,
        Method::Rodas5p => OCHRE,
        Method::Radau5 => CYAN,
    }
}

/// Every role with a fixed colour (the first deck tableau standing for the others), for the
/// colour-map table in `docs/slides.md` and the tests.
pub fn all_roles() -> Vec<Role> {
    let mut v: Vec<Role> = Method::ALL.iter().map(|&m| Role::Method(m)).collect();
    v.extend([Role::Rk5, Role::Rk4Typo]);
    v.extend((0..TABLEAU_HUES.len()).map(Role::Tableau));
    v
}

/// The slide text's name for `role`'s colour ("vermillion").
pub fn name_of(role: Role) -> &'static str {
    hue_of(role).name
}

/// Bounds the colour-map test holds the map to, in CIEDE2000 units. Side by side, ΔE₀₀ ≈ 1–2 is
/// a just-noticeable difference for large patches; for lines a few points wide the difference
/// needed grows several times (Szafir 2018, "Modelling colour difference for visualization
/// design"). Normal vision: methods on one slide keep 15, above the pairs a lecturer could not
/// tell apart on the exported slide 13 (the typo's pink, DOP853's raspberry and Vern9's rose:
/// 12.7, 14.7 and 18.4, read as "three pinks"), so a slide's lines are told apart at a glance.
/// Simulated protanopia and deuteranopia: 7.5 (what seven lines between 3:1 on a dark and on a
/// light background leave a dichromat; a slide comparing that many labels them too). Any two
/// roles of the deck (never on one slide) keep 4.
pub const MIN_DELTA_E_ON_A_SLIDE: f32 = 15.0;
pub const MIN_DELTA_E_ON_A_SLIDE_DICHROMAT: f32 = 7.5;
pub const MIN_DELTA_E_ANY: f32 = 4.0;

/// The contrast every map colour has as a line on both themes' backgrounds and plot panels.
pub const MIN_LINE_CONTRAST: f32 = 3.0;

/// CIE L*a*b* (D65) of an sRGB colour.
pub fn lab(c: [f32; 3]) -> [f32; 3] {
    let lin = |s: f32| {
        if s <= 0.04045 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        }
    };
    let [r, g, b] = c.map(lin);
    let x = 0.412_456_4 * r + 0.357_576_1 * g + 0.180_437_5 * b;
    let y = 0.212_672_9 * r + 0.715_152_2 * g + 0.072_175 * b;
    let z = 0.019_333_9 * r + 0.119_192 * g + 0.950_304_1 * b;
    let f = |t: f32| {
        let d = 6.0_f32 / 29.0;
        if t > d * d * d {
            t.cbrt()
        } else {
            t / (3.0 * d * d) + 4.0 / 29.0
        }
    };
    let (fx, fy, fz) = (f(x / 0.950_47), f(y), f(z / 1.088_83));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// sRGB components of a colour, 0 … 1.
pub fn srgb(c: Color32) -> [f32; 3] {
    [c.r(), c.g(), c.b()].map(|v| f32::from(v) / 255.0)
}

/// CIEDE2000 colour difference of two L*a*b* colours (Sharma, Wu & Dalal 2005).
pub fn delta_e_2000(p: [f32; 3], q: [f32; 3]) -> f32 {
    let (p, q) = (p.map(f64::from), q.map(f64::from));
    let [l1, a1, b1] = p;
    let [l2, a2, b2] = q;
    let c_bar = 0.5 * (a1.hypot(b1) + a2.hypot(b2));
    let c7 = c_bar.powi(7);
    let g = 0.5 * (1.0 - (c7 / (c7 + 25f64.powi(7))).sqrt());
    let (a1p, a2p) = ((1.0 + g) * a1, (1.0 + g) * a2);
    let (c1p, c2p) = (a1p.hypot(b1), a2p.hypot(b2));
    let hue = |a: f64, b: f64| {
        if a == 0.0 && b == 0.0 {
            0.0
        } else {
            b.atan2(a).to_degrees().rem_euclid(360.0)
        }
    };
    let (h1p, h2p) = (hue(a1p, b1), hue(a2p, b2));
    let dl = l2 - l1;
    let dc = c2p - c1p;
    let dh = if c1p * c2p == 0.0 {
        0.0
    } else {
        let d = h2p - h1p;
        if d > 180.0 {
            d - 360.0
        } else if d < -180.0 {
            d + 360.0
        } else {
            d
        }
    };
    let dh_big = 2.0 * (c1p * c2p).sqrt() * (dh.to_radians() / 2.0).sin();
    let l_bar = 0.5 * (l1 + l2);
    let cp_bar = 0.5 * (c1p + c2p);
    let h_bar = if c1p * c2p == 0.0 {
        h1p + h2p
    } else if (h1p - h2p).abs() <= 180.0 {
        0.5 * (h1p + h2p)
    } else if h1p + h2p < 360.0 {
        0.5 * (h1p + h2p + 360.0)
    } else {
        0.5 * (h1p + h2p - 360.0)
    };
    let cos = |deg: f64| deg.to_radians().cos();
    let t =
        1.0 - 0.17 * cos(h_bar - 30.0) + 0.24 * cos(2.0 * h_bar) + 0.32 * cos(3.0 * h_bar + 6.0)
            - 0.20 * cos(4.0 * h_bar - 63.0);
    let d_theta = 30.0 * (-((h_bar - 275.0) / 25.0).powi(2)).exp();
    let cp7 = cp_bar.powi(7);
    let r_c = 2.0 * (cp7 / (cp7 + 25f64.powi(7))).sqrt();
    let s_l = 1.0 + 0.015 * (l_bar - 50.0).powi(2) / (20.0 + (l_bar - 50.0).powi(2)).sqrt();
    let s_c = 1.0 + 0.045 * cp_bar;
    let s_h = 1.0 + 0.015 * cp_bar * t;
    let r_t = -(2.0 * d_theta).to_radians().sin() * r_c;
    let (x, y, z) = (dl / s_l, dc / s_c, dh_big / s_h);
    (x * x + y * y + z * z + r_t * y * z).sqrt() as f32
}

/// Colour vision a colour is seen with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Vision {
    Normal,
    /// Missing L cones (about 1 % of men).
    Protanopia,
    /// Missing M cones (about 1 % of men; anomalous trichromacy, milder, 5 %).
    Deuteranopia,
}

/// `c` as seen with `vision`: Machado, Oliveira & Fernandes (2009), severity 1, applied to
/// linear RGB.
pub fn simulate(c: Color32, vision: Vision) -> [f32; 3] {
    let m: [[f32; 3]; 3] = match vision {
        Vision::Normal => return srgb(c),
        Vision::Protanopia => [
            [0.152_286, 1.052_583, -0.204_868],
            [0.114_503, 0.786_281, 0.099_216],
            [-0.003_882, -0.048_116, 1.051_998],
        ],
        Vision::Deuteranopia => [
            [0.367_322, 0.860_646, -0.227_968],
            [0.280_085, 0.672_501, 0.047_413],
            [-0.011_820, 0.042_940, 0.968_881],
        ],
    };
    let lin = |s: f32| {
        if s <= 0.04045 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        }
    };
    let unlin = |l: f32| {
        let l = l.clamp(0.0, 1.0);
        if l <= 0.003_130_8 {
            12.92 * l
        } else {
            1.055 * l.powf(1.0 / 2.4) - 0.055
        }
    };
    let x = srgb(c).map(lin);
    let row = |r: [f32; 3]| unlin(r[0] * x[0] + r[1] * x[1] + r[2] * x[2]);
    [row(m[0]), row(m[1]), row(m[2])]
}

/// The least ΔE₀₀ two methods on one slide must keep, seen with `vision`.
pub fn min_delta_e_on_a_slide(vision: Vision) -> f32 {
    match vision {
        Vision::Normal => MIN_DELTA_E_ON_A_SLIDE,
        Vision::Protanopia | Vision::Deuteranopia => MIN_DELTA_E_ON_A_SLIDE_DICHROMAT,
    }
}

/// ΔE₀₀ of two colours as seen with `vision`.
pub fn delta_e(a: Color32, b: Color32, vision: Vision) -> f32 {
    delta_e_2000(lab(simulate(a, vision)), lab(simulate(b, vision)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ciede2000_matches_sharmas_test_data() {
        // pairs 1, 7 and 17 of Sharma, Wu & Dalal (2005), table 1
        let cases = [
            ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
            ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
            ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0], 27.1492),
        ];
        for (p, q, want) in cases {
            let got = delta_e_2000(p, q);
            assert!((got - want).abs() < 1e-3, "{p:?} {q:?}: {got} ≠ {want}");
        }
    }

    #[test]
    fn simulated_dichromats_confuse_what_they_should() {
        // red and green, far apart for normal vision, nearly merge for a deuteranope; blue and
        // yellow stay apart for both
        let (red, green) = (
            Color32::from_rgb(200, 60, 40),
            Color32::from_rgb(110, 140, 40),
        );
        assert!(delta_e(red, green, Vision::Normal) > 30.0);
        assert!(delta_e(red, green, Vision::Deuteranopia) < 12.0);
        let (blue, yellow) = (
            Color32::from_rgb(0, 90, 200),
            Color32::from_rgb(230, 200, 40),
        );
        for v in [Vision::Protanopia, Vision::Deuteranopia] {
            assert!(delta_e(blue, yellow, v) > 40.0, "{v:?}");
        }
    }

    #[test]
    fn every_role_has_its_own_named_colour() {
        let roles = all_roles();
        for (i, a) in roles.iter().enumerate() {
            for b in &roles[i + 1..] {
                let (ha, hb) = (hue_of(*a), hue_of(*b));
                assert_ne!(ha.name, hb.name, "{a:?} and {b:?}");
                let d = delta_e(ha.color, hb.color, Vision::Normal);
                assert!(d >= MIN_DELTA_E_ANY, "{a:?} and {b:?}: ΔE {d:.1}");
            }
        }
    }
}
