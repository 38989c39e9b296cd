//! The deposition (`initial = "bed"`): the particles settle under gravity with the fluid at
//! rest for `solver.lagrangian.settle_time`, one fluid period per call so that the driver sees it
//! (phase [`crate::run::Phase::Setup`]) and `solver.lagrangian.max_steps` bounds it; then, with a
//! rough bottom, the lowest particles are removed or fixed, and with `surface =
//! "deposit"` the free surface is put `water_depth` above the deposit.

use std::borrow::Cow;

use super::averaging::{CellSums, Seen};
use super::config::{Bottom, FluidMode, Surface};
use super::drag::{FluidField, FluidForces};
use super::setup;
use super::solver::{Lagrangian, Stage, CHECK_STEPS};
use super::stats::Stats;
use crate::column::{FluidColumn, Grid};
use crate::run::{Breakdown, Ending, Place};

impl Lagrangian<'_> {
    /// Deposition steps up to the next fluid period (the fluid is averaged and the
    /// particles checked at its first step, as in the flow), then the end of the
    /// deposition when its time is up. `Some` when the run is over.
    pub(super) fn deposit_period(&mut self) -> Option<Ending> {
        let max_steps = self.cfg.settings.numerics.max_steps;
        if self.settle_steps >= max_steps {
            return Some(Ending::MaxSteps);
        }
        let fluid = self.cfg.settings.numerics.fluid != FluidMode::Off;
        let period = self.fluid_every.min(CHECK_STEPS);
        let end = (self.settle_steps + period).min(self.settle_total).min(max_steps);
        while self.settle_steps < end {
            let update = self.settle_steps.is_multiple_of(self.fluid_every) && fluid;
            let checkpoint = self.settle_steps.is_multiple_of(CHECK_STEPS);
            self.dem_step(update, false);
            self.settle_steps += 1;
            if update {
                self.average();
            }
            if update || checkpoint {
                if let Err(b) = self.check() {
                    return Some(Ending::Unstable(during_deposition(b)));
                }
            }
        }
        if self.settle_steps >= self.settle_total {
            if let Err(b) = self.finish_deposition() {
                return Some(Ending::Unstable(during_deposition(b)));
            }
        }
        None
    }

    /// The bed is down: restore the flow's body force, fix the rough layer or stop the
    /// particles, forget the contacts, fit the column and start the flow's clocks.
    fn finish_deposition(&mut self) -> Result<(), Breakdown> {
        self.dem.body = self.flow_body;
        if self.cfg.settings.numerics.bottom == Bottom::Rough {
            let (_, removed, fixed) = setup::bed_counts(&self.cfg, &self.mat);
            self.dem.p = setup::fix_rough_layer(&self.dem.p, removed, fixed, self.mat.rho_p);
        } else {
            let p = &mut self.dem.p;
            for v in [&mut p.vx, &mut p.vy, &mut p.vz, &mut p.wx, &mut p.wy, &mut p.wz] {
                v.fill(0.0);
            }
        }
        self.dem.reset_topology();
        if self.cfg.settings.numerics.surface == Surface::Deposit && self.cfg.settings.numerics.fluid != FluidMode::Off
        {
            self.fit_column_to_deposit()?;
        }
        let n = self.dem.p.len();
        let fallback = self.forces.fallback_period;
        self.forces = FluidForces::new(n, self.seed, self.forces.rho_f, self.forces.nu_f, self.mat.rho_p);
        self.forces.fallback_period = fallback;
        self.forces.restart_fluctuations();
        self.dem.time = 0.0;
        self.next_vtk = 0.0;
        self.stage = Stage::Flow;
        Ok(())
    }

    /// Surface of the deposit above the column bottom (m): the highest level where the
    /// packing, averaged over one diameter, is half its largest such average. It sums the
    /// particles into the cell sums, so it is no getter.
    fn measure_deposit_surface(&mut self) -> f64 {
        let d = self.mat.d;
        let dz = self.field.dz;
        let n = self.sums.vol.len();
        // only the volumes are read: either exchange would do
        self.sums.accumulate(&self.dem.p, self.field.base, dz, &self.forces.k, &self.forces.urx, Seen::Centre);
        let w = ((d / dz).round() as usize).max(1);
        // running sums: a window of w cells per cell would cost cells * d / dz, 1e11
        // operations for a million cells
        let mut prefix = Vec::with_capacity(n + 1);
        prefix.push(0.0);
        let mut acc = 0.0;
        for &v in &self.sums.vol {
            acc += v;
            prefix.push(acc);
        }
        let mean: Vec<f64> = (0..n)
            .map(|c| {
                let (lo, hi) = (c.saturating_sub(w / 2), (c + w / 2 + 1).min(n));
                (prefix[hi] - prefix[lo]) / ((hi - lo) as f64 * self.cell_volume)
            })
            .collect();
        let best = mean.iter().fold(0.0f64, |a, &m| a.max(m));
        match (0..n).rev().find(|&c| mean[c] >= 0.5 * best) {
            Some(c) => (c as f64 + 0.5) * dz,
            None => self.bed_surface,
        }
    }

    /// Put the free surface `water_depth` above the deposit: a new column of the same
    /// cell size (before the flow starts; it allocates).
    fn fit_column_to_deposit(&mut self) -> Result<(), Breakdown> {
        let surface = self.measure_deposit_surface();
        let dz = self.field.dz;
        let height = surface + self.cfg.domain.water_depth;
        let cells = ((height / dz).round() as usize).max(2);
        let fail = |reason: String| Breakdown {
            time: 0.0,
            place: Place::Column,
            field: Cow::Borrowed("height"),
            value: height,
            reason,
        };
        let grid = Grid::uniform(cells, height).map_err(|e| fail(e.to_string()))?;
        let dz = grid.dz()[0];
        if let Some(params) = self.column_params {
            self.column = Some(FluidColumn::new(grid, params).map_err(|e| fail(e.to_string()))?);
        }
        let base = self.field.base;
        self.field = FluidField::at_rest(cells, dz, base);
        self.field.set_bed_threshold(self.fluctuation.and_then(|f| f.above_bed()));
        self.sums = CellSums::new(cells);
        let v = |x: f64| vec![x; cells];
        self.phi = v(0.0);
        self.u_p = v(0.0);
        self.beta = v(0.0);
        self.tau_t = v(0.0);
        self.stats = Stats::new(cells);
        if self.granular.is_some() {
            self.granular = Some(super::granular::GranularStats::new(cells));
        }
        self.zero_faces = vec![0.0; cells + 1];
        self.cell_volume = self.cfg.domain.length * self.cfg.domain.width * dz;
        self.bed_surface = surface;
        Ok(())
    }
}

/// A breakdown of the deposition says so.
fn during_deposition(mut b: Breakdown) -> Breakdown {
    b.reason.push_str(" (during the deposition)");
    b
}
