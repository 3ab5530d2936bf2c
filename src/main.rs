//! The `skelfit` command-line tool: parse, validate, call the library, write explicit outputs.

mod cli;

fn main() -> std::process::ExitCode {
    cli::main()
}
