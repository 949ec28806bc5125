//! The glint binary: parse the command line, run it, print the error chain and exit non-zero on failure.

fn main() {
    if let Err(e) = glint::cli::main() {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
