//! `saltus`: closure models and solvers for two-phase sediment transport.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use saltus::args::{Cli, ClosureCommand, Command};
use saltus::eval::{evaluate, parse_model};
use saltus::table::Table;
use saltus_core::scene::Scene;

/// `print!` that treats a closed stdout (`saltus run ... | head`) as the end of the output
/// instead of panicking: the outputs are already on disk by then.
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if let Err(e) = write!(std::io::stdout(), $($arg)*) {
            if e.kind() == std::io::ErrorKind::BrokenPipe {
                return Ok(());
            }
            return Err(e.into());
        }
    }};
}

/// `println!` counterpart of [`out!`].
macro_rules! outln {
    ($($arg:tt)*) => {{
        out!($($arg)*);
        out!("\n");
    }};
}

pub fn main() -> ExitCode {
    ExitCode::from(code(Cli::parse()))
}

/// The program on `args` (the program name first) instead of the process arguments, for
/// a host that runs it in-process (`python -m saltus`): the exit code. A parse error or
/// `--help` prints as the program does and gives clap's code.
#[allow(dead_code)] // the binary does not call it; `saltus::cli` does
pub fn main_from(args: Vec<std::ffi::OsString>) -> u8 {
    match Cli::try_parse_from(args) {
        Ok(cli) => code(cli),
        Err(e) => {
            let _ = e.print();
            u8::try_from(e.exit_code()).unwrap_or(saltus::runner::EXIT_BAD_INPUT)
        }
    }
}

fn code(cli: Cli) -> u8 {
    match run(cli) {
        Ok(()) => 0,
        Err(e) => {
            saltus::errln!("error: {}", saltus::describe(&e));
            // a run stopped early wrote its outputs and says how it stopped; anything
            // else is a failure before or around the work
            // a closure check that ran and found a failing check: 1, as a test runner would
            if e.downcast_ref::<saltus::check::ChecksFailed>().is_some() {
                return 1;
            }
            e.downcast_ref::<saltus::runner::Stopped>().map_or(saltus::runner::EXIT_BAD_INPUT, |s| s.code)
        }
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    saltus::ensure_registry()?;
    match cli.command {
        Command::Models { family, json } => {
            let family = family.as_deref().map(saltus::listing::parse_family).transpose()?;
            if json {
                outln!("{}", serde_json::to_string_pretty(&saltus::listing::json(family))?);
            } else {
                out!("{}", saltus::listing::text(family));
            }
        }
        Command::Check { scene, set, closures } => {
            let s = saltus::runner::load_checked(&scene, &set, closures.as_deref())?;
            outln!("# {} resolved: every default filled in, ranges and closure needs checked", scene.display());
            out!("{}", s.to_toml()?);
        }
        Command::Run { scene, set, closures, out, restart, warm_start, max_wall, log_interval, quiet, json, seeds } => {
            if !(log_interval.is_finite() && log_interval > 0.0 && log_interval <= 1e9) {
                anyhow::bail!("--log-interval {log_interval}: must be a number of seconds in (0, 1e9]");
            }
            if let Some(w) = max_wall.filter(|w| !(w.is_finite() && *w >= 0.0 && *w <= 1e9)) {
                anyhow::bail!("--max-wall {w}: must be a number of seconds in [0, 1e9]");
            }
            if let (Some(_), Some(from)) = (&restart, &warm_start) {
                anyhow::bail!(
                    "--warm-start {}: a continued run (--restart) goes on from its own checkpoint",
                    from.display()
                );
            }
            let warm = |s: &Scene| -> anyhow::Result<Option<saltus_solvers::WarmStart>> {
                let Some(from) = &warm_start else { return Ok(None) };
                if from.join(saltus::seeds::FILE).is_file() {
                    anyhow::bail!(
                        "--warm-start {}: the developed states of several seeds start a run of as many seeds (--seeds N), one each; a single run starts from one of its seed_<k>/ folders",
                        from.display()
                    );
                }
                match saltus::runner::warm_state(s, from).map_err(|e| anyhow::anyhow!("--warm-start: {e:#}"))? {
                    Ok(w) => Ok(Some(w)),
                    Err(why) => anyhow::bail!("--warm-start {}: {why}", from.display()),
                }
            };
            if let Some(n) = seeds {
                if let Err(e) = saltus::runner::catch_interrupt() {
                    saltus::errln!("warning: {e:#}; an interrupt ends the runs without writing their outputs");
                }
                let base = Scene::from_file_with_closures(&scene, &set, closures.as_deref())?;
                // a folder of several seeds' developed states starts each seed from its own
                let starts = saltus::seeds::warm_starts(&base, warm_start.as_deref())?;
                let settings =
                    saltus::runner::RunSettings { restart, log_every: None, max_wall, warm_start: starts.single };
                let out = out.unwrap_or_else(|| saltus::runner::default_out(&base));
                let report = saltus::seeds::run_seeds(
                    &scene,
                    &set,
                    closures.as_deref(),
                    n,
                    &out,
                    &settings,
                    starts.bank,
                    &saltus::runner::interrupted,
                )?;
                if !quiet {
                    outln!("{}\noutputs: {}", report.text(), report.file.display());
                }
                let failed: Vec<String> = report
                    .runs
                    .iter()
                    .filter_map(|r| r.outcome.error.as_ref().map(|e| format!("seed {}: {e}", r.seed)))
                    .collect();
                if !failed.is_empty() {
                    anyhow::bail!("{}", failed.join("; "));
                }
                return Ok(());
            }
            // the solver's set-up inside `run` is `validate` (`resolve`), refused before
            // any output is written: loading the schema is all that is left to do here
            let s = Scene::from_file_with_closures(&scene, &set, closures.as_deref())?;
            // a continued run goes on in the folder it continues, unless told otherwise
            let out = out
                .or_else(|| restart.as_deref().map(saltus_solvers::run::checkpoint::folder))
                .unwrap_or_else(|| saltus::runner::default_out(&s));
            let bar = saltus::runner::progress_bar(!quiet && std::io::stderr().is_terminal());
            if let Err(e) = saltus::runner::catch_interrupt() {
                saltus::errln!("warning: {e:#}; an interrupt ends the run without writing its outputs");
            }
            let settings = saltus::runner::RunSettings {
                restart,
                log_every: (!quiet).then(|| std::time::Duration::from_secs_f64(log_interval)),
                max_wall,
                warm_start: warm(&s)?,
            };
            let outcome = saltus::runner::run_scene(&s, &out, &bar, &settings);
            if !quiet {
                for w in &outcome.warnings {
                    saltus::errln!("warning: {w}");
                }
            }
            let Some(report) = &outcome.report else {
                anyhow::bail!("{}", outcome.error.unwrap_or_else(|| "the run failed".into()));
            };
            // the last state is reported whatever the ending; an early stop then sets
            // the exit code (see `saltus::runner::Stopped`)
            let figure = outcome.figure.iter().chain(&outcome.phase_figures).fold(String::new(), |mut s, p| {
                s.push_str(&format!("\nfigure:  {}", p.display()));
                s
            });
            let paragraph = format!("{report}\noutputs: {}{figure}", out.display());
            if json {
                outln!("{}", serde_json::to_string_pretty(&report.summary)?);
                if !quiet {
                    saltus::errln!("{paragraph}");
                }
            } else if !quiet {
                outln!("{paragraph}");
            }
            if let Some(stopped) = outcome.stopped(&s, &out) {
                return Err(stopped.into());
            }
        }
        Command::Compare { file, set, out } => {
            let cmp = saltus::compare::load(&file, &set)?;
            let out = out.unwrap_or_else(|| saltus::compare::default_out(&cmp));
            if let Err(e) = saltus::runner::catch_interrupt() {
                saltus::errln!("warning: {e:#}; an interrupt ends the comparison without writing its outputs");
            }
            let report = saltus::compare::run(&cmp, &out, std::io::stderr().is_terminal())?;
            for w in &report.warnings {
                saltus::errln!("warning: {w}");
            }
            out!("{}", report.text_table());
            if !report.precision.is_empty() {
                outln!("work against precision:");
                out!("{}", saltus::compare::precision::text(&report.precision));
            }
            outln!("outputs: {}", out.display());
            outln!("table:   {}", report.table.display());
            if let Some(png) = &report.figure {
                outln!("figure:  {}", png.display());
            }
            if let Some(t) = &report.precision_table {
                outln!("precision: {}", t.display());
            }
            if let Some(png) = &report.precision_figure {
                outln!("precision figure: {}", png.display());
            }
            if saltus::runner::interrupted() {
                return Err(saltus::runner::Stopped {
                    code: saltus::runner::EXIT_INTERRUPTED,
                    message: format!(
                        "{}: interrupted; each variant wrote the state it had reached into {}",
                        file.display(),
                        out.display()
                    ),
                }
                .into());
            }
            let failed = report.failures();
            if failed > 0 {
                anyhow::bail!(
                    "{}: {failed} of {} variants failed (see the error column)",
                    file.display(),
                    report.runs.len()
                );
            }
        }
        Command::Calibrate { file, set, out, check } => {
            let cal = saltus::calibrate::load(&file, &set)?;
            if check {
                outln!("{}", saltus::calibrate::check(cal)?);
                return Ok(());
            }
            let out = out.unwrap_or_else(|| saltus::calibrate::default_out(&cal));
            let report = saltus::calibrate::run(cal, &out)?;
            for w in &report.warnings {
                saltus::errln!("warning: {w}");
            }
            out!("{}", report.text());
            for f in &report.files {
                outln!("{}", f.display());
            }
        }
        Command::Sweep { file, set, out, resume, jobs, emit, collect, quiet } => {
            if jobs == Some(0) {
                anyhow::bail!("--jobs 0: give the number of points run at once, at least 1");
            }
            let sweep = saltus::sweep::load(&file, &set)?;
            if let Some(dir) = emit {
                let files = saltus::sweep::emit(&sweep, &dir)?;
                outln!("{}: {} points written to {}", file.display(), files.len(), dir.display());
                outln!("run each:  saltus run {}/point_NNNN.toml", dir.display());
                outln!("then:      saltus sweep {} --collect {}", file.display(), dir.display());
                return Ok(());
            }
            let report = match collect {
                Some(dir) => saltus::sweep::collect(&sweep, &dir)?,
                None => {
                    let out = out.unwrap_or_else(|| saltus::sweep::default_out(&sweep));
                    if let Err(e) = saltus::runner::catch_interrupt() {
                        saltus::errln!("warning: {e:#}; an interrupt ends the sweep without writing its outputs");
                    }
                    let opts =
                        saltus::sweep::Options { resume, jobs, progress: std::io::stderr().is_terminal(), quiet };
                    saltus::sweep::run::run(&sweep, &out, &opts)?
                }
            };
            if !quiet {
                for w in &report.warnings {
                    saltus::errln!("warning: {w}");
                }
                out!("{}", report.text());
            }
            for f in &report.files {
                outln!("{}", f.display());
            }
            if saltus::runner::interrupted() {
                return Err(saltus::runner::Stopped {
                    code: saltus::runner::EXIT_INTERRUPTED,
                    message: format!(
                        "{}: interrupted; the finished points and the state of the running ones are in {}; continue with `saltus sweep {} --resume{}`",
                        file.display(),
                        report.out.display(),
                        file.display(),
                        if report.out == saltus::sweep::default_out(&sweep) { String::new() } else { format!(" --out {}", report.out.display()) }
                    ),
                }
                .into());
            }
            let failed = report.failures();
            if failed > 0 {
                anyhow::bail!(
                    "{}: {failed} of {} points did not finish (see the status column of {})",
                    file.display(),
                    report.manifest.points.len(),
                    report.out.join(saltus::sweep::table::TABLE).display()
                );
            }
        }
        Command::Diagnose { dir, closures, out, phi_min, fit, pool, z_min, z_max } => {
            let window = saltus::diagnose::Window { z_min, z_max };
            let dirs: Vec<PathBuf> = std::iter::once(dir.clone()).chain(pool).collect();
            let opts = saltus::diagnose::Options { phi_min, fit, window };
            let d = saltus::diagnose::diagnose_pooled(&dirs, &closures, opts)?;
            let out = out.unwrap_or_else(|| dir.join("diagnose"));
            let written = d.write(&out)?;
            for w in &written.warnings {
                saltus::errln!("warning: {w}");
            }
            out!("{}", d.text());
            outln!("outputs: {}", out.display());
        }
        Command::Closure { command } => match command {
            ClosureCommand::Eval { family, model, input, output, seed } => {
                let model = parse_model(&model, family)?;
                let (table, origin) = if input.as_os_str() == "-" {
                    (Table::read_csv(std::io::stdin().lock(), "<stdin>")?, "<stdin>".to_string())
                } else {
                    (Table::read_csv_file(&input)?, input.display().to_string())
                };
                let result = evaluate(family, model, &table, &origin, seed)?;
                match output {
                    Some(p) => result.write_csv_file(&p)?,
                    None => result.write_csv(std::io::stdout().lock())?,
                }
            }
            ClosureCommand::Check { family, model, cases } => {
                let family = saltus::listing::parse_family(&family)?;
                let model = saltus::check::parse_model(&model)?;
                let report = saltus::check::check(family, model, saltus::check::Options { cases })?;
                out!("{}", report.text());
                if !report.passed() {
                    return Err(saltus::check::ChecksFailed { failures: report.failures(), model: report.model }.into());
                }
            }
            ClosureCommand::Plot { file, out } => {
                let stem = file.file_stem().map_or_else(|| "closures".into(), |s| s.to_string_lossy().into_owned());
                let out = out.unwrap_or_else(|| PathBuf::from("out/closures").join(stem));
                let written = saltus::plot::run(&file, &out)?;
                outln!("{}: {} figures written to {}", file.display(), written.len() / 2, out.display());
                for w in written {
                    outln!("  {}", w.display());
                }
            }
        },
    }
    Ok(())
}
