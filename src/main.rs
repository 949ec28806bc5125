//! The glint binary: parse the command line, run it, print the error chain and exit non-zero on failure.

use clap::Parser;

fn main() {
    let cli = glint::cli::Cli::parse();
    if let Err(e) = glint::cli::run(cli) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
