//! Fuzzing `lectern check`'s entry points: the bundled decks, scenes, problems, tableaux and
//! shaders, mutated at random (cut, duplicated or moved spans, inserted tokens, extreme
//! numbers), must give problems, never a panic.
//!
//! Seeded, so a failure is reproducible; the failing input is written to
//! `target/check-fuzz-failures/`. CI runs 10 000 cases (a few seconds); for a longer run:
//!
//!     LECTERN_FUZZ_CASES=1000000 LECTERN_FUZZ_SEED=7 cargo test --release --test suite check_fuzz::

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;

use lectern::cli::check::{Kind, Report, check_text};
use lectern::cli::check_deck::DeckChecker;

/// xorshift64*: small, seedable, good enough to pick mutations.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Tokens that stress parsers and validators (RON, WGSL, Typst, expressions, paths).
const TOKENS: &[&str] = &[
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ",",
    ":",
    ";",
    "\"",
    "'",
    "r#\"",
    "\"#",
    "#",
    "$",
    "\\",
    "\n",
    "NaN",
    "inf",
    "-inf",
    "1e309",
    "-0.0",
    "0",
    "18446744073709551616",
    "-1",
    "None",
    "Some(",
    "true",
    "Widget(",
    "Math(src: \"",
    "Columns([[",
    "Image(path: \"../../x.png\")",
    "Stability((files: [\"../x.ron\"]))",
    "x/0",
    "sqrt(-1)",
    "^^",
    "é",
    "ω",
    "\u{0}",
    "//",
    "/*",
    "fn",
    "@binding(7)",
    "@group(9)",
    "var<uniform>",
    "struct",
    "->",
    "//!include ",
    "frac(",
    "#let x = ",
    "$x$",
    "a[0][0]",
    "vars",
    "rhs",
    "t0",
];

/// The nearest char boundary at or before `i`.
fn boundary(s: &str, mut i: usize) -> usize {
    i = i.min(s.len());
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn mutate(text: &str, rng: &mut Rng) -> String {
    let mut s = text.to_owned();
    for _ in 0..1 + rng.below(3) {
        let n = s.len();
        let at = boundary(&s, rng.below(n + 1));
        let end = boundary(&s, at + 1 + rng.below(24));
        match rng.below(6) {
            0 => s.replace_range(at..end, ""),
            1 => {
                let piece = s[at..end].to_owned();
                let to = boundary(&s, rng.below(n + 1));
                s.insert_str(to, &piece);
            }
            2 | 3 => s.insert_str(at, TOKENS[rng.below(TOKENS.len())]),
            4 => {
                // an extreme value in place of the next number
                if let Some(k) = s[at..].find(|c: char| c.is_ascii_digit()).map(|k| k + at) {
                    let stop = s[k..]
                        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
                        .map_or(n, |e| e + k);
                    let v = ["1e300", "-1e300", "0", "NaN", "99999999999", "-7"][rng.below(6)];
                    s.replace_range(k..stop, v);
                }
            }
            _ => {
                // move a span elsewhere
                let piece = s[at..end].to_owned();
                s.replace_range(at..end, "");
                let to = boundary(&s, rng.below(s.len() + 1));
                s.insert_str(to, &piece);
            }
        }
    }
    s
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn files_in(dir: &str, ext: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    v.sort();
    v
}

fn env_or(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
fn mutated_files_never_panic_check() {
    let cases = env_or("LECTERN_FUZZ_CASES", 10_000) as usize;
    let seed = env_or("LECTERN_FUZZ_SEED", 0x5eed_1ec7e2);
    let mut rng = Rng(seed | 1);
    let mut sources: Vec<(Kind, PathBuf)> = vec![
        (Kind::Deck, root().join("slides/lecture.ron")),
        (Kind::Scene, root().join("scenes/water.ron")),
    ];
    sources.extend(
        files_in("slides/problems", "ron")
            .into_iter()
            .map(|p| (Kind::Problem, p)),
    );
    sources.extend(
        files_in("slides/tableaux", "ron")
            .into_iter()
            .map(|p| (Kind::Tableau, p)),
    );
    let shaders = files_in("shaders", "wgsl");
    // Shaders are checked from files (includes resolve beside them): mutate a copy.
    let shader_dir = tempfile::tempdir().unwrap();
    for s in &shaders {
        std::fs::copy(s, shader_dir.path().join(s.file_name().unwrap())).unwrap();
    }
    let texts: Vec<String> = sources
        .iter()
        .map(|(_, p)| std::fs::read_to_string(p).unwrap())
        .collect();
    let shader_texts: Vec<String> = shaders
        .iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();

    let mut decks = DeckChecker::new();
    let failures_dir = root().join("target/check-fuzz-failures");
    let mut failures = Vec::new();
    let mut per_kind = [0usize; 5];
    let mut secs_per_kind = [0f64; 5];
    let quiet = QuietPanics::on_this_thread();
    for case in 0..cases {
        // Costs per case in a debug build: a shader ~5 ms (naga is unoptimised there), a deck
        // ~1 ms plus ~10 ms per new formula typeset, the others well under 1 ms. So: shaders
        // one case in twenty, and formulas typeset in one deck case in twenty (other deck cases
        // reuse the verdicts on formulas seen before and skip new ones).
        let pick = rng.below(20);
        decks.skip_typesetting = rng.below(20) != 0;
        let (kind, file, mutated) = if pick == 0 {
            let k = rng.below(shaders.len());
            let file = shader_dir.path().join(shaders[k].file_name().unwrap());
            let mutated = mutate(&shader_texts[k], &mut rng);
            std::fs::write(&file, &mutated).unwrap();
            (Kind::Shader, file, mutated)
        } else {
            let kind = match pick {
                1..=6 => Kind::Deck,
                7..=11 => Kind::Scene,
                12..=15 => Kind::Problem,
                _ => Kind::Tableau,
            };
            let of_kind: Vec<usize> = (0..sources.len())
                .filter(|&i| sources[i].0 == kind)
                .collect();
            let i = of_kind[rng.below(of_kind.len())];
            (kind, sources[i].1.clone(), mutate(&texts[i], &mut rng))
        };
        per_kind[kind as usize] += 1;
        let started = std::time::Instant::now();
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            check_text(kind, &mutated, &file, &mut decks, &mut Report::default())
        }));
        secs_per_kind[kind as usize] += started.elapsed().as_secs_f64();
        if outcome.is_err() {
            std::fs::create_dir_all(&failures_dir).unwrap();
            let name = format!(
                "{kind:?}-case{case}-{}",
                file.file_name().unwrap().to_string_lossy()
            );
            std::fs::write(failures_dir.join(&name), &mutated).unwrap();
            failures.push(name);
            // a panic may leave the checker's cache half-updated: start a fresh one
            decks = DeckChecker::new();
        }
        if kind == Kind::Shader {
            let original = shaders
                .iter()
                .position(|s| s.file_name() == file.file_name());
            std::fs::copy(&shaders[original.unwrap()], &file).unwrap();
        }
    }
    drop(quiet); // the verdict below must be heard
    println!(
        "{cases} cases (seed {seed}): deck, scene, shader, problem, tableau = {per_kind:?} \
         in {secs_per_kind:.2?} s"
    );
    assert!(
        failures.is_empty(),
        "check panicked on {} inputs, saved in {}:\n{}",
        failures.len(),
        failures_dir.display(),
        failures.join("\n")
    );
}

thread_local! {
    static QUIET: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Silences panic messages on this thread while it lives: the fuzzer expects panics and
/// reports them itself. The other tests of this binary run beside it and keep their messages,
/// so the hook is process-wide but asks the thread.
struct QuietPanics;

impl QuietPanics {
    fn on_this_thread() -> Self {
        static HOOK: std::sync::Once = std::sync::Once::new();
        HOOK.call_once(|| {
            let previous = std::panic::take_hook();
            std::panic::set_hook(Box::new(move |info| {
                if !QUIET.with(|q| q.get()) {
                    previous(info);
                }
            }));
        });
        QUIET.with(|q| q.set(true));
        QuietPanics
    }
}

impl Drop for QuietPanics {
    fn drop(&mut self) {
        QUIET.with(|q| q.set(false));
    }
}
