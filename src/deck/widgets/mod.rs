//! The widget specs: what a deck file says about each live widget (and, while presenting, the
//! widget's live, tweakable values). Pure data with serde, no egui: `crate::widgets` draws them.

use serde::{Deserialize, Serialize};

pub mod convergence;
pub mod energy;
pub mod methods;
pub mod neptune;
pub mod ode;
pub mod parallel_transport;
pub mod rigid_body;
pub mod scene;
pub mod simulation_loop;
pub mod slope_field;
pub mod spiral;
pub mod stability;
pub mod step_construction;
pub mod taylor;
pub mod work_precision;

pub use convergence::ConvergenceSpec;
pub use energy::EnergySpec;
pub use methods::{MethodRef, ResolvedMethod};
pub use neptune::NeptuneSpec;
pub use ode::{LoadedOde, OdeError, OdeSource};
pub use parallel_transport::ParallelTransportSpec;
pub use rigid_body::RigidBodySpec;
pub use scene::SceneSpec;
pub use simulation_loop::SimulationLoopSpec;
pub use slope_field::SlopeFieldSpec;
pub use spiral::SpiralSpec;
pub use stability::StabilitySpec;
pub use step_construction::StepSpec;
pub use taylor::{TaylorFn, TaylorSpec};
pub use work_precision::WorkPrecisionSpec;

/// How a plot maps its data to the screen: `Equal` keeps one unit the same length on both axes
/// (a circle stays round; for geometry: phase portraits of x–y, the complex plane), `Free`
/// stretches each axis to fill the plot (t–x plots, phase planes of mixed units such as x–v).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Aspect {
    Equal,
    Free,
}

/// Which widget a slide shows, with its parameters from the deck file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum WidgetSpec {
    /// 1. Slope field of ẋ = f(x, t) or a phase plane, with Euler / midpoint / RK4 / exact paths.
    SlopeField(SlopeFieldSpec),
    /// 2. One step of Euler, midpoint and RK4, built up stage by stage.
    StepConstruction(StepSpec),
    /// 3. Euler turns the circle x'' = −x into a spiral (the "inaccuracy" picture).
    Spiral(SpiralSpec),
    /// 4. "Off to Neptune": y' = λy (or any ODE) with h across the stability limit.
    Neptune(NeptuneSpec),
    /// 5. Taylor polynomials of order 1, 2, 3, … around a point.
    Taylor(TaylorSpec),
    /// 6. Global error vs h on log–log axes with fitted slopes.
    Convergence(ConvergenceSpec),
    /// 7. Work–precision: error vs f-evaluations and vs time, computed in the background.
    WorkPrecision(WorkPrecisionSpec),
    /// 8. Stability regions |R(z)| ≤ 1 in the complex plane.
    Stability(StabilitySpec),
    /// 9. A tumbling box near its intermediate axis (the Dzhanibekov flip).
    RigidBody(RigidBodySpec),
    /// 10. The exercise: fish along a path, Frenet frame vs parallel transport.
    ParallelTransport(ParallelTransportSpec),
    /// 11. The simulation loop of a floating body, drawn as a cycle with live numbers.
    SimulationLoop(SimulationLoopSpec),
    /// 12. The live water scene (or a debug view) with its techniques and camera from the deck.
    Scene(SceneSpec),
    /// 13. The energy of several methods' paths on one system, with their steps and f-evaluations
    /// (the stiff spring: explicit methods explode, implicit Euler damps, the midpoint keeps it).
    Energy(EnergySpec),
}

impl WidgetSpec {
    /// A short name for lists and snapshot files.
    pub fn kind(&self) -> &'static str {
        match self {
            WidgetSpec::SlopeField(_) => "slope-field",
            WidgetSpec::StepConstruction(_) => "step-construction",
            WidgetSpec::Spiral(_) => "spiral",
            WidgetSpec::Neptune(_) => "neptune",
            WidgetSpec::Taylor(_) => "taylor",
            WidgetSpec::Convergence(_) => "convergence",
            WidgetSpec::WorkPrecision(_) => "work-precision",
            WidgetSpec::Stability(_) => "stability",
            WidgetSpec::RigidBody(_) => "rigid-body",
            WidgetSpec::ParallelTransport(_) => "parallel-transport",
            WidgetSpec::SimulationLoop(_) => "simulation-loop",
            WidgetSpec::Scene(_) => "scene",
            WidgetSpec::Energy(_) => "energy",
        }
    }
}

impl WidgetSpec {
    /// The widget's ODE source, if it draws an ODE.
    pub fn ode(&self) -> Option<&OdeSource> {
        match self {
            WidgetSpec::SlopeField(s) => Some(&s.ode),
            WidgetSpec::StepConstruction(s) => Some(&s.ode),
            WidgetSpec::Spiral(s) => Some(&s.ode),
            WidgetSpec::Neptune(s) => Some(&s.ode),
            WidgetSpec::Convergence(s) => Some(&s.ode),
            WidgetSpec::WorkPrecision(s) => Some(&s.ode),
            WidgetSpec::Energy(s) => Some(&s.ode),
            WidgetSpec::Taylor(_)
            | WidgetSpec::Stability(_)
            | WidgetSpec::RigidBody(_)
            | WidgetSpec::ParallelTransport(_)
            | WidgetSpec::SimulationLoop(_)
            | WidgetSpec::Scene(_) => None,
        }
    }

    /// The methods the widget names (tableau files to check), if it has a `methods:` list.
    pub fn methods(&self) -> &[MethodRef] {
        match self {
            WidgetSpec::SlopeField(s) => &s.methods,
            WidgetSpec::Spiral(s) => &s.methods,
            WidgetSpec::Neptune(s) => &s.methods,
            WidgetSpec::Convergence(s) => &s.methods,
            WidgetSpec::WorkPrecision(s) => &s.methods,
            WidgetSpec::Stability(s) => &s.methods,
            WidgetSpec::Energy(s) => &s.methods,
            WidgetSpec::StepConstruction(s) => std::slice::from_ref(&s.method),
            WidgetSpec::Taylor(_)
            | WidgetSpec::RigidBody(_)
            | WidgetSpec::ParallelTransport(_)
            | WidgetSpec::SimulationLoop(_)
            | WidgetSpec::Scene(_) => &[],
        }
    }
}
