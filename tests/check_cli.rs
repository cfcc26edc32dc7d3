//! `lectern check` as a lecturer runs it the evening before: each broken file below makes it
//! exit non-zero and print `file:line:col: message` at the value at fault, a position a text
//! editor can jump to; the bundled project says "all good".

use std::path::{Path, PathBuf};
use std::process::Command;

fn check(args: &[&Path]) -> (bool, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_lectern"))
        .arg("check")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    (o.status.success(), out)
}

/// A scratch project folder with `slides/`, `scenes/`, `slides/tableaux/`, `slides/problems/`.
fn project() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for sub in ["slides/tableaux", "slides/problems", "scenes"] {
        std::fs::create_dir_all(dir.path().join(sub)).unwrap();
    }
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let file = dir.join(name);
    std::fs::write(&file, text).unwrap();
    file
}

fn deck(body: &str) -> String {
    format!(
        "(\n  title: \"t\",\n  slides: [\n    (title: \"s\", body: [\n{body}\n    ]),\n  ],\n)\n"
    )
}

/// Exit status non-zero, and exactly one problem, at `file:line:col: ` with `needle` in it.
#[track_caller]
fn assert_one_problem(file: &Path, line: usize, col: usize, needle: &str) {
    let (ok, out) = check(&[file]);
    assert!(!ok, "{out}");
    let prefix = format!("{}:{line}:{col}: ", file.display());
    let problems: Vec<&str> = out
        .lines()
        .filter(|l| l.starts_with(&format!("{}:", file.display())) && l.contains(": "))
        .filter(|l| !l.contains(" planned"))
        .collect();
    assert_eq!(problems.len(), 1, "{out}");
    assert!(problems[0].starts_with(&prefix), "want {prefix}…\n{out}");
    assert!(problems[0].contains(needle), "want {needle:?}\n{out}");
}

#[test]
fn a_typst_error_at_its_character() {
    let p = project();
    let f = write(
        &p.path().join("slides"),
        "formula.ron",
        &deck(r#"      Math(src: "dot(x) = #nosuchfn(x)"),"#),
    );
    assert_one_problem(&f, 5, 28, "unknown variable: nosuchfn");
}

#[test]
fn a_missing_image_at_its_path() {
    let p = project();
    let f = write(
        &p.path().join("slides"),
        "image.ron",
        &deck(r#"      Image(path: "figures/nope.png"),"#),
    );
    assert_one_problem(&f, 5, 20, "no such file");
}

#[test]
fn a_missing_tableau_file_at_its_path() {
    let p = project();
    let f = write(
        &p.path().join("slides"),
        "tableau.ron",
        &deck(r#"      Widget(Stability((methods: [Tableau("tableaux/nope.ron")]))),"#),
    );
    assert_one_problem(&f, 5, 44, "`tableaux/nope.ron`: no such file");
}

#[test]
fn an_implicit_tableau_at_the_entry() {
    let p = project();
    let f = write(
        &p.path().join("slides/tableaux"),
        "implicit.ron",
        "(\n  name: \"x\",\n  a: [[0.0, 0.0, 0.0],\n      [0.5, 0.0, 0.0],\n      [0.0, 1.0, 0.25]],\n  b: [0.2, 0.3, 0.5],\n  c: [0.0, 0.5, 1.0],\n)\n",
    );
    assert_one_problem(&f, 5, 18, "a[3][3] = 0.25 is on or above the diagonal");
}

#[test]
fn a_bad_problem_name_at_the_name() {
    let p = project();
    let f = write(
        &p.path().join("slides/problems"),
        "bad.ron",
        "(\n    name: \"p\",\n    vars: [\"x\", \"my v\"],\n    rhs: [\"1\", \"x\"],\n    initial: [0.0, 0.0],\n)\n",
    );
    assert_one_problem(&f, 3, 18, "`my v` is not a valid name");
}

#[test]
fn non_finite_school_weights_at_the_weight() {
    let p = project();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("scenes/water.ron")).unwrap();
    let text = text.replacen("cohesion_weight: 0.8", "cohesion_weight: NaN", 1);
    let line = text.lines().position(|l| l.contains("NaN")).unwrap() + 1;
    let col = text.lines().nth(line - 1).unwrap().find("NaN").unwrap() + 1;
    let f = write(&p.path().join("scenes"), "bad.ron", &text);
    assert_one_problem(&f, line, col, "school weights must be finite");
}

#[test]
fn the_bundled_project_is_all_good() {
    let (ok, out) = check(&[]);
    assert!(ok, "{out}");
    assert!(out.lines().last().unwrap().ends_with("all good"), "{out}");
}

#[test]
fn an_energy_that_does_not_compile_at_its_value() {
    let p = project();
    write(
        &p.path().join("slides/problems"),
        "osc.ron",
        "(\n    name: \"osc\",\n    vars: [\"x\", \"v\"],\n    rhs: [\"v\", \"-x\"],\n    initial: [1.0, 0.0],\n)\n",
    );
    let f = write(
        &p.path().join("slides"),
        "energy.ron",
        &deck(r#"      Widget(Energy((ode: File("problems/osc.ron"), energy: "0.5*v*v + q"))),"#),
    );
    // at the value; the message gives the column inside the expression
    assert_one_problem(&f, 5, 61, "energy: unknown name `q`");
}
