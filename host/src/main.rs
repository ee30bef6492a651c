//! The `gsph` command: see `gsph --help`.
fn main() {
    std::process::exit(gsph::cli::main_with_args(std::env::args_os()));
}
