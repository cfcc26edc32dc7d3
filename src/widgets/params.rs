//! A widget's tweakable values, named stably, so the presenter view can show their controls,
//! keep them across reloads and write them back to the deck file.

use serde::{Deserialize, Serialize};

/// A mutable view of one tweakable value inside a widget's state.
pub enum ParamValue<'a> {
    /// A real value in `min..=max`; `log` asks for a logarithmic slider.
    F64 {
        value: &'a mut f64,
        min: f64,
        max: f64,
        log: bool,
    },
    Bool(&'a mut bool),
    Usize {
        value: &'a mut usize,
        min: usize,
        max: usize,
    },
}

/// One named parameter. `id` is stable (it is the field name in the deck file, e.g. `"h"` or
/// `"start.1"`, or the name of an ODE parameter, `"k"`); `label` is for people.
pub struct Param<'a> {
    pub id: String,
    pub label: String,
    pub value: ParamValue<'a>,
    /// Where Ctrl+S writes the value.
    pub write: WriteTo,
    /// An equation's parameter its (typed) equation no longer names: the slider stays, for
    /// bookmarks, write-back and typing the name back in, but greyed and marked "unused".
    pub unused: bool,
}

/// Where a parameter lives in the files, for write-back.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum WriteTo {
    /// The widget's own field named by the id (`h`, `start.1`).
    Spec,
    /// Parameter `name` of the widget's ODE (`params: {"k": …}` inline, or in its problem file).
    OdeParam(String),
    /// Nowhere: a live-only switch (showing or hiding a method).
    Nowhere,
}

/// The parameter `id` names among `params`: written as is, else in its other Greek spelling
/// (a bookmark's or a tweak file's `zeta` finds the parameter `ζ`, and `ω` finds `omega`).
pub fn find_param<'a>(params: Vec<Param<'a>>, id: &str) -> Option<Param<'a>> {
    let alias = crate::ode::expr::greek::alias(id);
    let mut by_alias = None;
    for p in params {
        if p.id == id {
            return Some(p);
        }
        if by_alias.is_none() && alias.as_deref() == Some(p.id.as_str()) {
            by_alias = Some(p);
        }
    }
    by_alias
}

/// A parameter's value detached from the widget, for keeping across reloads.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum ParamSnapshot {
    F64(f64),
    Bool(bool),
    Usize(usize),
}

impl<'a> Param<'a> {
    pub fn f64(
        id: impl Into<String>,
        label: impl Into<String>,
        value: &'a mut f64,
        min: f64,
        max: f64,
    ) -> Self {
        Self {
            id: id.into(),
            label: label.into(),
            write: WriteTo::Spec,
            unused: false,
            value: ParamValue::F64 {
                value,
                min,
                max,
                log: false,
            },
        }
    }
    /// The step size `h` of the integrator widgets, on a log slider over `range`: one id
    /// ("h", what bookmarks, `[`/`]` and write-back name) and one label for all of them.
    pub fn step_h(value: &'a mut f64, range: (f64, f64)) -> Self {
        Self::f64_log("h", "step h", value, range.0, range.1)
    }

    pub fn f64_log(
        id: impl Into<String>,
        label: impl Into<String>,
        value: &'a mut f64,
        min: f64,
        max: f64,
    ) -> Self {
        Self {
            id: id.into(),
            label: label.into(),
            write: WriteTo::Spec,
            unused: false,
            value: ParamValue::F64 {
                value,
                min,
                max,
                log: true,
            },
        }
    }
    pub fn bool(id: impl Into<String>, label: impl Into<String>, value: &'a mut bool) -> Self {
        Self {
            id: id.into(),
            label: label.into(),
            write: WriteTo::Spec,
            unused: false,
            value: ParamValue::Bool(value),
        }
    }
    pub fn usize(
        id: impl Into<String>,
        label: impl Into<String>,
        value: &'a mut usize,
        min: usize,
        max: usize,
    ) -> Self {
        Self {
            id: id.into(),
            label: label.into(),
            write: WriteTo::Spec,
            unused: false,
            value: ParamValue::Usize { value, min, max },
        }
    }

    /// The same parameter, written back to `write` instead of the spec field named by its id.
    pub fn writing_to(mut self, write: WriteTo) -> Self {
        self.write = write;
        self
    }

    pub fn get(&self) -> ParamSnapshot {
        match &self.value {
            ParamValue::F64 { value, .. } => ParamSnapshot::F64(**value),
            ParamValue::Bool(v) => ParamSnapshot::Bool(**v),
            ParamValue::Usize { value, .. } => ParamSnapshot::Usize(**value),
        }
    }

    /// Sets the value, clamped to its range; a NaN or a value of the wrong kind is refused.
    pub fn set(&mut self, v: ParamSnapshot) -> Result<(), String> {
        match (&mut self.value, v) {
            (
                ParamValue::F64 {
                    value, min, max, ..
                },
                ParamSnapshot::F64(x),
            ) => {
                if !x.is_finite() {
                    return Err(format!("{}: {x} is not a finite number", self.id));
                }
                **value = x.clamp(*min, *max);
            }
            (ParamValue::Bool(value), ParamSnapshot::Bool(b)) => **value = b,
            (ParamValue::Usize { value, min, max }, ParamSnapshot::Usize(n)) => {
                **value = n.clamp(*min, *max)
            }
            (_, other) => return Err(format!("{}: {other:?} has the wrong kind", self.id)),
        }
        Ok(())
    }

    /// Marks it unused by the equation (see [`Param::unused`]).
    pub fn unused(mut self, unused: bool) -> Self {
        self.unused = unused;
        self
    }

    /// A control for this parameter (slider or checkbox), as the presenter view shows it; an
    /// unused one greyed, with "unused" after its label.
    pub fn ui(&mut self, ui: &mut egui::Ui) -> egui::Response {
        let label = if self.unused {
            format!("{} (unused by the equation)", self.label)
        } else {
            self.label.clone()
        };
        let value = &mut self.value;
        ui.add_enabled_ui(!self.unused, |ui| match value {
            ParamValue::F64 {
                value,
                min,
                max,
                log,
            } => ui.add(
                egui::Slider::new(&mut **value, *min..=*max)
                    .logarithmic(*log)
                    .text(label),
            ),
            ParamValue::Bool(v) => ui.checkbox(v, label),
            ParamValue::Usize { value, min, max } => {
                ui.add(egui::Slider::new(&mut **value, *min..=*max).text(label))
            }
        })
        .inner
    }
}

/// All of a widget's parameter values by id.
pub fn snapshot(w: &mut dyn super::SlideWidget) -> Vec<(String, ParamSnapshot)> {
    w.params().iter().map(|p| (p.id.clone(), p.get())).collect()
}

/// Applies saved values by id; ids the widget no longer has are skipped (the deck changed).
pub fn restore(w: &mut dyn super::SlideWidget, saved: &[(String, ParamSnapshot)]) {
    for mut p in w.params() {
        if let Some((_, v)) = saved.iter().find(|(id, _)| *id == p.id) {
            let _ = p.set(*v);
        }
    }
}
