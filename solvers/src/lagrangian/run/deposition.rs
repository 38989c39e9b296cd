//! The deposition (`initial = "bed"`): the particles settle under gravity with the fluid at
//! rest for `solver.lagrangian.settle_time`, one fluid period per call so that the driver sees it
//! (phase [`crate::run::Phase::Setup`]) and `solver.lagrangian.max_steps` bounds it; then, with a
//! rough bottom, the lowest particles are removed or fixed, and with `surface =
//! "deposit"` the free surface is put `water_depth` above the deposit.

use std::borrow::Cow;

use super::config::{Bottom, FluidMode, Surface};
use super::sampling::average;
use super::setup;
use super::solver::{Lagrangian, CHECK_STEPS};
use super::state::Stage;
use super::stepping::{check, dem_step};
use crate::column::{FluidColumn, Grid};
use crate::lagrangian::coupling::averaging::{CellSums, Seen};
use crate::lagrangian::coupling::damping::SlipAverage;
use crate::lagrangian::coupling::drag::{FluidField, FluidForces};
use crate::lagrangian::coupling::smoothing::PhiWindow;
use crate::lagrangian::stats::granular::GranularStats;
use crate::lagrangian::stats::statistics::Stats;
use crate::run::{Breakdown, Ending, Limits, Place};

impl Lagrangian<'_> {
    /// Deposition steps up to the next fluid period (the fluid is averaged and the
    /// particles checked at its first step, as in the flow), then the end of the
    /// deposition when its time is up; never past the step cap of `limits`. `Some` when
    /// the deposition broke down.
    pub(crate) fn deposit_period(&mut self, limits: &Limits) -> Option<Ending> {
        let max_steps = limits.max_steps;
        let fluid = self.params.cfg.settings.numerics.fluid != FluidMode::Off;
        let period = self.params.fluid_every.min(CHECK_STEPS);
        let end = (self.state.settle_steps + period).min(self.params.settle_total).min(max_steps);
        while self.state.settle_steps < end {
            let update = self.state.settle_steps.is_multiple_of(self.params.fluid_every) && fluid;
            let checkpoint = self.state.settle_steps.is_multiple_of(CHECK_STEPS);
            dem_step(&self.params, &mut self.state, &mut self.work, update, false);
            self.state.settle_steps += 1;
            if update {
                average(&self.params, &mut self.state, &mut self.work);
            }
            if update || checkpoint {
                if let Err(b) = check(&self.params, &self.state) {
                    return Some(Ending::Unstable(during_deposition(b)));
                }
            }
        }
        if self.state.settle_steps >= self.params.settle_total {
            if let Err(b) = self.finish_deposition() {
                return Some(Ending::Unstable(during_deposition(b)));
            }
        }
        None
    }

    /// The bed is down: restore the flow's body force, fix the rough layer or stop the
    /// particles, forget the contacts, then start the flow ([`Lagrangian::start_flow`]).
    fn finish_deposition(&mut self) -> Result<(), Breakdown> {
        self.state.dem.body = self.params.flow_body;
        if self.params.cfg.settings.numerics.bottom == Bottom::Rough {
            let (_, removed, fixed) = setup::bed_counts(&self.params.cfg, &self.params.mat);
            self.state.dem.p = setup::fix_rough_layer(&self.state.dem.p, removed, fixed, self.params.mat.rho_p);
        } else {
            let p = &mut self.state.dem.p;
            for v in [&mut p.vx, &mut p.vy, &mut p.vz, &mut p.wx, &mut p.wy, &mut p.wz] {
                v.fill(0.0);
            }
        }
        self.state.dem.reset_topology();
        self.start_flow(None)?;
        match self.state.start.take() {
            Some(start) => self.start_with(&start),
            None => Ok(()),
        }
    }

    /// Start the flow on the grains as they lie: the column fitted to their deposit (with
    /// `surface = "deposit"`), every grain's fluid forces and random stream fresh from the
    /// seed, the clocks at zero. The end of a deposition and a warm start share it, so that
    /// a warm-started flow starts as the scene's own would but for its grains.
    ///
    /// `deposit` is the surface of the deposit when it is known (m above the column
    /// bottom): a warm start's, measured when the carried grains lay at rest. `None`
    /// measures it on the grains, which lie at rest only at the end of a deposition.
    pub(super) fn start_flow(&mut self, deposit: Option<f64>) -> Result<(), Breakdown> {
        // the forces first: the deposit's measure sums over them, one per grain as they lie
        let n = self.state.dem.p.len();
        let fallback = self.state.forces.fallback_period;
        self.state.forces = FluidForces::new(
            n,
            self.params.seed,
            self.state.forces.rho_f,
            self.state.forces.nu_f,
            self.params.mat.rho_p,
        );
        self.state.forces.fallback_period = fallback;
        self.state.forces.restart_fluctuations();
        if self.params.cfg.settings.numerics.surface == Surface::Deposit
            && self.params.cfg.settings.numerics.fluid != FluidMode::Off
        {
            self.fit_column_to_deposit(deposit)?;
        }
        self.state.stage = Stage::Flow;
        Ok(())
    }

    /// Surface of the deposit above the column bottom (m): the highest level where the
    /// packing, averaged over one diameter, is half its largest such average. The grains
    /// are summed on slices of the column's height that reach above the highest grain: a
    /// deposit packed looser than `bed_phi` stands above `bed_height`, and under shallow
    /// water above the scene's column, whose top would otherwise cap the measure.
    pub(super) fn measure_deposit_surface(&self) -> f64 {
        let d = self.params.mat.d;
        let dz = self.state.field.dz;
        let base = self.state.field.base;
        let p = &self.state.dem.p;
        let own = self.state.sums.vol.len();
        let top = (0..p.len()).map(|a| p.z[a] + p.radius[a] - base).filter(|z| z.is_finite()).fold(0.0f64, f64::max);
        // a grain thrown far above is no part of the deposit: the slices stop at four
        // columns' heights
        let n = own.max((top / dz).ceil() as usize + 1).min(4 * own.max(1));
        let mut sums = CellSums::new(n);
        // only the volumes are read: either exchange would do
        sums.accumulate(p, base, dz, &self.state.forces.k, &self.state.forces.urx, Seen::Centre);
        let w = ((d / dz).round() as usize).max(1);
        // running sums: a window of w cells per cell would cost cells * d / dz, 1e11
        // operations for a million cells
        let mut prefix = Vec::with_capacity(n + 1);
        prefix.push(0.0);
        let mut acc = 0.0;
        for &v in &sums.vol {
            acc += v;
            prefix.push(acc);
        }
        let mean: Vec<f64> = (0..n)
            .map(|c| {
                let (lo, hi) = (c.saturating_sub(w / 2), (c + w / 2 + 1).min(n));
                (prefix[hi] - prefix[lo]) / ((hi - lo) as f64 * self.state.cell_volume)
            })
            .collect();
        let best = mean.iter().fold(0.0f64, |a, &m| a.max(m));
        match (0..n).rev().find(|&c| mean[c] >= 0.5 * best) {
            Some(c) => (c as f64 + 0.5) * dz,
            None => self.state.bed_surface,
        }
    }

    /// Put the free surface `water_depth` above the deposit (its surface `deposit`, or
    /// measured): a new column of the same cell size (before the flow starts; it
    /// allocates).
    fn fit_column_to_deposit(&mut self, deposit: Option<f64>) -> Result<(), Breakdown> {
        let surface = match deposit {
            Some(z) => z,
            None => self.measure_deposit_surface(),
        };
        let dz = self.state.field.dz;
        let height = surface + self.params.cfg.domain.water_depth;
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
        if let Some(params) = self.params.column_params {
            self.state.column = Some(FluidColumn::new(grid, params).map_err(|e| fail(e.to_string()))?);
        }
        let base = self.state.field.base;
        self.state.field = FluidField::at_rest(cells, dz, base);
        self.state.field.set_bed_threshold(self.params.fluctuation.and_then(|f| f.above_bed()));
        self.state.sums = CellSums::new(cells);
        if !self.state.slip.is_empty() {
            self.state.slip = SlipAverage::new(cells);
        }
        if !self.state.phi_window.vol.is_empty() {
            self.state.phi_window = PhiWindow::new(cells);
        }
        let v = |x: f64| vec![x; cells];
        self.state.phi = v(0.0);
        self.state.u_p = v(0.0);
        self.state.beta = v(0.0);
        self.state.tau_t = v(0.0);
        self.state.stats = Stats::new(cells);
        if self.state.granular.is_some() {
            self.state.granular = Some(GranularStats::new(cells));
        }
        self.work.resize(cells);
        self.state.cell_volume = self.params.cfg.domain.length * self.params.cfg.domain.width * dz;
        self.state.bed_surface = surface;
        Ok(())
    }
}

/// A breakdown of the deposition says so.
fn during_deposition(mut b: Breakdown) -> Breakdown {
    b.reason.push_str(" (during the deposition)");
    b
}
