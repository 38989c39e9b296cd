//! The command line's arguments: every command and option of `saltus`, with the help
//! text they print (clap), read by the program in `src/main.rs`.
// the doc comments are the help text `saltus --help` prints as written: `[closures]` and
// `[fit]` there are TOML tables and `<family>` a placeholder, not links or HTML
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

use std::path::PathBuf;

use clap::{Parser, Subcommand};
use saltus::eval::EvalFamily;

#[derive(Parser)]
#[command(name = "saltus", version, about = "Closure models and solvers for two-phase sediment transport")]
pub struct Cli {
    /// the command
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
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
pub enum ClosureCommand {
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
pub const EXIT_CODES: &str =
    "Exit codes: 0 the run ended (steady, end_time or max_steps), 2 bad input or outputs that \
cannot be written (or a failed compare variant), 3 the run stopped unstable (its last good state is written), 130 \
interrupted by Ctrl-C, SIGINT or SIGTERM (the state so far is written, with a DEM checkpoint; a second interrupt quits \
at once).";
