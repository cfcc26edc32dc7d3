//! Every number a bundled widget prints is in its `-readouts.csv`, equals what the slide shows
//! (the slide is drawn, its texts collected from the shapes egui paints, and each readout,
//! formatted as the widget formats it, found there) and is right: recomputed here from the
//! maths, independently of the widget's code (the spiral's radii by hand-written loops, the
//! Taylor errors from sin, the rigid body's ω from R I_body⁻¹ Rᵀ L, the transport step's
//! angle, axis and quaternions from the headings).

use std::path::Path;
use std::sync::{Arc, Mutex};

use egui_kittest::Harness;
use glam::{DMat3, DQuat, DVec3, Quat, Vec3};
use lectern::app::{SlideState, slide_ui};
use lectern::deck::{Deck, load_deck};
use lectern::widgets::style::fmt_num;
use lectern::widgets::{Readout, WidgetSpec};

fn lecture() -> Deck {
    load_deck(&Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron")).unwrap()
}

/// The lecture's slide `id` drawn at 1920×1080: every text it paints (rows joined, so a
/// number is found whatever line it wrapped onto) and its first widget's readouts, taken from
/// the drawn widget itself.
struct Shown {
    text: String,
    readouts: Vec<Readout>,
}

impl Shown {
    fn of(id: &str) -> Self {
        Self::of_deck(lecture(), id)
    }

    fn of_deck(deck: Deck, id: &str) -> Self {
        let deck = Arc::new(deck);
        let n = deck.find(id).unwrap();
        let state = Arc::new(Mutex::new(SlideState::default()));
        let (shown, drawn) = (deck.clone(), state.clone());
        let mut h = Harness::builder()
            .with_size(egui::vec2(1920.0, 1080.0))
            .build_ui(move |ui| {
                slide_ui(ui, &shown, n, &mut drawn.lock().unwrap());
            });
        h.run_steps(3);
        let mut text = String::new();
        for c in &h.output().shapes {
            collect_text(&c.shape, &mut text);
        }
        let (path, _) = deck.slides[n].widgets().into_iter().next().unwrap();
        let readouts = state
            .lock()
            .unwrap()
            .widget_at(&path)
            .expect("the slide's widget")
            .readouts();
        Self { text, readouts }
    }

    fn get(&self, name: &str, series: &str) -> f64 {
        self.readouts
            .iter()
            .find(|r| r.name == name && r.series == series)
            .unwrap_or_else(|| panic!("no readout {name},{series}: {:?}", self.readouts))
            .value
    }

    fn has(&self, name: &str, series: &str) -> bool {
        self.readouts
            .iter()
            .any(|r| r.name == name && r.series == series)
    }

    /// The slide shows `printed` (a readout as the widget formats it).
    fn prints(&self, printed: &str) {
        assert!(
            self.text.contains(printed),
            "{printed:?} is not on the slide: {:?}",
            self.text
        );
    }
}

/// The spec of the first widget on the lecture's slide `id`, as the deck writes it.
fn first_widget(id: &str) -> WidgetSpec {
    let deck = lecture();
    let (_, spec) = deck.slides[deck.find(id).unwrap()]
        .widgets()
        .into_iter()
        .next()
        .unwrap();
    spec.clone()
}

fn collect_text(shape: &egui::epaint::Shape, out: &mut String) {
    use egui::epaint::Shape;
    match shape {
        Shape::Vec(v) => v.iter().for_each(|s| collect_text(s, out)),
        Shape::Text(t) => {
            for row in &t.galley.rows {
                out.extend(row.row.glyphs.iter().map(|g| g.chr));
            }
            out.push('\n');
        }
        _ => {}
    }
}

fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!((a - b).abs() <= tol, "{what}: {a} vs {b}");
}

/// `export --data` of the whole lecture writes a readouts file beside every widget that
/// prints numbers (all but the water scene's pictures), and it holds what the drawn widget
/// reports.
#[test]
fn every_lecture_widget_writes_its_readouts() {
    lectern::widgets::work_precision::DETERMINISTIC
        .store(true, std::sync::atomic::Ordering::Relaxed);
    let deck = lecture();
    let dir = tempfile::tempdir().unwrap();
    let files =
        lectern::cli::export_data::write_data(&deck, dir.path(), &Default::default()).unwrap();
    let digits = deck.slides.len().to_string().len().max(2);
    let mut checked = Vec::new();
    for (i, slide) in deck.slides.iter().enumerate() {
        for (k, (_, w)) in slide.widgets().into_iter().enumerate() {
            if w.kind() == "scene" {
                continue;
            }
            let file = dir
                .path()
                .join(format!("slide-{:0digits$}-w{}-readouts.csv", i + 1, k + 1));
            assert!(
                files.contains(&file),
                "slide {} ({}): no {}",
                i + 1,
                w.kind(),
                file.display()
            );
            let text = std::fs::read_to_string(&file).unwrap();
            assert!(text.starts_with("readout,series,value\n") && text.lines().count() > 1);
            checked.push(w.kind());
        }
    }
    for kind in [
        "spiral",
        "taylor",
        "rigid-body",
        "parallel-transport",
        "stability",
    ] {
        assert!(checked.contains(&kind), "{kind} in {checked:?}");
    }
    // the file is the drawn widget's readouts (for widgets that do not play on their own)
    for id in ["inaccuracy", "taylor", "inertia", "exercise"] {
        let n = deck.find(id).unwrap();
        let file = dir
            .path()
            .join(format!("slide-{:0digits$}-w1-readouts.csv", n + 1));
        let text = std::fs::read_to_string(file).unwrap();
        assert_eq!(text, Readout::to_csv(&Shown::of(id).readouts), "{id}");
    }
}

/// Hand-written steps of (x, y)' = (−y, x), the circle problem.
fn circle_step(method: &str, p: [f64; 2], h: f64) -> [f64; 2] {
    let f = |p: [f64; 2]| [-p[1], p[0]];
    let add = |p: [f64; 2], k: [f64; 2], s: f64| [p[0] + s * k[0], p[1] + s * k[1]];
    match method {
        "euler" => add(p, f(p), h),
        "midpoint" => add(p, f(add(p, f(p), h / 2.0)), h),
        "rk4" => {
            let k1 = f(p);
            let k2 = f(add(p, k1, h / 2.0));
            let k3 = f(add(p, k2, h / 2.0));
            let k4 = f(add(p, k3, h));
            let k = [
                (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]) / 6.0,
                (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]) / 6.0,
            ];
            add(p, k, h)
        }
        _ => unreachable!("the spiral slide's methods"),
    }
}

/// Slide 6: the growth factor and every printed radius, recomputed by hand-written loops.
#[test]
fn the_spirals_radii_are_printed_and_right() {
    let s = Shown::of("inaccuracy");
    let h = s.get("h", "");
    close(
        s.get("growth_per_step", "euler"),
        (1.0 + h * h).sqrt(),
        1e-15,
        "√(1+h²)",
    );
    s.prints(&format!("√(1+h²) = {:.4} per step", (1.0 + h * h).sqrt()));
    for key in ["euler", "midpoint", "rk4"] {
        let mut printed = Vec::new();
        for turn in 1..=4 {
            let name = format!("radius_turn_{turn}");
            if !s.has(&name, key) {
                break;
            }
            let steps = (turn as f64 * std::f64::consts::TAU / h).round() as usize;
            let mut p = [1.0, 0.0];
            for _ in 0..steps {
                p = circle_step(key, p, h);
            }
            let r = s.get(&name, key);
            close(r, p[0].hypot(p[1]), 1e-12, &format!("{key} turn {turn}"));
            printed.push(fmt_num(r));
        }
        // the slide has three revolutions: three radii per panel
        assert_eq!(printed.len(), 3, "{key}");
        s.prints(&format!("r per turn: {}", printed.join(", ")));
    }
    // Euler's radius is (1 + h²)^(n/2) after n steps: the spiral the slide is about
    let n1 = (std::f64::consts::TAU / h).round();
    close(
        s.get("radius_turn_1", "euler"),
        (1.0 + h * h).powf(n1 / 2.0),
        1e-9,
        "Euler's growth",
    );
}

/// Slide 9: the error of each order at the printed point, from sin itself.
#[test]
fn the_taylor_errors_are_printed_and_right() {
    let s = Shown::of("taylor");
    let WidgetSpec::Taylor(spec) = first_widget("taylor") else {
        panic!("the Taylor slide's widget");
    };
    let (a, t) = (spec.a, s.get("t", ""));
    assert!((spec.range.0..=spec.range.1).contains(&t) && (t - a).abs() > 0.5);
    s.prints(&format!(
        "error at t = {}:",
        lectern::widgets::style::fmt_signed(t)
    ));
    // sin's derivatives cycle sin, cos, −sin, −cos
    let derivative = |k: usize| match k % 4 {
        0 => a.sin(),
        1 => a.cos(),
        2 => -a.sin(),
        _ => -a.cos(),
    };
    let mut errors = Vec::new();
    for n in 1..=spec.order {
        let poly: f64 = (0..=n)
            .map(|k| {
                let fact: f64 = (1..=k).map(|i| i as f64).product();
                derivative(k) * (t - a).powi(k as i32) / fact
            })
            .sum();
        let want = (poly - t.sin()).abs();
        let got = s.get("error", &format!("order{n}"));
        close(got, want, 1e-12, &format!("order {n}"));
        s.prints(&fmt_num(got));
        errors.push(got);
    }
    // a series that converges: each order closer than the one before, at one unit from a
    assert!(errors.windows(2).all(|w| w[1] < w[0]), "{errors:?}");
}

/// Slide 16: each method's ω_body is Rᵀ I_world⁻¹ L with I_world⁻¹ = R I_body⁻¹ Rᵀ built
/// here from the exported q, its E/E₀ and |L|/|L₀| from ω₀, the inertia line from the box
/// formula; and the slide prints each.
#[test]
fn the_rigid_body_numbers_are_printed_and_right() {
    let s = Shown::of("inertia");
    let WidgetSpec::RigidBody(spec) = first_widget("inertia") else {
        panic!("the rigid-body slide's widget");
    };
    let i_body = DVec3::new(spec.inertia.0, spec.inertia.1, spec.inertia.2);
    let omega0 = DVec3::new(spec.omega0.0, spec.omega0.1, spec.omega0.2);
    let l0 = i_body * omega0;
    let e0 = 0.5 * omega0.dot(l0);
    s.prints(&format!("t = {:.1}", spec.t));
    for key in ["euler", "midpoint", "rk4", "symplectic-euler"] {
        let r = |name: &str| s.get(name, key);
        close(r("time"), spec.t, 1e-9, "each method at the slide's t");
        let [w, x, y, z] = [r("q_w"), r("q_x"), r("q_y"), r("q_z")];
        close(w * w + x * x + y * y + z * z, 1.0, 1e-12, "unit q");
        // the rotation matrix of a unit quaternion, written out
        let rot = DMat3::from_cols_array(&[
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + w * z),
            2.0 * (x * z - w * y),
            2.0 * (x * y - w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z + w * x),
            2.0 * (x * z + w * y),
            2.0 * (y * z - w * x),
            1.0 - 2.0 * (x * x + y * y),
        ]);
        close(
            (rot * DVec3::X).distance(DQuat::from_xyzw(x, y, z, w) * DVec3::X),
            0.0,
            1e-12,
            "R written out is glam's",
        );
        let inv_world = rot * DMat3::from_diagonal(i_body.recip()) * rot.transpose();
        let l = DVec3::new(r("l_x"), r("l_y"), r("l_z"));
        let omega = inv_world * l;
        let omega_body = rot.transpose() * omega;
        for (axis, want) in ["x", "y", "z"].iter().zip(omega_body.to_array()) {
            close(r(&format!("omega_body_{axis}")), want, 1e-12, "ω_body");
        }
        close(r("energy_ratio"), 0.5 * l.dot(omega) / e0, 1e-12, "E/E₀");
        close(
            r("momentum_ratio"),
            l.length() / l0.length(),
            1e-12,
            "|L|/|L₀|",
        );
        s.prints(&format!("E/E₀     {}", fmt_num(r("energy_ratio"))));
        s.prints(&format!("|L|/|L₀| {}", fmt_num(r("momentum_ratio"))));
        s.prints(&format!(
            "ω_body ({:+.2}, {:+.2}, {:+.2})",
            omega_body.x, omega_body.y, omega_body.z
        ));
    }
    // the box is turned by t = 12: its world tensor is not diagonal (what slide 17 once printed)
    let q = DQuat::from_xyzw(
        s.get("q_x", "rk4"),
        s.get("q_y", "rk4"),
        s.get("q_z", "rk4"),
        s.get("q_w", "rk4"),
    );
    let rot = DMat3::from_quat(q);
    let inv_world = rot * DMat3::from_diagonal(i_body.recip()) * rot.transpose();
    assert!(inv_world.x_axis.y.abs() + inv_world.x_axis.z.abs() + inv_world.y_axis.z.abs() > 1e-3);
    // inertia of the drawn box at m = 1: m/12 (b² + c², …) exactly, n³ points (1 − 1/n²) of it
    let d = DVec3::new(
        s.get("dims_x", ""),
        s.get("dims_y", ""),
        s.get("dims_z", ""),
    );
    let box_formula = DVec3::new(
        d.y * d.y + d.z * d.z,
        d.x * d.x + d.z * d.z,
        d.x * d.x + d.y * d.y,
    ) / 12.0;
    let n = s.get("n", "");
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        close(
            s.get(&format!("inertia_mesh_{axis}"), ""),
            box_formula[k],
            1e-12,
            "Mirtich",
        );
        close(
            s.get(&format!("inertia_points_{axis}"), ""),
            box_formula[k] * (1.0 - 1.0 / (n * n)),
            1e-12,
            "points",
        );
    }
    close(
        s.get("inertia_rel_error", ""),
        1.0 / (n * n),
        1e-12,
        "rel. error",
    );
    s.prints(&format!(
        "mesh (Mirtich) ({:.4}, {:.4}, {:.4})",
        box_formula.x, box_formula.y, box_formula.z
    ));
    s.prints(&format!(
        "rel. error {}",
        fmt_num(s.get("inertia_rel_error", ""))
    ));
}

fn v3(s: &Shown, name: &str) -> Vec3 {
    Vec3::new(
        s.get(&format!("{name}_x"), "") as f32,
        s.get(&format!("{name}_y"), "") as f32,
        s.get(&format!("{name}_z"), "") as f32,
    )
}

fn quat(s: &Shown, name: &str) -> Quat {
    let c = |k: &str| s.get(&format!("{name}_{k}"), "") as f32;
    Quat::from_xyzw(c("x"), c("y"), c("z"), c("w"))
}

/// The same rotation up to the sign a quaternion may carry.
fn same_rotation(a: Quat, b: Quat, what: &str) {
    assert!(a.dot(b).abs() > 1.0 - 1e-5, "{what}: {a:?} vs {b:?}");
}

/// The step panel's quaternions make an orthonormal frame that carries the old heading to the
/// new one by the smallest rotation: axis t_old × t_new, angle acos(t_old · t_new).
fn check_transport_step(s: &Shown) {
    let (t_old, t_new) = (v3(s, "t_old"), v3(s, "t_new"));
    let (q_old, q_r, q_new) = (quat(s, "q_old"), quat(s, "q_rotation"), quat(s, "q_new"));
    for (q, what) in [(q_old, "q_old"), (q_r, "q(R)"), (q_new, "q_new")] {
        assert!(
            (q.length() - 1.0).abs() < 1e-5,
            "{what} is a unit quaternion"
        );
    }
    // the fish's frame (forward, up, side) stays orthonormal
    use lectern::school::{FISH_FORWARD, FISH_UP};
    let (f, u) = (q_new * FISH_FORWARD, q_new * FISH_UP);
    assert!(
        f.dot(u).abs() < 1e-5 && (f.length() - 1.0).abs() < 1e-5 && (u.length() - 1.0).abs() < 1e-5
    );
    assert!(
        (q_old * FISH_FORWARD).distance(t_old) < 1e-5,
        "q_old heads along t_old"
    );
    assert!(
        f.distance(t_new.normalize()) < 1e-4,
        "q_new heads along t_new"
    );
    let angle_deg = t_old
        .dot(t_new.normalize())
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees();
    close(s.get("angle_deg", ""), f64::from(angle_deg), 0.05, "angle");
    same_rotation(
        q_new,
        (q_r * q_old).normalize(),
        "q_new = normalize(q(R) q_old)",
    );
    let cross = t_old.cross(t_new);
    if cross.length() < 1e-4 {
        assert!(!s.has("axis_x", ""), "no axis on a straight step");
        same_rotation(q_r, Quat::IDENTITY, "R = identity");
        s.prints("R = identity");
    } else {
        let axis = cross.normalize();
        assert!(v3(s, "axis").distance(axis) < 1e-4, "axis");
        same_rotation(
            q_r,
            Quat::from_axis_angle(axis, angle_deg.to_radians()),
            "q(R)",
        );
        s.prints(&format!(
            "axis t_old×t_new ({:+.2}, {:+.2}, {:+.2}), angle acos(t_old·t_new) = {:.1}°",
            axis.x, axis.y, axis.z, angle_deg
        ));
    }
    let q_text = |q: Quat| format!("({:+.2}, {:+.2}, {:+.2}, {:+.2})", q.w, q.x, q.y, q.z);
    s.prints(&format!(
        "q_new = normalize(q(R)·q_old) = {}",
        q_text(q_new)
    ));
    s.prints(&format!(
        "q(R) = {}   q_old = {}",
        q_text(q_r),
        q_text(q_old)
    ));
    s.prints(&format!("Frenet flips: {}", s.get("frenet_flips", "")));
}

/// Slide 18 as bundled (a straight step) and on the curve of the same path (a step with an
/// axis): the printed frame, angle and axis are the transport's.
#[test]
fn the_transport_step_is_printed_and_right() {
    let s = Shown::of("exercise");
    check_transport_step(&s);
    assert!(!s.has("axis_x", ""), "the bundled step is straight");
    // a turning step of the same slide: the lecture's deck with the step moved onto the S
    let mut deck = lecture();
    let n = deck.find("exercise").unwrap();
    for b in deck.slides[n].body.iter_mut() {
        if let lectern::deck::Block::Widget(lectern::widgets::WidgetSpec::ParallelTransport(p)) = b
        {
            p.step = 12;
        }
    }
    let s = Shown::of_deck(deck, "exercise");
    assert!(s.has("axis_x", ""), "step 12 turns");
    check_transport_step(&s);
}

/// Slide 28: each method's steps and f-evaluations are printed as the readouts say, and they
/// are right for the fixed-step methods (Euler 1 f and RK4 4 f per step; implicit Euler and
/// midpoint take t_end / h steps), the exploding ones say where, and the adaptive one is marked.
#[test]
fn the_stiff_slides_work_is_printed_and_right() {
    let s = Shown::of("stiff");
    let h = s.get("h", "");
    for key in [
        "euler",
        "rk4",
        "implicit-euler",
        "implicit-midpoint",
        "radau5",
    ] {
        let (steps, f) = (s.get("steps", key), s.get("f_evals", key));
        s.prints(&format!("{steps} steps, {f} f"));
        match key {
            "euler" => assert_eq!(f, steps, "{key}"),
            "rk4" => assert_eq!(f, 4.0 * steps, "{key}"),
            "implicit-euler" | "implicit-midpoint" => {
                assert_eq!(steps, (10.0 / h).round(), "{key}")
            }
            _ => assert!(steps < 100.0, "radau5: {steps}"),
        }
    }
    for key in ["euler", "rk4"] {
        let t = s.get("diverged_at", key);
        s.prints(&format!(
            "|x| > 10⁶ at t = {}",
            lectern::widgets::style::fmt_signed(t)
        ));
    }
    s.prints("Radau IIA 5 (adaptive)");
    assert!(!s.has("diverged_at", "radau5"));
}
