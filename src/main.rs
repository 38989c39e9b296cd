//! `saltus`: closure models and solvers for two-phase sediment transport.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::{Parser, Subcommand};
use saltus::eval::{evaluate, parse_model, EvalFamily};
use saltus::table::Table;
use saltus_core::closure::Family;
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
        /// only this family (drag, hindrance, viscosity, granular, turbulence, fluctuation)
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
    },
    /// Run a scene with its solver and write its outputs.
    Run {
        /// scene file
        scene: PathBuf,
        /// override one key (repeatable)
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// output folder (default: the scene's output.dir, else out/<scene name>)
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Run several variants of one scene in parallel and compare them: a table of their
    /// summaries (comparison.csv) and their profiles on one figure (comparison.png).
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
        /// closure family (drag, hindrance, viscosity, granular, turbulence, fluctuation)
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
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            saltus::errln!("error: {e:#}");
            // a run stopped early wrote its outputs and says how it stopped; anything
            // else is a failure before or around the work
            // a closure check that ran and found a failing check: 1, as a test runner would
            if e.downcast_ref::<saltus::check::ChecksFailed>().is_some() {
                return ExitCode::from(1);
            }
            ExitCode::from(e.downcast_ref::<saltus::runner::Stopped>().map_or(2, |s| s.code))
        }
    }
}

fn parse_family(name: &str) -> anyhow::Result<Family> {
    Family::from_key(name).with_context(|| {
        format!(
            "unknown family `{name}`; known: {}",
            Family::ALL.iter().map(|f| f.key()).collect::<Vec<_>>().join(", ")
        )
    })
}

/// A scene checked whole: the schema at load, then what its solver needs to start (the
/// set-up `run` does before any work, so `check` and `run` refuse the same scenes).
fn load(scene: &std::path::Path, set: &[String]) -> anyhow::Result<Scene> {
    let s = Scene::from_file_with(scene, set)?;
    saltus_solvers::validate(&s)?;
    Ok(s)
}

fn run(cli: Cli) -> anyhow::Result<()> {
    saltus::ensure_registry()?;
    match cli.command {
        Command::Models { family, json } => {
            let family = family.as_deref().map(parse_family).transpose()?;
            if json {
                outln!("{}", serde_json::to_string_pretty(&saltus::listing::json(family))?);
            } else {
                out!("{}", saltus::listing::text(family));
            }
        }
        Command::Check { scene, set } => {
            let s = load(&scene, &set)?;
            outln!("# {} resolved: every default filled in, ranges and closure needs checked", scene.display());
            out!("{}", s.to_toml()?);
        }
        Command::Run { scene, set, out } => {
            // the solver's set-up inside `run` is `validate` (`resolve`), refused before
            // any output is written: loading the schema is all that is left to do here
            let s = Scene::from_file_with(&scene, &set)?;
            let out = out.unwrap_or_else(|| saltus::runner::default_out(&s));
            let bar = saltus::runner::progress_bar(std::io::stderr().is_terminal());
            if let Err(e) = saltus::runner::catch_interrupt() {
                saltus::errln!("warning: {e:#}; Ctrl-C ends the run without writing its outputs");
            }
            let outcome = saltus::runner::run_scene(&s, &out, &bar);
            for w in &outcome.warnings {
                saltus::errln!("warning: {w}");
            }
            let Some(report) = &outcome.report else {
                anyhow::bail!("{}", outcome.error.unwrap_or_else(|| "the run failed".into()));
            };
            // the last state is reported whatever the ending; an early stop then sets
            // the exit code (see `saltus::runner::Stopped`)
            outln!("{report}");
            outln!("outputs: {}", out.display());
            if let Some(png) = &outcome.figure {
                outln!("figure:  {}", png.display());
            }
            if let Some(stopped) = outcome.stopped(&s, &out) {
                return Err(stopped.into());
            }
        }
        Command::Compare { file, set, out } => {
            let cmp = saltus::compare::load(&file, &set)?;
            let out = out.unwrap_or_else(|| saltus::compare::default_out(&cmp));
            let report = saltus::compare::run(&cmp, &out, std::io::stderr().is_terminal())?;
            for w in &report.warnings {
                saltus::errln!("warning: {w}");
            }
            out!("{}", report.text_table());
            outln!("outputs: {}", out.display());
            outln!("table:   {}", report.table.display());
            if let Some(png) = &report.figure {
                outln!("figure:  {}", png.display());
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
                let family = parse_family(&family)?;
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
