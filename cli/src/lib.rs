//! The `ocean-fft` command-line tool: bakes an ocean-fft sea into OpenEXR or 16-bit PNG
//! texture sequences with a JSON sidecar, for tools, engines and render farms. The binary
//! is `src/main.rs`; this library holds everything, so that the tests drive it directly.
//! The user documentation is the repository's `docs/guide/baking.md`.

pub mod args;
pub mod bake;
pub mod describe;
pub mod encode;
pub mod error;
pub mod frames;
pub mod progress;
pub mod setup;
pub mod sim;
pub mod warnings;

use args::{Cli, Command};
use error::CliError;

/// Runs a parsed command line, printing to stdout and stderr.
///
/// # Errors
/// A [`CliError`] whose kind gives the exit code.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Bake(args) => {
            let mut progress = progress::for_stdout();
            let report = bake::bake(&args, progress.as_mut())?;
            eprintln!("{}", bake::summary(&report));
            Ok(())
        }
        Command::Info(args) => {
            let sea = setup::build(&args.sea)?;
            let mut simulator = sim::Simulator::new(&sea)?;
            for warning in warnings::check(&sea, simulator.ocean()) {
                eprintln!("{warning}");
            }
            if sea.looping.is_some() && args.measure_foam {
                // The loop's foam pre-roll, to report how it converged.
                simulator.advance_to(0)?;
            }
            print!(
                "{}",
                describe::info(&sea, simulator.ocean(), simulator.convergence())
            );
            Ok(())
        }
    }
}
