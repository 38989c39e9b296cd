//! `saltus run SCENE --seeds N`: N seeds of a DEM scene run side by side as one answer.
//!
//! The error of a DEM transport rate is set by the scatter between seeds more than by one
//! run's block error (the peer case's seeds scatter by 1.9 %, two to five times one run's
//! blocks: docs/lagrangian.md). The seeds run in parallel, each into `OUT/seed_<k>/` with
//! all of its own outputs; with `solver.lagrangian.target_error` the scene's own rule is
//! replaced by one rule on the pooled answer, evaluated at the same simulated times in
//! every seed (each second of flow), so that the seeds stop together and the result does
//! not depend on the number of threads or on the order in which the seeds reach a time.
//!
//! The pooled answer is the mean of the seeds' window means (each seed's window found by
//! MSER-5 in its own series, docs/lagrangian.md "The averaging window and the stopping
//! rule"); its standard error is the larger of the within-seed error,
//! sqrt(sum_i se_i^2) / N, and the between-seed error, sd(mean_i) / sqrt(N); from three
//! seeds on the between-seed error stands alone where a seed's blocks give no error yet
//! (two seeds give it one degree of freedom only). The rule holds when every seed has a
//! level window (Geweke |z| <= 2) and the pooled relative error is at or below the target. `OUT/seeds.json` holds the answer,
//! each seed's and the rule.

use std::path::{Path, PathBuf};
use std::sync::{Condvar, Mutex};

use anyhow::{bail, Context};
use saltus_core::scene::{Scene, SolverKind};
use saltus_solvers::lagrangian::stats::truncation::GEWEKE_Z;
use saltus_solvers::run::{Answer, Clock, Control, Phase};
use saltus_solvers::{Ending, Observer, Progress, Stepper};
use serde::Serialize;

use crate::runner::{self, RunOutcome, RunSettings};

/// Most seeds one `--seeds` runs.
pub const MAX_SEEDS: usize = 256;

/// Simulated time between two evaluations of the pooled rule (s of flow).
pub const POOL_INTERVAL: f64 = 1.0;

/// The pooled answer of several seeds at one time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Pooled {
    /// seeds pooled
    pub seeds: usize,
    /// mean of the seeds' window means (qs, m^2/s)
    pub mean: f64,
    /// the larger of the within- and between-seed standard errors (m^2/s; infinite while
    /// unknown)
    pub stderr: f64,
    /// sqrt(sum se_i^2) / N, or `None` when a seed has no block error yet
    pub stderr_within: Option<f64>,
    /// sd(mean_i) / sqrt(N) (N >= 2)
    pub stderr_between: Option<f64>,
    /// stderr / |mean|
    pub relative_error: f64,
    /// every seed's window is level (Geweke |z| <= 2) and the error is known
    pub level: bool,
}

/// Pool the answers of seeds; `None` when a seed has no window yet.
pub fn pool_answers(answers: &[Answer]) -> Option<Pooled> {
    if answers.is_empty() {
        return None;
    }
    let n = answers.len() as f64;
    let mean = answers.iter().map(|a| a.mean).sum::<f64>() / n;
    let within = answers.iter().map(|a| a.stderr.map(|e| e * e)).sum::<Option<f64>>().map(|s| s.sqrt() / n);
    let between = (answers.len() >= 2).then(|| {
        let var = answers.iter().map(|a| (a.mean - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (var / n).sqrt()
    });
    // two seeds give the between-seed error one degree of freedom: it stands alone from
    // three seeds on, and with fewer only beside each seed's block error
    let stderr = match (within, between) {
        (Some(w), b) => w.max(b.unwrap_or(0.0)),
        (None, Some(b)) if answers.len() >= 3 => b,
        _ => f64::INFINITY,
    };
    let level = stderr.is_finite() && answers.iter().all(|a| a.geweke_z.is_some_and(|z| z.abs() <= GEWEKE_Z));
    let relative_error = if mean != 0.0 { stderr / mean.abs() } else { f64::INFINITY };
    Some(Pooled {
        seeds: answers.len(),
        mean,
        stderr,
        stderr_within: within,
        stderr_between: between,
        relative_error,
        level,
    })
}

/// What one seed has told the pool in the current round.
#[derive(Clone, Copy, Debug)]
enum Post {
    Waiting,
    Posted(Option<Answer>),
    Gone,
}

#[derive(Debug)]
struct PoolState {
    posts: Vec<Post>,
    /// rounds decided so far
    decided: u64,
    /// the rule held at the last decision
    stop: bool,
    /// the pooled answer of the last decision, and its time
    last: Option<(f64, Pooled)>,
}

/// The seeds' meeting point: each posts its answer at the same simulated times; the last
/// to post (or to leave) decides for all.
#[derive(Debug)]
pub struct Pool {
    target: f64,
    state: Mutex<PoolState>,
    cv: Condvar,
}

impl Pool {
    /// A pool of `n` seeds stopping at the relative error `target`.
    pub fn new(n: usize, target: f64) -> Self {
        let state = PoolState { posts: vec![Post::Waiting; n], decided: 0, stop: false, last: None };
        Self { target, state: Mutex::new(state), cv: Condvar::new() }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, PoolState> {
        // a seed that panicked holding the lock leaves a state the others can still read
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Decide round `round` when every seed still running has posted.
    fn decide_if_complete(&self, st: &mut PoolState, round: u64, time: f64) {
        if st.decided >= round || st.posts.iter().any(|p| matches!(p, Post::Waiting)) {
            return;
        }
        let answers: Vec<Option<Answer>> =
            st.posts.iter().filter_map(|p| if let Post::Posted(a) = p { Some(*a) } else { None }).collect();
        let pooled = answers.iter().copied().collect::<Option<Vec<Answer>>>().and_then(|a| pool_answers(&a));
        st.stop = pooled.is_some_and(|p| p.level && p.relative_error <= self.target);
        if let Some(p) = pooled {
            st.last = Some((time, p));
        }
        st.decided = round;
        for p in st.posts.iter_mut() {
            if let Post::Posted(_) = p {
                *p = Post::Waiting;
            }
        }
        self.cv.notify_all();
    }

    /// Seed `i` at round `round` (time `time`) with its answer: whether the pooled rule
    /// holds. Waits for the other seeds of the round.
    fn post(&self, i: usize, round: u64, time: f64, answer: Option<Answer>) -> bool {
        let mut st = self.lock();
        st.posts[i] = Post::Posted(answer);
        self.decide_if_complete(&mut st, round, time);
        while st.decided < round {
            st = self.cv.wait(st).unwrap_or_else(|e| e.into_inner());
        }
        st.stop
    }

    /// Seed `i` has ended: the rounds go on without it.
    fn leave(&self, i: usize, round: u64, time: f64) {
        let mut st = self.lock();
        if matches!(st.posts[i], Post::Gone) {
            return;
        }
        st.posts[i] = Post::Gone;
        if st.posts.iter().any(|p| matches!(p, Post::Posted(_))) {
            self.decide_if_complete(&mut st, round + 1, time);
        }
        self.cv.notify_all();
    }

    /// The pooled answer of the last decision and its time.
    pub fn last(&self) -> Option<(f64, Pooled)> {
        self.lock().last
    }
}

/// One seed's observer: posts its answer every [`POOL_INTERVAL`] of flow.
struct Member<'a> {
    pool: &'a Pool,
    index: usize,
    next: f64,
    round: u64,
    time: f64,
}

impl Observer for Member<'_> {
    fn step(&mut self, stepper: &dyn Stepper, progress: &Progress, _: &Clock) -> Control {
        if progress.phase != Phase::Flow || progress.time < self.next {
            return Control::Continue;
        }
        while self.next <= progress.time {
            self.next += POOL_INTERVAL;
        }
        self.round += 1;
        self.time = progress.time;
        if self.pool.post(self.index, self.round, progress.time, stepper.answer()) {
            Control::Answered
        } else {
            Control::Continue
        }
    }

    fn finish(&mut self, _: &dyn Stepper, _: &Ending, _: &Clock) {
        self.pool.leave(self.index, self.round, self.time);
    }
}

/// A seed leaves the pool when its member goes, however its run ended: at its ending
/// (`finish`), after a failure before its first unit of work, or while a panic unwinds its
/// thread, so that the other seeds never wait for a round it cannot post.
impl Drop for Member<'_> {
    fn drop(&mut self) {
        self.pool.leave(self.index, self.round, self.time);
    }
}

/// One seed of a `--seeds` run.
#[derive(Debug)]
pub struct SeedRun {
    /// the scene's seed of this run
    pub seed: u64,
    /// its output folder
    pub out: PathBuf,
    /// what it left behind
    pub outcome: RunOutcome,
}

/// What `--seeds` wrote.
#[derive(Debug)]
pub struct SeedsReport {
    /// every seed's run, in seed order
    pub runs: Vec<SeedRun>,
    /// the pooled answer of the seeds' final windows
    pub pooled: Option<Pooled>,
    /// qs* of the pooled answer and its standard error (the seeds' transport scale)
    pub qs_star: Option<(f64, f64)>,
    /// the target of the pooled rule
    pub target_error: Option<f64>,
    /// `seeds.json`
    pub file: PathBuf,
}

#[derive(Serialize)]
struct SeedRow<'a> {
    seed: u64,
    dir: &'a Path,
    ending: Option<&'a str>,
    error: Option<&'a str>,
    sim_time_s: Option<f64>,
    cpu_time_s: Option<f64>,
    window_start_s: Option<f64>,
    qs_window: Option<f64>,
    qs_window_stderr: Option<f64>,
}

#[derive(Serialize)]
struct SeedsFile<'a> {
    scene: &'a str,
    seeds: usize,
    target_error: Option<f64>,
    pool_interval_s: f64,
    ending: String,
    qs: Option<f64>,
    qs_stderr: Option<f64>,
    qs_star: Option<f64>,
    qs_star_stderr: Option<f64>,
    pooled: Option<Pooled>,
    cpu_time_s: f64,
    runs: Vec<SeedRow<'a>>,
}

impl SeedsReport {
    /// The ending of the seeds together: theirs when they agree, else `mixed`.
    pub fn ending(&self) -> String {
        let endings: Vec<Option<&str>> =
            self.runs.iter().map(|r| r.outcome.ending.as_ref().map(|e| e.name())).collect();
        match endings.first() {
            Some(Some(first)) if endings.iter().all(|e| e == &Some(*first)) => first.to_string(),
            _ => "mixed".into(),
        }
    }

    /// The paragraph `saltus run --seeds` prints.
    pub fn text(&self) -> String {
        let mut s = format!("{} seeds, ending {}", self.runs.len(), self.ending());
        match (self.pooled, self.qs_star) {
            (Some(p), Some((q, e))) => s.push_str(&format!(
                ": qs* = {q:.5} +- {e:.2e} (relative {:.2e}; within seeds {}, between seeds {}){}",
                p.relative_error,
                p.stderr_within.map_or("-".into(), |x| format!("{:.2e}", x / p.mean.abs())),
                p.stderr_between.map_or("-".into(), |x| format!("{:.2e}", x / p.mean.abs())),
                self.target_error.map_or(String::new(), |t| format!("; target {t}")),
            )),
            _ => s.push_str(": no pooled answer (a seed has no averaging window)"),
        }
        for r in &self.runs {
            let sm = r.outcome.report.as_ref().map(|x| &x.summary);
            let q = sm.and_then(|x| x.qs_window).map_or("-".into(), |q| format!("{q:.4e}"));
            let t = sm.map_or("-".into(), |x| format!("{:.1}", x.sim_time_s));
            s.push_str(&format!("\n  seed {}: t = {t} s, qs window {q} m^2/s  {}", r.seed, r.out.display()));
        }
        s
    }
}

/// The pooled answer's file in the output folder of a run of several seeds.
pub const FILE: &str = "seeds.json";

/// The developed states of a run of several seeds in `from` (its `seeds.json` and its
/// `seed_<k>/` folders), in the order of their seeds, each checked against `scene` as a
/// single warm start is: the beds a pooled answer starts its seeds from, one each, so that
/// the scatter between its seeds is the scatter between beds. `Ok(None)` when `from` holds
/// no `seeds.json`.
pub fn warm_bank(scene: &Scene, from: &Path) -> anyhow::Result<Option<Vec<saltus_solvers::WarmStart>>> {
    if !from.join(FILE).is_file() {
        return Ok(None);
    }
    let entries = std::fs::read_dir(from).with_context(|| format!("{}: cannot read the folder", from.display()))?;
    let mut folders: Vec<(u64, PathBuf)> = entries
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            let name = e.file_name().into_string().ok()?;
            let seed = name.strip_prefix("seed_")?.parse::<u64>().ok()?;
            e.path().is_dir().then_some((seed, e.path()))
        })
        .collect();
    folders.sort();
    if folders.is_empty() {
        bail!("{}: a seeds.json without seed_<k>/ folders", from.display());
    }
    let mut bank = Vec::with_capacity(folders.len());
    for (_, dir) in folders {
        match runner::warm_state(scene, &dir)? {
            Ok(w) => bank.push(w),
            Err(why) => bail!("{}: {why}", dir.display()),
        }
    }
    Ok(Some(bank))
}

/// The warm starts of a run of several seeds of `scene` from the folder `from`: a bank of
/// developed states, one per seed, when `from` holds the output of a run of several seeds
/// ([`warm_bank`]), else the one final state of the run in `from`, which every seed
/// starts from ([`runner::warm_state`]). Errors name `from` and why it cannot start them.
pub fn warm_starts(scene: &Scene, from: Option<&Path>) -> anyhow::Result<WarmStarts> {
    let Some(from) = from else { return Ok(WarmStarts::default()) };
    let context = |e: anyhow::Error| anyhow::anyhow!("--warm-start {}: {e:#}", from.display());
    if let Some(bank) = warm_bank(scene, from).map_err(context)? {
        return Ok(WarmStarts { single: None, bank: Some(bank) });
    }
    match runner::warm_state(scene, from).map_err(|e| anyhow::anyhow!("--warm-start: {e:#}"))? {
        Ok(w) => Ok(WarmStarts { single: Some(w), bank: None }),
        Err(why) => bail!("--warm-start {}: {why}", from.display()),
    }
}

/// Where the seeds of a run start: all from one state, each from its own, or (both
/// `None`) from the scene.
#[derive(Default)]
pub struct WarmStarts {
    /// the state every seed starts from
    pub single: Option<saltus_solvers::WarmStart>,
    /// one state per seed, in seed order
    pub bank: Option<Vec<saltus_solvers::WarmStart>>,
}

/// Run `n` seeds of the DEM scene `file` (with `set` and `closures` as `saltus run` takes
/// them) into `out/seed_<k>/`, k = the scene's seed .. seed + n - 1, in parallel, then
/// write `out/seeds.json`. `settings` apply to every seed (no `--restart`); `stop` is
/// asked by every seed after each unit of work, and true ends them all, interrupted,
/// with their outputs written.
#[allow(clippy::too_many_arguments)]
pub fn run_seeds(
    file: &Path,
    set: &[String],
    closures: Option<&Path>,
    n: usize,
    out: &Path,
    settings: &RunSettings,
    bank: Option<Vec<saltus_solvers::WarmStart>>,
    stop: &(dyn Fn() -> bool + Sync),
) -> anyhow::Result<SeedsReport> {
    if n == 0 || n > MAX_SEEDS {
        bail!("--seeds {n}: must be an integer in [1, {MAX_SEEDS}]");
    }
    if let Some(b) = bank.as_ref().filter(|b| b.len() < n) {
        bail!(
            "--seeds {n} --warm-start: {n} seeds start from {n} developed states, one each, and the folder holds {}",
            b.len()
        );
    }
    if settings.restart.is_some() {
        bail!("--seeds: a run of several seeds starts from its scene, not from a checkpoint (--restart)");
    }
    let base = Scene::from_file_with_closures(file, set, closures)?;
    if base.solver.kind != SolverKind::Lagrangian {
        bail!(
            "{}: --seeds runs the DEM (solver.type = \"lagrangian\"); the {} solver has no seed to vary",
            file.display(),
            base.solver.kind.name()
        );
    }
    let draws = base.closures.fluctuation.as_ref().is_some_and(|f| f.is_active());
    if n > 1 && bank.is_none() && !draws && matches!(settings.warm_start, Some(saltus_solvers::WarmStart::State(_))) {
        bail!(
            "{}: --seeds {n} --warm-start: the scene draws no random numbers after its deposition (no active closures.fluctuation), so {n} seeds from one developed state are one run {n} times; start them from as many developed states (--warm-start the output of a run of {n} seeds) or from rest",
            file.display()
        );
    }
    let target = base.solver.lagrangian.target_error;
    let mut scenes = Vec::with_capacity(n);
    for k in 0..n as u64 {
        let seed = base.seed.checked_add(k).context("--seeds: the seeds pass the largest seed")?;
        let mut s = set.to_vec();
        s.push(format!("seed={seed}"));
        if base.solver.lagrangian.threads == 0 && n > 1 {
            // the seeds share the cores; a seed's result does not depend on its threads
            s.push("solver.lagrangian.threads=1".into());
        }
        let mut scene = Scene::from_file_with_closures(file, &s, closures)?;
        // the pooled rule stops the seeds; each alone would stop on its own error
        scene.solver.lagrangian.target_error = None;
        scenes.push((seed, scene));
    }
    std::fs::create_dir_all(out).with_context(|| format!("{}: cannot create the folder", out.display()))?;
    let pool = target.map(|t| Pool::new(n, t));
    let seed_settings: Vec<RunSettings> = (0..n)
        .map(|i| RunSettings {
            log_every: None,
            warm_start: bank.as_ref().map_or_else(|| settings.warm_start.clone(), |b| Some(b[i].clone())),
            ..settings.clone()
        })
        .collect();
    let runs: Vec<SeedRun> = std::thread::scope(|sc| {
        let handles: Vec<_> = scenes
            .iter()
            .enumerate()
            .map(|(i, (seed, scene))| {
                let (pool, seed_settings) = (pool.as_ref(), &seed_settings[i]);
                sc.spawn(move || {
                    let dir = out.join(format!("seed_{seed}"));
                    let bar = runner::progress_bar(false);
                    let mut member =
                        pool.map(|pool| Member { pool, index: i, next: POOL_INTERVAL, round: 0, time: 0.0 });
                    let extra = member.as_mut().map(|m| m as &mut dyn Observer);
                    let outcome = runner::run_scene_observed(scene, &dir, &bar, seed_settings, &mut |_| stop(), extra)
                        .unwrap_or_else(|e| RunOutcome::failed(e.to_string()));
                    drop(member);
                    SeedRun { seed: *seed, out: dir, outcome }
                })
            })
            .collect();
        handles
            .into_iter()
            .zip(&scenes)
            .map(|(h, (seed, _))| {
                h.join().unwrap_or_else(|_| SeedRun {
                    seed: *seed,
                    out: out.join(format!("seed_{seed}")),
                    outcome: RunOutcome::failed("the run stopped on an internal error".into()),
                })
            })
            .collect()
    });
    let answers: Option<Vec<Answer>> = runs
        .iter()
        .map(|r| {
            let s = &r.outcome.report.as_ref()?.summary;
            Some(Answer {
                start: s.window_start_s?,
                mean: s.qs_window?,
                stderr: s.qs_window_stderr,
                geweke_z: s.qs_window_geweke_z,
            })
        })
        .collect();
    let pooled = answers.as_deref().and_then(pool_answers);
    // qs* over qs: the transport scale of the scene, the same in every seed
    let scale = runs.iter().find_map(|r| {
        let s = &r.outcome.report.as_ref()?.summary;
        let (q, qs) = (s.qs?, s.qs_star?);
        (q != 0.0 && q.is_finite()).then(|| qs / q)
    });
    let qs_star = pooled.zip(scale).map(|(p, k)| (p.mean * k, p.stderr * k));
    let file_out = out.join(FILE);
    let report = SeedsReport { runs, pooled, qs_star, target_error: target, file: file_out.clone() };
    let rows = report
        .runs
        .iter()
        .map(|r| {
            let s = r.outcome.report.as_ref().map(|x| &x.summary);
            SeedRow {
                seed: r.seed,
                dir: &r.out,
                ending: r.outcome.ending.as_ref().map(|e| e.name()),
                error: r.outcome.error.as_deref(),
                sim_time_s: s.map(|x| x.sim_time_s),
                cpu_time_s: s.and_then(|x| x.cpu_time_s),
                window_start_s: s.and_then(|x| x.window_start_s),
                qs_window: s.and_then(|x| x.qs_window),
                qs_window_stderr: s.and_then(|x| x.qs_window_stderr),
            }
        })
        .collect::<Vec<_>>();
    let finite = |x: Option<f64>| x.filter(|v| v.is_finite());
    let doc = SeedsFile {
        scene: &base.meta.name,
        seeds: n,
        target_error: target,
        pool_interval_s: POOL_INTERVAL,
        ending: report.ending(),
        qs: finite(pooled.map(|p| p.mean)),
        qs_stderr: finite(pooled.map(|p| p.stderr)),
        qs_star: finite(qs_star.map(|q| q.0)),
        qs_star_stderr: finite(qs_star.map(|q| q.1)),
        pooled: pooled.filter(|p| p.stderr.is_finite() && p.relative_error.is_finite()),
        cpu_time_s: rows.iter().filter_map(|r| r.cpu_time_s).sum(),
        runs: rows,
    };
    let json = serde_json::to_string_pretty(&doc)?;
    std::fs::write(&file_out, json).with_context(|| format!("{}: cannot write", file_out.display()))?;
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn answer(mean: f64, stderr: Option<f64>, z: f64) -> Answer {
        Answer { start: 1.0, mean, stderr, geweke_z: Some(z) }
    }

    #[test]
    fn the_pooled_error_is_the_larger_of_within_and_between_seeds() {
        let p = pool_answers(&[answer(1.0, Some(0.01), 0.5), answer(1.2, Some(0.02), -1.0)]).expect("pooled");
        assert!((p.mean - 1.1).abs() < 1e-15);
        let within = (0.01f64.powi(2) + 0.02f64.powi(2)).sqrt() / 2.0;
        assert!((p.stderr_within.unwrap() - within).abs() < 1e-15);
        assert!((p.stderr_between.unwrap() - 0.1).abs() < 1e-12, "sd 0.1414 over sqrt 2");
        assert!((p.stderr - 0.1).abs() < 1e-12 && p.level);
        // alike seeds: the within-seed error bounds it from below
        let p = pool_answers(&[answer(1.0, Some(0.05), 0.0), answer(1.0, Some(0.05), 0.0)]).expect("pooled");
        assert!((p.stderr - 0.05 / 2f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn without_block_errors_two_seeds_do_not_know_their_error_and_three_do() {
        let two = pool_answers(&[answer(1.0, None, 0.0), answer(1.1, Some(0.01), 0.0)]).expect("pooled");
        assert!(two.stderr.is_infinite() && !two.level);
        let three = pool_answers(&[answer(1.0, None, 0.0), answer(1.1, Some(0.01), 0.0), answer(0.9, None, 0.0)])
            .expect("pooled");
        assert!((three.stderr - 0.1 / 3f64.sqrt()).abs() < 1e-12 && three.level);
        // a seed whose window still drifts (Geweke |z| > 2) is not level
        let drift = pool_answers(&[answer(1.0, Some(0.01), 2.5), answer(1.0, Some(0.01), 0.0)]).expect("pooled");
        assert!(!drift.level);
        assert!(pool_answers(&[]).is_none());
    }

    /// A seed whose thread panics leaves the pool as it unwinds: the seed waiting for the
    /// round is released (within 10 s; without the release the test fails, leaving the
    /// waiting thread behind) and decides it alone.
    #[test]
    fn a_seed_that_panics_does_not_hold_the_others() {
        let pool = std::sync::Arc::new(Pool::new(2, 0.05));
        let (tx, rx) = std::sync::mpsc::channel();
        let waiting = pool.clone();
        std::thread::spawn(move || {
            let _ = tx.send(waiting.post(0, 1, 1.0, Some(answer(1.0, Some(0.5), 0.0))));
        });
        let crashing = pool.clone();
        let crashed = std::thread::spawn(move || {
            let _member = Member { pool: &crashing, index: 1, next: POOL_INTERVAL, round: 0, time: 0.0 };
            panic!("a seed's run panics");
        });
        assert!(crashed.join().is_err());
        let stop = rx.recv_timeout(std::time::Duration::from_secs(10)).expect("the waiting seed was released");
        assert!(!stop, "an error of 0.5 does not meet the target 0.05");
    }
}
