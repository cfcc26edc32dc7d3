//! Formulas that compute too much are stopped within their bounds, in a worker process (the
//! `lectern` binary re-executed), and reported as errors; Typst's own guards still answer for
//! infinite loops and recursion; this process's memory stays bounded throughout.

use std::time::{Duration, Instant};

use lectern::math::wire::Request;
use lectern::math::{Bounds, MathSyntax, pool, set_worker_program};

const BOUNDS: Bounds = Bounds {
    time: Duration::from_secs(2),
    memory_mb: 512,
};

fn setup() {
    set_worker_program(Some(env!("CARGO_BIN_EXE_lectern").into()));
    pool().set_bounds(BOUNDS);
}

fn typeset(src: &str) -> (Result<(u32, u32), String>, Duration) {
    setup();
    let t = Instant::now();
    let r = pool().typeset(Request {
        src: src.to_owned(),
        syntax: MathSyntax::Typst,
        style: Default::default(),
        size_px: 40.0,
        rgba: [0, 0, 0, 255],
    });
    (
        r.map(|f| (f.width, f.height)).map_err(|e| e.to_string()),
        t.elapsed(),
    )
}

/// Peak resident memory of this (test) process, in MiB.
fn peak_rss_mb() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
        .map_or(0, |kb| kb / 1024)
}

/// Stopped at the budget (plus starting a fresh worker and some slack for a loaded machine),
/// never at the formula's own pace.
fn within_budget(took: Duration) -> bool {
    took < BOUNDS.time + Duration::from_secs(8)
}

#[test]
fn a_formula_that_computes_too_much_is_stopped_and_reported() {
    for src in [
        "#range(3000000).map(i => i).len()",
        "#range(100000000).map(i => i).len()",
    ] {
        let (r, took) = typeset(src);
        let err = r.expect_err(src);
        eprintln!("{src}: {err} in {took:?}");
        assert!(
            err.contains("stopped after 2 s") || err.contains("used more than 512 MB"),
            "{src}: {err}"
        );
        assert!(within_budget(took), "{src}: took {took:?}");
    }
    // the worker that was killed is replaced: an ordinary formula still typesets
    let (r, _) = typeset("x^2 + y^2");
    assert!(r.is_ok(), "{r:?}");
    // the work happened in another process: this one never held those gigabytes
    assert!(peak_rss_mb() < 1500, "peak RSS {} MB", peak_rss_mb());
}

#[test]
fn a_huge_allocation_hits_the_memory_bound_not_the_machine() {
    // a string of 1 G characters: far beyond 512 MB, asked for at once
    let (r, took) = typeset("#(\"x\" * 1000000000).len()");
    let err = r.unwrap_err();
    eprintln!("{err} in {took:?}");
    assert!(err.contains("used more than 512 MB"), "{err}");
    assert!(within_budget(took), "took {took:?}");
    assert!(peak_rss_mb() < 1500, "peak RSS {} MB", peak_rss_mb());
}

#[test]
fn a_megabyte_formula_and_deep_nesting_are_reported_within_the_budget() {
    let long = "x + ".repeat(250_000) + "x";
    assert!(long.len() > 1_000_000);
    let deep = "(".repeat(10_000) + "x" + &")".repeat(10_000);
    let deep_calls = "sqrt(".repeat(10_000) + "x" + &")".repeat(10_000);
    for (name, src) in [
        ("1 MB", &long),
        ("10 000 parentheses", &deep),
        ("10 000 roots", &deep_calls),
    ] {
        let (r, took) = typeset(src);
        // either typeset (Typst coped) or an error; never a hang or a crash of this process
        if let Err(e) = &r {
            assert!(!e.is_empty(), "{name}");
        }
        assert!(within_budget(took), "{name}: took {took:?}");
        eprintln!(
            "{name}: {:?} in {took:?}",
            r.as_ref().map_err(|e| &e[..e.len().min(100)])
        );
    }
}

#[test]
fn infinite_loops_and_recursion_still_get_typsts_own_errors() {
    let (r, took) = typeset("#let n = 0; #while n < 1 { }");
    let err = r.unwrap_err();
    assert!(err.contains("infinite"), "{err}");
    assert!(within_budget(took));
    let (r, _) = typeset("#let f(x) = f(x); #f(1)");
    let err = r.unwrap_err();
    assert!(err.contains("depth"), "{err}");
}

#[test]
fn ordinary_formulas_match_in_process_typesetting() {
    setup();
    let src = "x(t + h) = x(t) + h dot(x)(t) + h^2/2 dot.double(x)(t)";
    let direct =
        lectern::math::render_formula(src, MathSyntax::Typst, 40.0, [0, 0, 0, 255]).unwrap();
    let pooled = pool()
        .typeset(Request {
            src: src.into(),
            syntax: MathSyntax::Typst,
            style: Default::default(),
            size_px: 40.0,
            rgba: [0, 0, 0, 255],
        })
        .unwrap();
    assert_eq!(
        direct, pooled,
        "the worker draws exactly what this process would"
    );
    assert!(
        pool().stats().workers_started >= 1,
        "it ran in a worker process"
    );
}

/// `lectern check` on a deck with a formula that computes too much and a picture from outside
/// the project: both reported at their file:line:col within seconds, exit status 1.
#[test]
fn check_reports_a_heavy_formula_and_an_outside_image_at_their_positions() {
    let dir = tempfile::tempdir().unwrap();
    let slides = dir.path().join("slides");
    std::fs::create_dir_all(&slides).unwrap();
    let deck = r##"(
    title: "t",
    slides: [
        (title: "a", body: [
            Math(src: r#"#range(100000000).map(i => i).len()"#),
            Image(path: "../../../../etc/passwd"),
            Math(src: "x + undefinedthing(2)"),
        ]),
    ],
)"##;
    let path = slides.join("deck.ron");
    std::fs::write(&path, deck).unwrap();
    let t = Instant::now();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lectern"))
        .arg("check")
        .arg(&path)
        .output()
        .unwrap();
    let took = t.elapsed();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(within_budget(took), "check took {took:?}");
    let shown = path.display();
    for (needle, what) in [
        // Which bound stops the heavy formula first depends on the machine's speed: a fast
        // one fills 512 MB before 2 s pass. Either way it is stopped and reported in place.
        (
            "#range",
            &["formula stopped after 2 s", "more than 512 MB"][..],
        ),
        ("../../", &["leads outside the project folder"][..]),
        ("undefinedthing", &["unknown variable"][..]),
    ] {
        let byte = deck.find(needle).unwrap();
        let line = deck[..byte].matches('\n').count() + 1;
        let col = byte - deck[..byte].rfind('\n').unwrap();
        let want = format!("{shown}:{line}:{col}: ");
        assert!(
            stdout
                .lines()
                .any(|l| l.starts_with(&want) && what.iter().any(|w| l.contains(w))),
            "no {want}…{what:?} in\n{stdout}"
        );
    }
}
