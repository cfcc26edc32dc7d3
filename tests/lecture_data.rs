//! What the bundled lecture's slides say and compute, read back from `export --data` (the
//! CSVs of the plot widgets and the `-readouts.csv` of the numbers they print): the defaults
//! teach each slide's point, the stability regions are whole and inside the plot, and the
//! printed numbers agree with the maths.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use lectern::deck::{Block, Deck, load_deck};

fn lecture() -> Deck {
    load_deck(&Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron")).unwrap()
}

/// `export --data` of the lecture's slides with these ids (in the deck's order): the folder
/// and, per id, the CSV text of its first widget and its readouts.
struct Exported {
    _dir: tempfile::TempDir,
    csv: HashMap<String, String>,
    readouts: HashMap<String, Vec<(String, String, f64)>>,
}

fn export(ids: &[&str]) -> Exported {
    export_deck(only(ids))
}

/// The lecture with only the slides with these ids.
fn only(ids: &[&str]) -> Deck {
    let mut deck = lecture();
    deck.slides.retain(|s| ids.contains(&s.key()));
    assert_eq!(
        deck.slides.len(),
        ids.len(),
        "every id is a slide of the lecture"
    );
    deck
}

fn export_deck(deck: Deck) -> Exported {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("data");
    let files = lectern::cli::export_data::write_data(&deck, &out, &Default::default()).unwrap();
    let mut csv = HashMap::new();
    let mut readouts = HashMap::new();
    for (i, s) in deck.slides.iter().enumerate() {
        let stem = format!("slide-{:02}-w1", i + 1);
        let file = |name: String| -> Option<PathBuf> {
            let p = out.join(name);
            files.contains(&p).then_some(p)
        };
        if let Some(p) = file(format!("{stem}.csv")) {
            csv.insert(s.key().to_owned(), std::fs::read_to_string(p).unwrap());
        }
        if let Some(p) = file(format!("{stem}-readouts.csv")) {
            let text = std::fs::read_to_string(p).unwrap();
            assert!(text.starts_with("readout,series,value\n"), "{text}");
            let rows = text
                .lines()
                .skip(1)
                .map(|l| {
                    let v: Vec<&str> = l.split(',').collect();
                    (v[0].to_owned(), v[1].to_owned(), v[2].parse().unwrap())
                })
                .collect();
            readouts.insert(s.key().to_owned(), rows);
        }
    }
    Exported {
        _dir: dir,
        csv,
        readouts,
    }
}

impl Exported {
    fn readout(&self, slide: &str, name: &str, series: &str) -> f64 {
        self.readouts[slide]
            .iter()
            .find(|r| r.0 == name && r.1 == series)
            .unwrap_or_else(|| {
                panic!(
                    "{slide}: no readout {name},{series}: {:?}",
                    self.readouts[slide]
                )
            })
            .2
    }

    /// The rows of a `series,a,b[,…]` CSV belonging to `series`, as numbers.
    fn rows(&self, slide: &str, series: &str) -> Vec<Vec<f64>> {
        self.csv[slide]
            .lines()
            .skip(1)
            .filter(|l| l.split(',').next() == Some(series))
            .map(|l| l.split(',').skip(1).map(|v| v.parse().unwrap()).collect())
            .collect()
    }
}

/// Where a closed polyline crosses Im z = 0 (`axis` 0: the Re values) or Re z = 0 (`axis` 1:
/// the Im values), by linear interpolation between its vertices.
fn crossings(line: &[Vec<f64>], axis: usize) -> Vec<f64> {
    let other = 1 - axis;
    line.windows(2)
        .filter(|w| (w[0][other] <= 0.0) != (w[1][other] <= 0.0))
        .map(|w| {
            let t = w[0][other] / (w[0][other] - w[1][other]);
            w[0][axis] + t * (w[1][axis] - w[0][axis])
        })
        .collect()
}

#[test]
fn the_stability_regions_are_whole_and_inside_the_plot() {
    let e = export(&["stability"]);
    assert!(e.csv["stability"].starts_with("series,re,im\n"));
    let plot = [
        e.readout("stability", "plot_re_min", ""),
        e.readout("stability", "plot_re_max", ""),
        e.readout("stability", "plot_im_min", ""),
        e.readout("stability", "plot_im_max", ""),
    ];
    for key in ["euler", "midpoint", "rk4", "rk4-typo"] {
        let line = e.rows("stability", key);
        assert!(line.len() > 50, "{key}: a polyline, {} points", line.len());
        assert_eq!(line.first(), line.last(), "{key}: closed");
        for z in &line {
            assert!(
                (plot[0]..=plot[1]).contains(&z[0]) && (plot[2]..=plot[3]).contains(&z[1]),
                "{key}: {z:?} outside the plotted {plot:?}"
            );
        }
    }
    let leftmost = |key: &str| {
        crossings(&e.rows("stability", key), 0)
            .into_iter()
            .fold(f64::MAX, f64::min)
    };
    let typo = leftmost("rk4-typo");
    assert!(
        (typo + 4.0).abs() <= 0.02,
        "the typo's region reaches {typo}, not −4.0"
    );
    let rk4 = leftmost("rk4");
    assert!(
        (rk4 + 2.785).abs() <= 0.01,
        "RK4's region reaches {rk4}, not −2.785"
    );
    let im = crossings(&e.rows("stability", "rk4"), 1);
    let (lo, hi) = im
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
    assert!(
        (hi - 2.83).abs() <= 0.01 && (lo + 2.83).abs() <= 0.01,
        "RK4 on the imaginary axis: {lo} … {hi}"
    );
    // the plot is fitted to the regions, not a fixed −9 … 8
    assert!(
        plot[0] > -5.0 && plot[0] < -4.0 && plot[1] < 1.0,
        "{plot:?}"
    );
    // λ = i: Euler is never stable (the slide says "never"), RK4 up to 2√2
    assert_eq!(e.readout("stability", "stable_h", "euler"), 0.0);
    let rk4_h = e.readout("stability", "stable_h", "rk4");
    assert!((rk4_h - 8f64.sqrt()).abs() < 1e-6, "{rk4_h}");
}

#[test]
fn the_default_euler_step_is_visibly_wrong() {
    let e = export(&["euler"]);
    let err = e.readout("euler", "error_end", "euler");
    let exact = e.readout("euler", "exact_end", "");
    assert!(
        err > 0.05 * exact.abs(),
        "Euler misses by {err}, only {:.1} % of {exact}",
        100.0 * err / exact.abs()
    );
    // the CSV's step lands where the readout says
    let step = e.rows("euler", "euler");
    let x_end = e.readout("euler", "x_end", "euler");
    assert_eq!(step.last().unwrap()[1], x_end);
}

#[test]
fn the_default_neptune_path_runs_away() {
    let e = export(&["instability"]);
    let euler = e.rows("instability", "euler");
    let start = euler[0][1].abs();
    let most = euler.iter().map(|r| r[1].abs()).fold(0.0, f64::max);
    assert!(
        most > 10.0 * start,
        "Euler's |y| grows only {:.1}×",
        most / start
    );
    // RK4 at the same h still decays, and λ is what the slide prints
    let rk4 = e.rows("instability", "rk4");
    assert!(rk4.last().unwrap()[1].abs() < start);
    assert!((e.readout("instability", "lambda_re", "") + 5.0).abs() < 1e-6);
    let h = e.readout("instability", "h", "");
    let euler_limit = e.readout("instability", "stable_h", "euler");
    assert!(
        (euler_limit - 0.4).abs() < 1e-6 && h > euler_limit,
        "h {h}, limit {euler_limit}"
    );
}

#[test]
fn the_slope_fields_errors_are_at_the_end_of_the_interval() {
    let e = export(&["slope-field"]);
    let t_end = e.readout("slope-field", "t_end", "");
    for key in ["euler", "midpoint", "rk4"] {
        let last = e.rows("slope-field", key).last().unwrap().clone();
        assert_eq!(last[0], t_end, "{key} ends at t_end");
        let err = e.readout("slope-field", "error_at_end", key);
        let exact = e.rows("slope-field", "exact").last().unwrap().clone();
        assert_eq!(exact[0], t_end);
        assert!((err - (last[1] - exact[1]).abs()).abs() < 1e-12, "{key}");
    }
}

/// The loop prints the world inverse inertia in full, and the ω beside it is that matrix
/// times L.
#[test]
fn the_simulation_loop_prints_the_world_inverse_inertia() {
    let e = export(&["simulation"]);
    let r = |name: &str, s: &str| e.readout("simulation", name, s);
    let l = [r("l", "x"), r("l", "y"), r("l", "z")];
    for (row, axis) in ["x", "y", "z"].iter().enumerate() {
        let w: f64 = (0..3)
            .map(|c| r("inv_inertia_world", &format!("r{row}c{c}")) * l[c])
            .sum();
        assert!((w - r("omega", axis)).abs() < 1e-12, "ω_{axis}");
    }
    // the body is turned: R I_body⁻¹ Rᵀ is not I_body⁻¹'s diagonal (what the slide printed)
    let off = r("inv_inertia_world", "r0c1").abs()
        + r("inv_inertia_world", "r0c2").abs()
        + r("inv_inertia_world", "r1c2").abs();
    let diag = r("inv_inertia_world", "r0c0").abs();
    assert!(off > 1e-3 * diag, "off-diagonal {off} vs {diag}");
}

/// Slide 9: four orders, four curves — around a = 1 no term of sin's series vanishes, so each
/// order differs from the one before it visibly inside the plotted range.
#[test]
fn the_taylor_slide_shows_four_distinct_orders() {
    use lectern::deck::widgets::WidgetSpec;
    use lectern::widgets::taylor::truncation;
    let deck = lecture();
    let slide = &deck.slides[deck.find("taylor").unwrap()];
    let Some(Block::Widget(WidgetSpec::Taylor(t))) =
        slide.body.iter().find(|b| matches!(b, Block::Widget(_)))
    else {
        panic!("the Taylor slide has its widget");
    };
    assert!(t.order >= 4);
    let (lo, hi) = t.range;
    // within a unit of the expansion point, where the slide's y-range shows the curves
    let near: Vec<f64> = (0..=200)
        .map(|i| (t.a - 1.0) + 2.0 * i as f64 / 200.0)
        .filter(|x| (lo..=hi).contains(x))
        .collect();
    for n in 1..4 {
        let gap = near
            .iter()
            .map(|&x| {
                (truncation(t.function, t.a, n + 1, x) - truncation(t.function, t.a, n, x)).abs()
            })
            .fold(0.0, f64::max);
        assert!(
            gap > 0.02,
            "orders {n} and {} coincide (differ by {gap})",
            n + 1
        );
    }
}

/// Slide 18's default step sits on the straight part: no rotation axis is printed there.
#[test]
fn no_axis_is_printed_on_a_straight_step() {
    use lectern::deck::widgets::WidgetSpec;
    use lectern::widgets::parallel_transport::{ParallelTransport, rotation_text};
    let deck = lecture();
    let slide = &deck.slides[deck.find("exercise").unwrap()];
    let spec = slide
        .widgets()
        .into_iter()
        .find_map(|(_, w)| match w {
            WidgetSpec::ParallelTransport(s) => Some(s.clone()),
            _ => None,
        })
        .unwrap();
    let step = ParallelTransport::new(spec).shown_step();
    assert!(step.angle_rad.abs() < 1e-6, "the default step is straight");
    let text = rotation_text(&step);
    assert!(
        step.axis.is_none() && !text.contains("axis t_old"),
        "{text}"
    );
}

/// The counter counts the talk: the last slide paging reaches reads "n / n", and an optional
/// slide says so instead of claiming a place in the talk.
#[test]
fn the_counter_agrees_with_paging() {
    let deck = lecture();
    let mut nav = lectern::deck::Nav::new(&deck);
    nav.first(&deck);
    let mut seen = vec![deck.counter(nav.index())];
    while nav.next(&deck) {
        seen.push(deck.counter(nav.index()));
    }
    let n = seen.len();
    for (k, c) in seen.iter().enumerate() {
        assert_eq!(
            c,
            &format!("{} / {n}", k + 1),
            "paging shows consecutive numbers"
        );
    }
    for (i, s) in deck.slides.iter().enumerate().filter(|(_, s)| s.skip) {
        assert_eq!(
            deck.counter(i),
            format!("{} · optional", i + 1),
            "{}",
            s.title
        );
    }
    let title = &deck.slides[0];
    assert_eq!(title.layout, lectern::deck::Layout::Title);
    assert!(deck.lecturer.is_some() && deck.date.is_some());
}

/// Slide 13: each slope is fitted where truncation error dominates, so the high orders read
/// as their orders, not steeper (round-off flattens, then scatters, the last points).
#[test]
fn the_convergence_slopes_are_the_orders() {
    let e = export(&["convergence"]);
    for (key, order, tol) in [
        ("euler", 1.0, 0.15),
        ("midpoint", 2.0, 0.2),
        ("rk4", 4.0, 0.3),
        ("rk4-typo", 1.0, 0.2),
        ("dop853", 8.0, 0.3),
    ] {
        let slope = e.readout("convergence", "slope", key);
        assert!(
            (slope - order).abs() <= tol,
            "{key}: slope {slope}, order {order}"
        );
    }
    // Vern9 reaches round-off (1e-15) after two halvings: two points are no measured order,
    // so no slope is printed (it used to read 10.53)
    assert!(
        !e.readouts["convergence"]
            .iter()
            .any(|r| r.0 == "slope" && r.1 == "vern9"),
        "{:?}",
        e.readouts["convergence"]
    );
}

/// Slide 12 names the typo's line by the colour the colour map gives it on slide 13.
#[test]
fn the_rk4_slide_names_the_typos_colour() {
    use lectern::widgets::colors::{Role, name_of};
    let deck = lecture();
    let slide = &deck.slides[deck.find("rk4").unwrap()];
    let text: String = slide
        .body
        .iter()
        .filter_map(|b| match b {
            Block::Text(t) => Some(t.src.as_str()),
            _ => None,
        })
        .collect();
    let name = name_of(Role::Rk4Typo);
    assert!(
        text.contains(&format!("{name} line")),
        "{text:?} does not say the {name} line"
    );
}

/// The work-precision widget on a stiff problem file (issue #26): a deck with it exports; the
/// stiff solvers' points are there and meet their tolerance; DOPRI5 and DOP853 are stopped by
/// their stiffness test (read back as `stiff_at`) instead of grinding through the 2¹⁸-step
/// budget; fixed-step RK4 explodes.
#[test]
fn the_work_precision_widget_runs_the_stiff_solvers_on_a_stiff_problem() {
    use lectern::widgets::work_precision::{DETERMINISTIC, WorkPrecision};
    DETERMINISTIC.store(true, std::sync::atomic::Ordering::Relaxed);
    let deck_file = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/stiff-test.ron");
    let text = r#"(
        title: "stiff",
        slides: [(
            id: "stiff",
            title: "Van der Pol, mu = 1000",
            body: [Widget(WorkPrecision((ode: File("problems/vanderpol-1000.ron"), t_end: 2000.0, levels: 4, methods: [Rk4, Dopri5, Dop853, Rodas5p, Radau5], rk5: false)))],
        )],
    )"#;
    // as if the file were in slides/ (its problem path resolves there)
    let deck = lectern::deck::parse_deck_file(text, &deck_file).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let start = std::time::Instant::now();
    let files =
        lectern::cli::export_data::write_data(&deck, dir.path(), &Default::default()).unwrap();
    let csv_file = dir.path().join("slide-01-w1.csv");
    assert!(files.contains(&csv_file), "{files:?}");
    let csv = std::fs::read_to_string(&csv_file).unwrap();
    let rows = |series: &str| -> Vec<Vec<f64>> {
        csv.lines()
            .filter(|l| l.split(',').next() == Some(series))
            .map(|l| l.split(',').skip(2).map(|v| v.parse().unwrap()).collect())
            .collect()
    };
    // (tol, f-evals, error) per run of each stiff solver: all twelve tolerances, and from
    // 1e-4 to 1e-9 the error within 100·tol of the reference (RADAU5 at rtol 1e-13, as
    // `ode::study::reference` picks for a stiff problem; rodas5p agrees with it to 3e-13)
    for stiff in ["rodas5p", "radau5"] {
        let runs = rows(stiff);
        assert_eq!(runs.len(), 12, "{stiff}: {csv}");
        for r in runs.iter().filter(|r| r[0] <= 1e-4 && r[0] >= 1e-9) {
            assert!(
                r[2] < 100.0 * r[0],
                "{stiff} at tol {:e}: error {:e}",
                r[0],
                r[2]
            );
        }
        // a few thousand f-evaluations at 1e-6, where an explicit pair needs millions
        let at_1e6 = runs
            .iter()
            .find(|r| (r[0] / 1e-6 - 1.0).abs() < 1e-9)
            .unwrap();
        assert!(at_1e6[1] < 3e4, "{stiff}: {at_1e6:?}");
    }
    // the explicit pairs stop at the stiffness test: not finished (error ∞) after far fewer
    // f-evaluations than the step budget would allow (2¹⁸ steps × 6 or 12)
    for pair in ["dopri5", "dop853"] {
        let runs = rows(pair);
        assert_eq!(runs.len(), 12);
        for r in &runs {
            assert!(r[2].is_infinite(), "{pair}: {r:?}");
            assert!(r[1] < 2e5, "{pair} ran {} f-evaluations", r[1]);
        }
    }
    // fixed-step RK4 at h = 1 … 1/8 is far beyond its stability limit (|λ| ~ 1000): diverged
    assert!(rows("rk4").iter().all(|r| r[2].is_infinite()));
    // the widget says where the pairs were stopped (its caption reads "stiff: stopped at t = …")
    let spec = match &deck.slides[0].widgets()[0].1 {
        lectern::widgets::WidgetSpec::WorkPrecision(s) => s.clone(),
        _ => unreachable!("the deck above has one WorkPrecision"),
    };
    let curves =
        WorkPrecision::new(spec, lectern::widgets::MadeIn::deck(Some(&deck_file))).compute();
    for c in &curves {
        let stiff_at = c.stiff_at();
        match c.key.as_str() {
            "dopri5" | "dop853" => {
                let t = stiff_at.unwrap_or_else(|| panic!("{}: {:?}", c.key, c.samples));
                // the first relaxation jump of Van der Pol, mu = 1000, is near t ≈ 807; the
                // test fires on the slow branch before it
                assert!(t > 0.0 && t < 2000.0, "{}: {t}", c.key);
            }
            _ => assert_eq!(stiff_at, None, "{}", c.key),
        }
    }
    println!("export and study: {:.1} s", start.elapsed().as_secs_f64());
}

/// The stiff slide's energy, computed here from the CSV's states and the problem file's k
/// (independently of the widget's own energy expression).
fn stiff_energy(x: &[f64], k: f64) -> f64 {
    // rows: t, x1, v1, x2, v2
    let (x1, v1, x2, v2) = (x[1], x[2], x[3], x[4]);
    0.5 * (v1 * v1 + v2 * v2) + 0.5 * x1 * x1 + 0.5 * k * (x2 - x1).powi(2)
}

fn stiff_k() -> f64 {
    let p = lectern::ode::problem::Problem::load(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/problems/stiff-spring.ron"),
    )
    .unwrap();
    p.params.iter().find(|(n, _)| n == "k").unwrap().1
}

/// The optional stiff slide's defaults make its point: at h = 0.1 on k = 1000 explicit Euler
/// and RK4 explode, implicit Euler stays stable but drains the energy, implicit midpoint keeps
/// it, and radau5 finishes in few steps.
#[test]
fn the_stiff_slide_explodes_damps_and_keeps() {
    let e = export(&["stiff"]);
    let k = stiff_k();
    assert!(e.csv["stiff"].starts_with("series,t,x1,v1,x2,v2\n"));
    let grows = |key: &str| {
        let rows = e.rows("stiff", key);
        let size = |r: &Vec<f64>| r[1].abs().max(r[3].abs());
        rows.iter().map(size).fold(0.0, f64::max) / size(&rows[0])
    };
    for key in ["euler", "rk4"] {
        let g = grows(key);
        assert!(g > 10.0, "{key}: |x| grows {g}×, not > 10×");
        assert!(e.readout("stiff", "diverged_at", key) < 10.0, "{key}");
    }
    let energy = |key: &str| -> Vec<f64> {
        e.rows("stiff", key)
            .iter()
            .map(|r| stiff_energy(r, k))
            .collect()
    };
    let ie = energy("implicit-euler");
    let decay = 1.0 - ie.last().unwrap() / ie[0];
    assert!(decay > 0.2, "implicit Euler's energy decays {decay}");
    let im = energy("implicit-midpoint");
    for v in &im {
        assert!(
            (v / im[0] - 1.0).abs() < 0.01,
            "implicit midpoint: {}",
            v / im[0]
        );
    }
    // the widget's own readout agrees with the CSV's energy
    let printed = e.readout("stiff", "energy_end", "implicit-euler");
    assert!(
        (printed - ie.last().unwrap() / ie[0]).abs() < 1e-9,
        "{printed}"
    );
    // the adaptive method ends near the reference and took large steps
    let radau_rows = e.rows("stiff", "radau5");
    assert_eq!(*radau_rows.last().unwrap().first().unwrap(), 10.0);
    let err = e.readout("stiff", "error_at_end", "radau5");
    assert!(err < 1e-3, "radau5 ends {err} from the reference");
    let steps = e.readout("stiff", "steps", "radau5");
    assert_eq!(steps as usize, radau_rows.len() - 1);
}

/// At equal end error the adaptive implicit method takes far fewer steps than RK4: RK4's h is
/// walked down from the slide's 0.1 by 5 % at a time until RK4 finishes with an error at t_end
/// no larger than radau5's — the stiff spring's stability limit comes first, and below it
/// RK4 is already more accurate than asked: its step is set by stability, not accuracy.
#[test]
fn radau5_takes_far_fewer_steps_than_rk4_at_equal_error() {
    let with_h = |h: f64| {
        let mut deck = only(&["stiff"]);
        for b in &mut deck.slides[0].body {
            if let Block::Widget(lectern::deck::widgets::WidgetSpec::Energy(s)) = b {
                s.h = h;
            }
        }
        export_deck(deck)
    };
    let mut found = None;
    for j in 1..120 {
        let h = 0.1 * 0.95_f64.powi(j);
        let e = with_h(h);
        let radau_err = e.readout("stiff", "error_at_end", "radau5");
        let radau_steps = e.readout("stiff", "steps", "radau5");
        let rk4 = e.readouts["stiff"]
            .iter()
            .find(|r| r.0 == "error_at_end" && r.1 == "rk4")
            .map(|r| r.2);
        if let Some(rk4_err) = rk4
            && rk4_err <= radau_err
        {
            found = Some((
                h,
                rk4_err,
                radau_err,
                e.readout("stiff", "steps", "rk4"),
                radau_steps,
            ));
            break;
        }
    }
    let (h, rk4_err, radau_err, rk4_steps, radau_steps) =
        found.expect("RK4 reaches radau5's error at some h ≥ 0.0003");
    eprintln!(
        "equal error: RK4 h = {h}, error {rk4_err:e}, {rk4_steps} steps; radau5 error {radau_err:e}, {radau_steps} steps"
    );
    assert!(
        radau_steps * 5.0 <= rk4_steps,
        "radau5 {radau_steps} steps vs RK4 {rk4_steps} at h = {h}"
    );
}

/// The implicit methods' regions, from `export --data`: implicit Euler's boundary is the
/// circle |z − 1| = 1, radau5's lies in Re z > 0 (A-stable), and the plot box is not absurdly
/// wide.
#[test]
fn the_implicit_regions_are_their_true_shapes() {
    let e = export(&["stiff-stability"]);
    let ie = e.rows("stiff-stability", "implicit-euler");
    assert!(ie.len() > 50, "{} points", ie.len());
    for z in &ie {
        let d = (z[0] - 1.0).hypot(z[1]);
        assert!((d - 1.0).abs() < 1e-3, "{z:?} is {d} from 1");
    }
    let radau = e.rows("stiff-stability", "radau5");
    assert!(radau.len() > 50, "{} points", radau.len());
    assert!(
        radau.iter().all(|z| z[0] > 0.0),
        "radau5's boundary crosses into Re z ≤ 0"
    );
    let plot = [
        e.readout("stiff-stability", "plot_re_min", ""),
        e.readout("stiff-stability", "plot_re_max", ""),
    ];
    assert!(plot[1] - plot[0] < 30.0, "{plot:?}");
    // at λ = −10 ± 141i and h = 0.05 RK4 is past its limit (0.0204), the implicit methods
    // never are
    let rk4 = e.readout("stiff-stability", "stable_h", "rk4");
    assert!(rk4 > 0.019 && rk4 < 0.021, "{rk4}");
    assert!(rk4 < e.readout("stiff-stability", "h", ""));
    for key in ["implicit-euler", "implicit-midpoint", "radau5"] {
        assert_eq!(e.readout("stiff-stability", "stable_h", key), 10.0, "{key}");
    }
}
