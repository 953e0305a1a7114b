//! `ocean-fft`: bake an FFT ocean into texture sequences. `ocean-fft --help` for the
//! commands, `ocean-fft bake --help` for the options; exit codes are listed there.

use clap::Parser;

fn main() {
    let cli = ocean_fft_cli::args::Cli::parse(); // exits with 2 (and a message) on bad usage
    if let Err(e) = ocean_fft_cli::run(cli) {
        eprintln!("error: {e}");
        std::process::exit(e.kind.exit_code());
    }
}
