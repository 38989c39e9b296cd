//! What a resolved scene must hold together: the active solver's needs, the closures'
//! needs of each other, and the periodic statistics' forcing.

use super::*;

impl Scene {
    /// `output.phases` needs a periodic forcing and a whole period after the spin-up.
    pub(super) fn check_phases(&self, end_time: f64, end_key: &str) -> Result<()> {
        let f = self.path.as_path();
        if self.output.phases == 0 {
            return Ok(());
        }
        let Some(period) = self.physics.forcing.as_ref().and_then(Forcing::period) else {
            return Err(Error::Key {
                file: f.into(),
                key: "output.phases".into(),
                message: "phase averages need a periodic physics.forcing (sinusoids, stokes2, abreu2010, or a table with a period)".into(),
            });
        };
        let needed = (self.output.spin_up_periods as f64 + 1.0) * period;
        if end_time < needed * (1.0 - 1e-12) {
            return Err(Error::Key {
                file: f.into(),
                key: "output.spin_up_periods".into(),
                message: format!(
                    "= {} periods of {} s leave no whole period before {end_key} = {} s (at least {} s)",
                    self.output.spin_up_periods,
                    crate::param::number(period),
                    crate::param::number(end_time),
                    crate::param::number(needed)
                ),
            });
        }
        Ok(())
    }

    /// What the active solver needs beyond the ranges of its keys.
    pub(super) fn check_active(&self) -> Result<()> {
        let f = self.path.as_path();
        let (end_time, end_key) = self.end_time();
        self.output.check(f, end_time, end_key)?;
        let key = |k: &str, m: String| Error::Key { file: f.into(), key: k.into(), message: m };
        self.check_phases(end_time, end_key)?;
        let unsteady = self.physics.forcing.as_ref().is_some_and(Forcing::is_unsteady);
        match self.solver.kind {
            SolverKind::Eulerian if unsteady && self.solver.eulerian.time_stepping == TimeStepping::Steady => {
                return Err(key(
                    "solver.eulerian.time_stepping",
                    "= \"steady\" marches to a steady state that a time-dependent physics.forcing never reaches, with a first-order time error; use \"accurate\"".into(),
                ));
            }
            SolverKind::Lagrangian if unsteady && self.solver.lagrangian.stop_when_steady => {
                return Err(key(
                    "solver.lagrangian.stop_when_steady",
                    "= true stops at a steady transport rate that a time-dependent physics.forcing never gives; set it to false".into(),
                ));
            }
            _ => {}
        }
        match self.solver.kind {
            SolverKind::Eulerian => {
                if self.domain.height() <= 0.0 {
                    return Err(key(
                        "domain.water_depth",
                        "the column height bed_height + water_depth must be > 0".into(),
                    ));
                }
                let cells = self.domain.cells.ok_or_else(|| {
                    key(
                        "domain.cells",
                        format!("missing, and cells of d/4 over the column are more than {MAX_CELLS}; give it"),
                    )
                })?;
                check(f, "domain.cells", cells as f64, ParamRange::closed(4.0, MAX_CELLS as f64))?;
                // the widths of a stretched grid span r^(cells - 1): past four decades the
                // phi step of a dense bed goes unstable (case 1 at r = 1.2 runs with 60 cells,
                // a span of 4.7e4, and stops at 66, 1.4e5; r = 1.1 runs at 100 cells, stops
                // at 200), and 1.2 over 400 cells makes a first cell of 4e-34 m
                let r = self.domain.stretching;
                if r > 1.0 && (cells - 1) as f64 * r.log10() > MAX_STRETCH_DECADES {
                    let most = 1 + (MAX_STRETCH_DECADES / r.log10()).floor() as usize;
                    return Err(key(
                        "domain.stretching",
                        format!(
                            "{r} over {cells} cells makes the largest cell {} times the first; at most 1e{MAX_STRETCH_DECADES} is allowed, so at most {most} cells at this ratio (or a ratio closer to 1)",
                            crate::param::number(r.powi(cells as i32 - 1))
                        ),
                    ));
                }
                if self.closures.wall_friction.is_some() {
                    return Err(key(
                        "closures.wall_friction",
                        "the Eulerian column has no channel width, so no side walls: only the lagrangian solver with solver.lagrangian.side_walls = true takes the walls' friction".into(),
                    ));
                }
                let phi_max = self.closures.max_packing().ok_or_else(|| {
                    key(
                        "closures.granular",
                        "missing; the Eulerian solver needs a granular closure (mu_i, mu_k or frictional_collisional)"
                            .into(),
                    )
                })?;
                let below = ParamRange::open(0.0, phi_max);
                let why = format!("< {phi_max} (maximum packing of closures.granular)");
                let bed_phi = self.domain.bed_phi.unwrap_or(EULERIAN_BED_PHI);
                for (k, v) in [("domain.bed_phi", bed_phi), ("domain.suspension_phi", self.domain.suspension_phi)] {
                    if v != 0.0 && !below.contains(v) {
                        return Err(Error::OutOfRange {
                            file: f.into(),
                            key: k.into(),
                            value: crate::param::number(v),
                            allowed: why,
                        });
                    }
                }
                let rlp =
                    self.solver.eulerian.elastic_phi_rlp.unwrap_or_else(|| solver::default_elastic_phi_rlp(phi_max));
                let local = self.closures.granular.as_deref().and_then(|g| g.as_local()).is_some();
                if local && rlp >= phi_max {
                    return Err(Error::OutOfRange {
                        file: f.into(),
                        key: "solver.eulerian.elastic_phi_rlp".into(),
                        value: crate::param::number(rlp),
                        allowed: format!("< {phi_max} (the closure's packing at zero shear)"),
                    });
                }
            }
            SolverKind::Lagrangian => {
                self.solver.lagrangian.check_active(f, &self.case())?;
                if self.particles.contact.law == ContactModel::Linear && self.particles.contact.stiffness.is_none() {
                    return Err(key(
                        "particles.contact.stiffness",
                        format!("missing, and the rigid-limit default needs grains heavier than the fluid under gravity, inside {STIFFNESS}; give it"),
                    ));
                }
                // a lid (Fry et al. 2024's Couette bedload) or a symmetry plane bounds the
                // DEM's fluid column: it needs the column solved, and k-omega has no wall
                // treatment at a lid
                if self.domain.top != Top::FreeSurface && self.solver.lagrangian.fluid != FluidMode::Coupled {
                    return Err(key(
                        "domain.top",
                        "`lid` and `symmetry` bound the fluid column: they need solver.lagrangian.fluid = \"coupled\""
                            .into(),
                    ));
                }
                // the walls' friction is felt by the fluid column between two walls
                if self.closures.wall_friction.is_some() {
                    if !self.solver.lagrangian.side_walls {
                        return Err(key(
                            "closures.wall_friction",
                            "the walls whose friction the fluid loses need solver.lagrangian.side_walls = true (width is then the channel width); remove [closures.wall_friction] or add the walls".into(),
                        ));
                    }
                    if self.solver.lagrangian.fluid != FluidMode::Coupled {
                        return Err(key(
                            "closures.wall_friction",
                            "acts on the fluid column, which only solver.lagrangian.fluid = \"coupled\" solves; remove [closures.wall_friction]".into(),
                        ));
                    }
                }
                if self.domain.top == Top::Lid
                    && self.closures.turbulence.as_ref().is_some_and(|t| !t.transported().is_empty())
                {
                    return Err(key("domain.top", "`lid` is not supported with a transported turbulence model (no wall treatment at a moving lid); use laminar or mixing_length".into()));
                }
                let unused = [
                    ("domain.lid_velocity", self.domain.top != Top::Lid && self.domain.lid_velocity != 0.0),
                    ("domain.stretching", self.domain.stretching != 1.0),
                    ("domain.suspension_phi", self.domain.suspension_phi != 0.0),
                ];
                if let Some((k, _)) = unused.iter().find(|(_, set)| *set) {
                    return Err(key(k, "not supported by the lagrangian solver (a free-surface column on a uniform grid, grains from solver.lagrangian.initial)".into()));
                }
            }
        }
        Ok(())
    }

    /// Fields provided by the scene's closures.
    pub fn provided(&self) -> Needs {
        let mut p = Needs::NONE;
        if let Some(t) = &self.closures.turbulence {
            p = p.union(t.provides());
        }
        if let Some(g) = &self.closures.granular {
            p = p.union(g.provides());
        }
        p
    }

    pub(super) fn check_needs(&self) -> Result<()> {
        let provided = self.provided();
        if let Some(fl) = &self.closures.fluctuation {
            if let Some(field) = fl.needs().missing(provided).next() {
                let turb = self.closures.turbulence.as_ref().map_or("none", |t| t.name());
                return Err(Error::UnmetNeed {
                    file: self.path.clone(),
                    key: "closures.fluctuation".into(),
                    model: fl.name().into(),
                    field: field.name().into(),
                    provider: provider_sentence(field, turb),
                });
            }
        }
        Ok(())
    }
}

fn provider_sentence(field: Field, turbulence: &str) -> String {
    match field {
        Field::GranularTemperature => {
            "only a kinetic granular closure provides (closures.granular type = \"frictional_collisional\")".into()
        }
        _ => format!("turbulence model `{turbulence}` (closures.turbulence) does not provide"),
    }
}
