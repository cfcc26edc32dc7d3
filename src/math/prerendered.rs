//! The web player's "typesetting pool": no Typst, no worker, no thread. `lectern export --web`
//! typesets every formula of the deck (at twice the size the slide lays it out at, in the
//! colour it is drawn in) into the bundle; the player [`install`]s them at start, and a request
//! is answered at once from that table, resampled to the size asked for (downsampling the
//! larger master keeps it sharp on a high-DPI screen). The same API as the native
//! [`pool`](self) the [`super::MathCache`] talks to, so the cache and every slide that draws
//! maths are shared with the desktop app.

use std::collections::HashMap;
use std::sync::{Arc, OnceLock};

use super::formula::{MathError, MathStyle, MathSyntax, RenderedFormula, Request};
pub use super::formula::{Notify, Poll};

/// One formula as the export typeset it.
#[derive(Debug, Clone, PartialEq)]
pub struct Prerendered {
    pub src: String,
    pub syntax: MathSyntax,
    pub style: MathStyle,
    pub rgba: [u8; 4],
    /// Pixels per em it was typeset at.
    pub em_px: f32,
    pub result: Result<RenderedFormula, MathError>,
}

type Key = (String, MathSyntax, MathStyle, [u8; 4]);

static TABLE: OnceLock<HashMap<Key, Prerendered>> = OnceLock::new();

/// The formulas of the bundle, once, at start (later calls are ignored).
pub fn install(formulas: impl IntoIterator<Item = Prerendered>) {
    let table = formulas
        .into_iter()
        .map(|p| ((p.src.clone(), p.syntax, p.style, p.rgba), p))
        .collect();
    let _ = TABLE.set(table);
}

/// One formula asked for: answered when asked.
pub struct Job {
    pub req: Request,
    result: Result<RenderedFormula, MathError>,
}

impl Job {
    pub fn poll(&self) -> Poll {
        Poll::Done(self.result.clone())
    }

    pub fn want(&self, _urgent: bool, _notify: Option<Notify>) {}

    pub fn wait(&self) -> Result<RenderedFormula, MathError> {
        self.result.clone()
    }
}

pub struct Pool;

pub fn pool() -> &'static Pool {
    &Pool
}

impl Pool {
    pub fn submit(
        &self,
        req: Request,
        _urgent: bool,
        _keep: bool,
        _notify: Option<Notify>,
    ) -> Arc<Job> {
        let result = answer(&req);
        Arc::new(Job { req, result })
    }
}

fn answer(req: &Request) -> Result<RenderedFormula, MathError> {
    let key = (req.src.clone(), req.syntax, req.style, req.rgba);
    let Some(p) = TABLE.get().and_then(|t| t.get(&key)) else {
        return Err(MathError {
            message: "this formula was not typeset into the web page (export it again)".into(),
            col: None,
        });
    };
    let master = p.result.clone()?;
    Ok(master.resampled(req.size_px / p.em_px.max(1e-3)))
}
