//! `lectern typeset-bench` (hidden): what typesetting off the UI thread costs and saves, on a
//! deck's formulas. Prints the tables of `docs/benchmarks/typeset.md`.
//!
//! Frames are egui passes of the app's slide renderer on a headless context (layout, widgets
//! and typesetting: the UI thread's work; painting on the GPU is the same before and after and
//! is left out). "Before" is the old path: every formula typeset inside the frame that first
//! shows it. "After" is the window's path: typeset in worker processes, ahead of time.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crate::app::SlideState;
use crate::app::slide_view::slide_ui;
use crate::deck::{Deck, load_deck};
use crate::math::worker::{Bounds, WorkerProcess};
use crate::math::{MathCache, MathSyntax, pool, set_worker_program};

/// Measure typesetting costs on a deck.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The deck [default: slides/lecture.ron]
    pub deck: Option<PathBuf>,
    /// Repetitions per measurement (medians are reported).
    #[arg(long, default_value_t = 5)]
    pub reps: usize,
    /// Window size in points, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720", value_parser = super::export::parse_size)]
    pub size: [u32; 2],
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// A headless egui context drawing slides of `deck` at the window size.
struct Frames {
    ctx: egui::Context,
    states: Vec<SlideState>,
    window: egui::Vec2,
}

impl Frames {
    fn new(deck: &Deck, live: bool, window: egui::Vec2) -> Self {
        let ctx = egui::Context::default();
        if live {
            crate::math::never_wait(&ctx);
        }
        let f = Self {
            ctx,
            states: deck.slides.iter().map(|_| SlideState::default()).collect(),
            window,
        };
        // fonts arrive with the second pass
        let mut plain = deck.clone();
        plain.slides.truncate(1);
        plain.slides[0].body.clear();
        let mut s = SlideState::default();
        for _ in 0..3 {
            let mut out = f.ctx.run_ui(f.input(), |ui| {
                slide_ui(ui, &plain, 0, &mut s);
            });
            out.textures_delta.clear(); // no GPU here
        }
        f
    }

    fn input(&self) -> egui::RawInput {
        egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, self.window)),
            ..Default::default()
        }
    }

    /// One frame of slide `i`: its time and how many formulas it drew as pictures.
    fn frame(&mut self, deck: &Deck, i: usize) -> (Duration, usize) {
        let t = Instant::now();
        let input = self.input();
        let mut out = self.ctx.run_ui(input, |ui| {
            slide_ui(ui, deck, i, &mut self.states[i]);
        });
        let took = t.elapsed();
        out.textures_delta.clear(); // no GPU here
        (took, self.formulas_drawn(&out.shapes))
    }

    fn formulas_drawn(&self, shapes: &[egui::epaint::ClippedShape]) -> usize {
        use egui::epaint::Shape;
        fn walk(s: &Shape, out: &mut Vec<egui::TextureId>) {
            match s {
                Shape::Vec(v) => v.iter().for_each(|s| walk(s, out)),
                Shape::Mesh(m) => out.push(m.texture_id),
                _ => {}
            }
        }
        let mut ids = Vec::new();
        shapes.iter().for_each(|s| walk(&s.shape, &mut ids));
        let tex = self.ctx.tex_manager();
        let tex = tex.read();
        ids.iter()
            .filter(|id| tex.meta(**id).is_some_and(|m| m.name.starts_with("math:")))
            .count()
    }
}

fn formula_count(deck: &Deck, i: usize) -> usize {
    crate::math::deck::formulas(deck, Some(i..i + 1)).len()
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let path = args.deck.unwrap_or_else(super::present::default_deck);
    let deck = load_deck(&path).map_err(|d| anyhow::anyhow!("{d}"))?;
    let reps = args.reps.max(1);
    let window = egui::vec2(args.size[0] as f32, args.size[1] as f32);
    let exe = std::env::current_exe()?;
    let em_px = crate::app::theme::size::MATH * window.x / crate::app::theme::CANVAS_WIDTH;
    println!(
        "deck {}: {} slides, {} formulas; window {}x{} (formulas at {em_px:.1} px/em)\n",
        path.display(),
        deck.slides.len(),
        crate::math::deck::formulas(&deck, None).len(),
        window.x,
        window.y
    );

    // 1. The worker mechanism, per formula.
    let bounds = Bounds::default();
    let mut starts = Vec::new();
    for _ in 0..reps {
        let t = Instant::now();
        let w = WorkerProcess::start(&exe, &bounds).map_err(|e| anyhow::anyhow!(e))?;
        starts.push(ms(t.elapsed()));
        drop(w);
    }
    let mut worker = WorkerProcess::start(&exe, &bounds).map_err(|e| anyhow::anyhow!(e))?;
    // Per formula: the first time (cold: Typst memoises, and the app typesets each (formula,
    // size, colour) once, so this is what a slide pays) and the median of the repeats (warm:
    // what is left is the pipe and the process switch).
    let mut cold = [Vec::new(), Vec::new(), Vec::new()];
    let mut warm = [Vec::new(), Vec::new(), Vec::new()];
    for f in crate::math::deck::formulas(&deck, None) {
        let req = f.request(em_px, [255, 255, 255, 255]);
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for _ in 0..=reps {
            let t = Instant::now();
            let r = req.render();
            a.push(ms(t.elapsed()));
            if a.len() == 1 && std::env::var_os("LECTERN_BENCH_HEIGHTS").is_some() {
                let h = r.map_or(0.0, |r| r.height as f32 / em_px);
                println!("height {h:.2} em: {}", f.src);
            }
            let t = Instant::now();
            let _ = worker.typeset(&req, &bounds);
            b.push(ms(t.elapsed()));
        }
        for (k, v) in [a[0], b[0], b[0] - a[0]].into_iter().enumerate() {
            cold[k].push(v);
        }
        let (wa, wb) = (median(a[1..].to_vec()), median(b[1..].to_vec()));
        for (k, v) in [wa, wb, wb - wa].into_iter().enumerate() {
            warm[k].push(v);
        }
    }
    drop(worker);
    let [cold_a, cold_b, cold_d] = cold.map(median);
    let [warm_a, warm_b, warm_d] = warm.map(median);
    println!("## Cost of the worker mechanism (medians over the deck's formulas, ms)\n");
    println!("| | first time (what a slide pays) | again (Typst's memo warm) |");
    println!("|---|---:|---:|");
    println!("| typeset + rasterise in this process | {cold_a:.2} | {warm_a:.2} |");
    println!("| the same through a warm worker process | {cold_b:.2} | {warm_b:.2} |");
    println!(
        "| difference per formula (median of per-formula differences) | {cold_d:.2} | {warm_d:.2} |"
    );
    println!(
        "| starting a worker (spawn, load fonts, first formula), median of {reps} | {:.1} | |",
        median(starts)
    );
    println!();

    // 2. First visit of each slide: key press -> slide fully drawn.
    set_worker_program(None);
    let mut before = Frames::new(&deck, false, window);
    set_worker_program(Some(exe.clone()));
    let mut after = Frames::new(&deck, true, window);
    println!("## First visit of each slide, key press → fully drawn (ms)\n");
    println!(
        "| slide | formulas | before: the frame (typesets inside) | after, paging forward: the frame | after: formulas on screen | after, jumping there cold: the frame | … fully drawn |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let mut cold = Frames::new(&deck, true, window);
    let (mut tb, mut ta, mut tc) = (Vec::new(), Vec::new(), Vec::new());
    let mut placeholders_paging = 0;
    for i in 0..deck.slides.len() {
        let n = formula_count(&deck, i);
        // before: the old path, every formula in the first frame
        let (b, _) = before.frame(&deck, i);
        // after, paging: the lecturer spent time on slide i-1 (its frames typeset ahead)
        if i > 0 {
            after.frame(&deck, i - 1);
            settle(&mut after, &deck, i - 1);
        }
        let key = Instant::now();
        let (a, drawn) = after.frame(&deck, i);
        if drawn < n && i > 0 {
            placeholders_paging += 1;
        }
        let full = if drawn >= n {
            a
        } else {
            until_drawn(&mut after, &deck, i, n, key, drawn)
        };
        // after, cold jump (nothing typeset ahead: the same window, its formulas forgotten)
        cold.frame(&deck, (i + deck.slides.len() / 2) % deck.slides.len());
        settle(
            &mut cold,
            &deck,
            (i + deck.slides.len() / 2) % deck.slides.len(),
        );
        if let Ok(mut c) = MathCache::shared(&cold.ctx).lock() {
            c.clear();
        }
        let key = Instant::now();
        let (c, cold_drawn) = cold.frame(&deck, i);
        let cold_full = if cold_drawn >= n {
            c
        } else {
            until_drawn(&mut cold, &deck, i, n, key, cold_drawn)
        };
        println!(
            "| {} {} | {n} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} |",
            i + 1,
            deck.slides[i].key(),
            ms(b),
            ms(a),
            ms(full),
            ms(c),
            ms(cold_full)
        );
        if n > 0 {
            tb.push(ms(b));
            ta.push(ms(a));
            tc.push(ms(c));
        }
    }
    println!(
        "\nslides with formulas, medians: before {:.1} ms, after (paging) {:.1} ms, after (cold jump) {:.1} ms; slides that showed a placeholder when paged to (from the previous one): {placeholders_paging}\n",
        median(tb),
        median(ta),
        median(tc)
    );

    // 3. Frames while the pool typesets in the background.
    let busy_slide = (0..deck.slides.len())
        .find(|&i| formula_count(&deck, i) == 0)
        .unwrap_or(0);
    let mut frames = Frames::new(&deck, true, window);
    let mut idle = Vec::new();
    for _ in 0..60 {
        idle.push(ms(frames.frame(&deck, busy_slide).0));
    }
    let all = crate::math::deck::formulas(&deck, None);
    // as the window asks for formulas ahead, at a size not typeset yet
    let jobs: Vec<_> = all
        .iter()
        .map(|f| {
            pool().submit(
                f.request(em_px * 2.0, [200, 220, 255, 255]),
                false,
                true,
                None,
            )
        })
        .collect();
    let t = Instant::now();
    let mut busy = Vec::new();
    while jobs
        .iter()
        .any(|j| j.poll() == crate::math::pool::Poll::Pending)
    {
        busy.push(ms(frames.frame(&deck, busy_slide).0));
        anyhow::ensure!(
            t.elapsed() < Duration::from_secs(120),
            "background work stalled"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
    let background = t.elapsed();
    let max = busy.iter().copied().fold(0.0, f64::max);
    println!("## Frame time while formulas are typeset in the background\n");
    println!("| | frames | median ms | max ms |\n|---|---:|---:|---:|");
    println!(
        "| idle | {} | {:.2} | {:.2} |",
        idle.len(),
        median(idle.clone()),
        idle.iter().copied().fold(0.0, f64::max)
    );
    println!(
        "| while the pool typesets all {} formulas at a new size ({:.0} ms in all) | {} | {:.2} | {:.2} |",
        all.len(),
        ms(background),
        busy.len(),
        median(busy),
        max
    );
    let syntax_note = all.iter().filter(|f| f.syntax == MathSyntax::Latex).count();
    println!("\n({syntax_note} of the formulas are LaTeX, converted by mitex in the worker.)");
    Ok(())
}

/// Runs frames of slide `i` until its formulas are drawn and the pool has finished what it
/// typesets ahead (the lecturer looking at the slide for a while).
fn settle(frames: &mut Frames, deck: &Deck, i: usize) {
    let n = formula_count(deck, i);
    let t = Instant::now();
    while frames.frame(deck, i).1 < n && t.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(2));
    }
    while pool().busy() > 0 && t.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// Frames of slide `i` until its `n` formulas are drawn (`drawn` in the first one); the time
/// since `key`.
fn until_drawn(
    frames: &mut Frames,
    deck: &Deck,
    i: usize,
    n: usize,
    key: Instant,
    mut drawn: usize,
) -> Duration {
    while drawn < n && key.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(1));
        drawn = frames.frame(deck, i).1;
    }
    key.elapsed()
}
