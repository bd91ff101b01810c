//! `vkocean`: parses the command line, runs a frontend, and maps the outcome to an exit code:
//! 0 ok, 1 runtime error, 2 bad usage, 3 validation reported warnings or errors.
//! Every failure is one line on stderr; no panics or backtraces reach the user.

use std::process::ExitCode;

use clap::Parser;
use vkocean::bench;
use vkocean::cli::{BenchCommand, Cli, Command, UsageError};
use vkocean::frontend;
use vkocean::gpu::{context, GpuError};

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"))
        .format_timestamp(None)
        .format_target(false)
        .init();

    let args = match vkocean::cli::with_config(std::env::args_os().collect()) {
        Ok(args) => args,
        Err(e) => return fail(&e.into()),
    };
    let mut cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            // clap's first line ("error: invalid value ... for '--frames <N>': ...") is the
            // message; the list of possible values, when clap gives one, joins it.
            let text = e.to_string();
            let first = text
                .lines()
                .next()
                .unwrap_or("invalid arguments")
                .trim_start_matches("error: ");
            match text.lines().find(|l| l.contains("[possible values:")) {
                Some(values) => eprintln!("vkocean: {first} {} (see --help)", values.trim()),
                None => eprintln!("vkocean: {first} (see --help)"),
            }
            return ExitCode::from(2);
        }
    };

    if cli.list_gpus {
        return match context::list_devices() {
            Ok(devices) if devices.is_empty() => {
                eprintln!("vkocean: {}", GpuError::NoDevice);
                ExitCode::from(1)
            }
            Ok(devices) => {
                for d in devices {
                    vkocean::outln!("{d}");
                }
                ExitCode::SUCCESS
            }
            Err(e) => fail(&e.into()),
        };
    }

    // Without --quality the level follows the device the run will use (bench fft has none).
    let fft_bench = matches!(cli.command, Some(Command::Bench(BenchCommand::Fft(_))));
    if cli.quality.is_none() && !fft_bench {
        cli.cpu_device = context::chosen_device_is_cpu(cli.gpu);
    }

    let outcome = match &cli.command {
        Some(Command::Bench(BenchCommand::Fft(args))) => match args.settings(&cli) {
            Ok(settings) => bench::fft(&settings),
            Err(e) => return fail(&e.into()),
        },
        Some(Command::Bench(BenchCommand::Frames(args))) => match args.settings(&cli) {
            Ok(settings) => bench::frames::frames(&settings),
            Err(e) => return fail(&e.into()),
        },
        Some(Command::Bench(BenchCommand::Gerstner(args))) => match args.settings(&cli) {
            Ok(settings) => bench::gerstner::gerstner(&settings),
            Err(e) => return fail(&e.into()),
        },
        None => match cli.settings() {
            Ok(settings) => frontend::run(&settings),
            Err(e) => return fail(&e.into()),
        },
    };
    match outcome {
        Ok(outcome) => {
            if cli.validation {
                eprintln!("{}", outcome.counters.summary());
                if outcome.counters.warnings() + outcome.counters.errors() > 0 {
                    return ExitCode::from(3);
                }
            }
            ExitCode::SUCCESS
        }
        Err(e) => fail(&e),
    }
}

/// Prints the error (with its causes) on one line; exit 2 for usage errors, 1 otherwise.
fn fail(e: &anyhow::Error) -> ExitCode {
    let usage = e.downcast_ref::<UsageError>().is_some()
        || e.downcast_ref::<GpuError>().is_some_and(GpuError::is_usage);
    let message: Vec<String> = e.chain().map(|c| c.to_string()).collect();
    eprintln!("vkocean: {}", message.join(": ").replace('\n', " "));
    ExitCode::from(if usage { 2 } else { 1 })
}
