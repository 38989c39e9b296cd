//! The Eulerian solver behind the [`Stepper`] interface until it implements it itself.
//!
//! COORDINATOR: interim. `Eulerian::run` keeps its time-step control in locals, so it
//! cannot be resumed step by step from outside `solvers/src/eulerian/`; this adapter runs
//! it whole in one `step`, so the observer (progress bar, Ctrl-C) sees an Eulerian run
//! only when it ends. Replace by the Eulerian's own `impl Stepper` in `resolve` and
//! delete this file.

use std::borrow::Cow;
use std::cell::RefCell;

use saltus_core::scene::Scene;

use super::{Breakdown, Ending, Phase, Place, Progress, Stepper};
use crate::eulerian::{self, Eulerian};
use crate::RunReport;

/// An Eulerian run as one unit of work.
pub(crate) struct EulerianRun<'a> {
    scene: &'a Scene,
    // `eulerian_report` reads derived fields through `&mut` (the lagged state is advanced
    // when read); the cell keeps `Stepper::report` a `&self` method meanwhile
    model: RefCell<Eulerian<'a>>,
    last: Progress,
}

impl<'a> EulerianRun<'a> {
    pub(crate) fn new(scene: &'a Scene, model: Eulerian<'a>) -> Self {
        let s = &model.config().settings;
        let last = Progress {
            phase: Phase::Flow,
            time: 0.0,
            end_time: s.end_time,
            steps: 0,
            dt: s.dt_initial,
            residual: None,
        };
        Self { scene, model: RefCell::new(model), last }
    }
}

fn progress(p: &eulerian::Progress) -> Progress {
    Progress {
        phase: Phase::Flow,
        time: p.time,
        end_time: p.end_time,
        steps: p.steps as u64,
        dt: p.dt,
        residual: p.residual.is_finite().then_some(p.residual),
    }
}

impl Stepper for EulerianRun<'_> {
    fn name(&self) -> &'static str {
        "eulerian"
    }

    fn step(&mut self) -> Option<Ending> {
        let mut last = self.last;
        let ending = self.model.get_mut().run(&mut |p| {
            last = progress(p);
            true
        });
        self.last = last;
        Some(match ending {
            eulerian::Ending::Steady => Ending::Steady,
            eulerian::Ending::EndTime => Ending::EndTime,
            eulerian::Ending::MaxSteps => Ending::MaxSteps,
            eulerian::Ending::Unstable(b) => Ending::Unstable(Breakdown {
                time: b.time,
                place: Place::Cell { index: b.cell, z: b.z },
                field: Cow::Borrowed(b.field),
                value: b.value,
                reason: b.reason,
            }),
        })
    }

    fn progress(&self) -> Progress {
        self.last
    }

    fn report(&self, ending: &Ending, wall: f64) -> RunReport {
        crate::eulerian_report(self.scene, &mut self.model.borrow_mut(), ending, wall)
    }
}
