//! `vkocean-plot`: PNG charts of `vkocean bench frames` output. See `vkocean-plot --help`.

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Result<Vec<String>, _> = std::env::args_os()
        .skip(1)
        .map(|a| a.into_string())
        .collect();
    let result = match args {
        Ok(args) => vkocean_plot::run(&args),
        Err(arg) => Err(vkocean_plot::Error::Usage(format!(
            "argument {arg:?} is not valid UTF-8"
        ))),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("vkocean-plot: {}", e.message());
            ExitCode::from(e.exit_code())
        }
    }
}
