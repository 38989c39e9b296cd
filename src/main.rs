//! `saltus`: closure models and solvers for two-phase sediment transport.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use saltus::eval::{evaluate, parse_model, EvalFamily};
use saltus::table::Table;
use saltus_core::scene::Scene;

#[derive(Parser)]
#[command(name = "saltus", version, about = "Closure models and solvers for two-phase sediment transport")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List every registered closure model per family, with parameters, defaults, ranges
    /// and sources.
    Models {
        /// only this family (drag, hindrance, viscosity, granular, turbulence, fluctuation, wall_friction)
        family: Option<String>,
        /// machine-readable JSON instead of text
        #[arg(long)]
        json: bool,
    },
    /// Parse a scene, fill defaults, check ranges and closure needs, print the resolved
    /// scene.
    Check {
        /// scene file
        scene: PathBuf,
        /// override one key, e.g. --set physics.slope=0.05 or
        /// --set 'closures.drag={type="stokes"}'
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// replace the scene's [closures.<family>] tables by those of FILE (a
        /// [closures] document such as the `fitted.toml` of `saltus diagnose --fit`;
        /// its [fit] table is metadata), before the --set overrides
        #[arg(long = "closures", value_name = "FILE")]
        closures: Option<PathBuf>,
    },
    /// Run a scene with its solver and write its outputs.
    #[command(after_help = EXIT_CODES)]
    Run {
        /// scene file
        scene: PathBuf,
        /// override one key (repeatable)
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// replace the scene's [closures.<family>] tables by those of FILE (a
        /// [closures] document such as the `fitted.toml` of `saltus diagnose --fit`;
        /// its [fit] table is metadata), before the --set overrides
        #[arg(long = "closures", value_name = "FILE")]
        closures: Option<PathBuf>,
        /// output folder (default: the --restart folder, else the scene's output.dir, else
        /// out/<scene name>); a folder where the run would write over its scene file or a
        /// reference file is refused
        #[arg(long)]
        out: Option<PathBuf>,
        /// continue the DEM run whose output folder (holding checkpoint.bin) is DIR, bit for
        /// bit as if it had not stopped, writing into DIR unless --out says otherwise; the
        /// scene must be the checkpoint's (the end time, step cap, threads and [output] may
        /// change)
        #[arg(long, value_name = "DIR")]
        restart: Option<PathBuf>,
        /// start from the final state of the finished run in DIR instead of from rest: an
        /// Eulerian scene from its profiles.csv; a DEM scene from the grains of its
        /// checkpoint.bin (a DEM run of the same grains, no deposition), or, when DIR is a
        /// two-fluid run, its grains deposited as from rest and then given the run's u_f and
        /// u_p (docs/lagrangian.md)
        #[arg(long, value_name = "DIR")]
        warm_start: Option<PathBuf>,
        /// stop the run after SECONDS of wall-clock time, writing its outputs (and a DEM
        /// checkpoint to continue from with --restart) as at its end; the summary's ending
        /// is `wall_clock`
        #[arg(long, value_name = "SECONDS")]
        max_wall: Option<f64>,
        /// wall-clock seconds between two progress lines when stderr is not a terminal
        #[arg(long, value_name = "SECONDS", default_value_t = saltus::runner::LOG_INTERVAL)]
        log_interval: f64,
        /// print nothing but errors: no progress, no warnings, no summary paragraph (the
        /// outputs are written as always; --json still prints the summary)
        #[arg(long, short)]
        quiet: bool,
        /// print the summary (summary.json) on stdout as JSON, and nothing else on stdout
        #[arg(long)]
        json: bool,
        /// run N seeds of a DEM scene in parallel (the scene's seed and the N - 1 after it),
        /// each into OUT/seed_<k>/, as one answer: with solver.lagrangian.target_error they
        /// stop together when the pooled transport rate has that relative error;
        /// OUT/seeds.json holds the pooled answer (docs/lagrangian.md)
        #[arg(long, value_name = "N")]
        seeds: Option<usize>,
    },
    /// Run several variants of one scene in parallel and compare them: a table of their
    /// summaries (comparison.csv) and their profiles on one figure (comparison.png).
    #[command(after_help = EXIT_CODES)]
    Compare {
        /// compare file: `base` scene, `[meta]`, `[[variant]]` tables with `name` and `set`
        file: PathBuf,
        /// override one key of every variant, before the variant's own (repeatable), e.g.
        /// --set solver.lagrangian.end_time=1
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// output folder (default: out/<meta.name>); each variant writes into a folder of
        /// its own inside it
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Fit closure constants jointly against a reference (seeds of a DEM run, run folders
    /// or the base scene's data), with their errors, correlations and profile likelihoods:
    /// calibrated.toml (for `saltus run --closures`), calibration.csv (every model run),
    /// calibration.json and figures. See docs/studies.md.
    Calibrate {
        /// calibrate file: `base` scene, `[[parameter]]` tables with `key` and `bounds`,
        /// `[reference]`, `[misfit]`, `[optimiser]`
        file: PathBuf,
        /// override one key of every model run, after the file's own `set` (repeatable)
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// output folder (default: out/<meta.name>)
        #[arg(long)]
        out: Option<PathBuf>,
        /// check the file, its base scene, keys and reference, and run nothing
        #[arg(long)]
        check: bool,
    },
    /// Run a study: a base scene over named axes of scene keys (their product or zip), the
    /// points in parallel, one folder each; a manifest (sweep.json), a table of the axes'
    /// values and every summary field (sweep.csv), and qs* against the swept number with
    /// the 3/2-law fit (sweep.png). See docs/studies.md.
    #[command(after_help = EXIT_CODES)]
    Sweep {
        /// sweep file: `base` scene, `[[axis]]` tables with `key` and `values` (or
        /// `linspace`/`logspace`), optional `combine`, `set`, `unset`, `[[point]]`
        file: PathBuf,
        /// override one key of every point, before the sweep's own (repeatable)
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// output folder (default: out/<meta.name>); each point writes into DIR/point_NNNN
        #[arg(long)]
        out: Option<PathBuf>,
        /// continue the sweep in the output folder: finished points are kept, interrupted
        /// DEM points continue from their checkpoints, the others run
        #[arg(long)]
        resume: bool,
        /// points run at once (default: the file's `jobs`, else the cores)
        #[arg(long, value_name = "N")]
        jobs: Option<usize>,
        /// run nothing: write one resolved scene per point (DIR/point_NNNN.toml) and the
        /// manifest, for a scheduler's job array (`saltus run DIR/point_NNNN.toml`)
        #[arg(long, value_name = "DIR", conflicts_with_all = ["collect", "resume", "out"])]
        emit: Option<PathBuf>,
        /// run nothing: gather the points run from `--emit DIR` into the table and figure
        #[arg(long, value_name = "DIR", conflicts_with_all = ["resume", "out"])]
        collect: Option<PathBuf>,
        /// print nothing but errors and the table's path
        #[arg(long, short)]
        quiet: bool,
    },
    /// Hold granular closures against the averaged fields of a run: mu and phi against I or
    /// K, g0 from the pressure, the dissipation, viscosity, heat flux and drag dissipation
    /// of kinetic theory; predicted and measured side by side (CSV, PNG) with their RMS
    /// difference (see docs/diagnostics.md).
    Diagnose {
        /// output folder of the run (holding profiles.csv and scene.toml)
        dir: PathBuf,
        /// closures to evaluate instead of the scene's: a TOML table (`type = "mu_i"`,
        /// `{type = "mu_k", alpha = 0.5}`), a [closures.granular] table, named tables of
        /// closures, or a file holding any of these (repeatable)
        #[arg(long = "closures", value_name = "TOML_OR_FILE")]
        closures: Vec<String>,
        /// output folder (default: DIR/diagnose)
        #[arg(long)]
        out: Option<PathBuf>,
        /// only cells with phi above this are used
        #[arg(long, default_value_t = saltus::diagnose::PHI_MIN)]
        phi_min: f64,
        /// fit the closures' parameters to the run (with standard errors) and write them
        /// as closure tables to OUT/fitted.toml, for `saltus run --closures`
        #[arg(long)]
        fit: bool,
        /// pool the cells of another run of the same scene (another seed) with DIR's in the
        /// comparisons and fits (repeatable)
        #[arg(long, value_name = "RUN_DIR")]
        pool: Vec<PathBuf>,
        /// fits only: lowest cell centre used (m)
        #[arg(long, value_name = "METRES", requires = "fit")]
        z_min: Option<f64>,
        /// fits only: highest cell centre used (m)
        #[arg(long, value_name = "METRES", requires = "fit")]
        z_max: Option<f64>,
    },
    /// Evaluate or plot closures on their own.
    Closure {
        #[command(subcommand)]
        command: ClosureCommand,
    },
}

#[derive(Subcommand)]
enum ClosureCommand {
    /// Evaluate one closure on the rows of a CSV whose header names its inputs; write the
    /// inputs followed by the outputs.
    #[command(after_help = EvalFamily::help())]
    Eval {
        /// closure family
        #[arg(long, value_enum)]
        family: EvalFamily,
        /// the model's TOML table, e.g. 'type = "haider_levenspiel"' or
        /// '{type = "richardson_zaki", exponent = 4.65}'
        #[arg(long)]
        model: String,
        /// input CSV (`-` for standard input)
        #[arg(long)]
        input: PathBuf,
        /// output CSV (standard output when absent)
        #[arg(long)]
        output: Option<PathBuf>,
        /// seed of the stochastic draws (fluctuation family), one stream per row
        #[arg(long, default_value_t = 0)]
        seed: u64,
    },
    /// Run the generic property checks on one closure (ours or a linked user's): every
    /// parameter documented, TOML round trip, finite output over the parameter and input
    /// ranges, batch = scalar, the model's declared limits. Exit 0 when all pass, 1 when a
    /// check fails, 2 on bad input.
    Check {
        /// closure family (drag, hindrance, viscosity, granular, turbulence, fluctuation, wall_friction)
        #[arg(long)]
        family: String,
        /// the model's TOML table, e.g. 'type = "dallavalle"' or '{type = "richardson_zaki", exponent = 4.65}'
        #[arg(long)]
        model: String,
        /// random cases per property check
        #[arg(long, default_value_t = 256)]
        cases: u32,
    },
    /// Draw closure curves side by side (PNG + CSV) from a comparison file such as
    /// cases/closures/drag.toml.
    Plot {
        /// comparison file
        file: PathBuf,
        /// output folder (default out/closures/<file stem>)
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

/// Exit codes of `run` and `compare`, in their help.
const EXIT_CODES: &str = "Exit codes: 0 the run ended (steady, end_time or max_steps), 2 bad input or outputs that \
cannot be written (or a failed compare variant), 3 the run stopped unstable (its last good state is written), 130 \
interrupted by Ctrl-C, SIGINT or SIGTERM (the state so far is written, with a DEM checkpoint; a second interrupt quits \
at once).";

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
