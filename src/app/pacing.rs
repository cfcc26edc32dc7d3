//! Pacing: time per slide against the deck's budgets, with pause and reset. Pure arithmetic on
//! seconds (no clock inside, no UI types): the app feeds it egui's time, tests feed numbers.

use serde::Serialize;

use crate::deck::Deck;

#[derive(Debug, Clone)]
pub struct Pacing {
    /// Planned seconds per slide (0 where the deck gives none).
    budgets: Vec<f64>,
    /// Seconds actually spent on each slide so far.
    spent: Vec<f64>,
    current: usize,
    running: bool,
    /// The time of the last `tick`, while running.
    last: Option<f64>,
}

/// Where the talk stands, for the presenter's timer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaceReport {
    pub slide_elapsed: f64,
    pub slide_budget: f64,
    /// Budget minus elapsed on this slide (negative: over).
    pub slide_left: f64,
    pub total_elapsed: f64,
    pub planned_total: f64,
    /// Planned total minus elapsed (negative: over time).
    pub total_left: f64,
    /// Seconds ahead of plan (negative: behind). The plan at this point is every budget of the
    /// slides before this one plus as much of this slide's budget as has been used.
    pub ahead: f64,
    pub running: bool,
}

impl Pacing {
    pub fn new(deck: &Deck) -> Self {
        let budgets = budgets(deck);
        Self {
            spent: vec![0.0; budgets.len()],
            budgets,
            current: 0,
            running: true,
            last: None,
        }
    }

    /// Accounts the time since the last tick to the current slide (if running).
    pub fn tick(&mut self, now: f64) {
        if self.running
            && let Some(last) = self.last
            && let Some(s) = self.spent.get_mut(self.current)
        {
            *s += (now - last).max(0.0);
        }
        self.last = self.running.then_some(now);
    }

    /// The presenter moved to slide `index` at time `now`.
    pub fn goto(&mut self, index: usize, now: f64) {
        self.tick(now);
        self.current = index.min(self.budgets.len().saturating_sub(1));
    }

    pub fn is_running(&self) -> bool {
        self.running
    }

    /// Pauses or resumes at `now`; time while paused counts nowhere.
    pub fn toggle_pause(&mut self, now: f64) {
        self.tick(now);
        self.running = !self.running;
        self.last = self.running.then_some(now);
    }

    /// Back to zero everywhere (keeps running or paused as it was).
    pub fn reset(&mut self, now: f64) {
        self.spent.iter_mut().for_each(|s| *s = 0.0);
        self.last = self.running.then_some(now);
    }

    /// After a reload: new budgets; time spent is kept for slides that still exist by position.
    pub fn set_deck(&mut self, deck: &Deck, index: usize) {
        self.budgets = budgets(deck);
        self.spent.resize(self.budgets.len(), 0.0);
        self.current = index.min(self.budgets.len().saturating_sub(1));
    }

    pub fn spent(&self) -> &[f64] {
        &self.spent
    }

    pub fn report(&self) -> PaceReport {
        let i = self.current;
        let slide_elapsed = self.spent.get(i).copied().unwrap_or(0.0);
        let slide_budget = self.budgets.get(i).copied().unwrap_or(0.0);
        let total_elapsed: f64 = self.spent.iter().sum();
        let planned_total: f64 = self.budgets.iter().sum();
        let planned_now: f64 = self.budgets[..i.min(self.budgets.len())]
            .iter()
            .sum::<f64>()
            + slide_elapsed.min(slide_budget);
        PaceReport {
            slide_elapsed,
            slide_budget,
            slide_left: slide_budget - slide_elapsed,
            total_elapsed,
            planned_total,
            total_left: planned_total - total_elapsed,
            ahead: planned_now - total_elapsed,
            running: self.running,
        }
    }

    /// The rehearsal record: planned and actual seconds per slide, as RON, for a file next to
    /// the deck (`lecture.timings.ron`).
    pub fn rehearsal_ron(&self, deck: &Deck) -> String {
        #[derive(Serialize)]
        struct Row<'a> {
            slide: &'a str,
            planned_secs: f64,
            actual_secs: f64,
        }
        let rows: Vec<Row> = deck
            .slides
            .iter()
            .zip(&self.spent)
            .zip(&self.budgets)
            .map(|((s, &actual), &planned)| Row {
                slide: s.key(),
                planned_secs: planned,
                actual_secs: (actual * 10.0).round() / 10.0,
            })
            .collect();
        let pretty = ron::ser::PrettyConfig::new().depth_limit(2);
        let body = ron::ser::to_string_pretty(&rows, pretty).unwrap_or_default();
        format!(
            "// Rehearsal timings written by lectern: planned vs actual seconds per slide.\n{body}\n"
        )
    }
}

fn budgets(deck: &Deck) -> Vec<f64> {
    deck.slides
        .iter()
        .map(|s| s.planned_secs() as f64)
        .collect()
}

/// `m:ss`, with a sign for negative values (`-0:12`).
pub fn clock(secs: f64) -> String {
    let sign = if secs < 0.0 { "-" } else { "" };
    let s = secs.abs().round() as u64;
    format!("{sign}{}:{:02}", s / 60, s % 60)
}
