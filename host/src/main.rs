//! The `gsph` command: see `gsph --help` and [`gsph::cli::run`].
fn main() {
    std::process::exit(gsph::cli::run(std::env::args_os()));
}
