//! `vkocean`: parses the command line, runs a frontend, and maps the outcome to an exit code:
//! 0 ok, 1 runtime error, 2 bad usage, 3 validation reported warnings or errors.
//! 128 + N stopped by signal N (130 Ctrl-C, 143 SIGTERM). Every failure is one line on stderr;
//! no panics or backtraces reach the user.

use std::process::ExitCode;

use vkocean::bench;
use vkocean::cli::{BenchCommand, Cli, Command, UsageError};
use vkocean::frontend;
use vkocean::gpu::{context, GpuError};

fn main() -> ExitCode {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"))
        .format_timestamp(None)
        .format_target(false)
        .init();
    // A panic is reported by `main` as one line (below), never by the default hook.
    std::panic::set_hook(Box::new(|info| {
        let message = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".to_string());
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        let mut slot = PANIC.lock().unwrap_or_else(|p| p.into_inner());
        slot.get_or_insert(format!("{message}{at}"));
    }));
    if let Err(e) = vkocean::interrupt::install() {
        eprintln!("vkocean: cannot install the signal handlers: {e}");
        return ExitCode::from(1);
    }
    let user_args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    match std::panic::catch_unwind(|| run(user_args)) {
        Ok(code) => code,
        Err(_) => {
            let message = PANIC
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .take()
                .unwrap_or_default();
            eprintln!("vkocean: {}", panic_line(&message).replace('\n', " "));
            ExitCode::from(1)
        }
    }
}

/// The first panic's message and place, kept by the panic hook for `main`.
static PANIC: std::sync::Mutex<Option<String>> = std::sync::Mutex::new(None);

/// A panic as the user's one line. winit panics when the X server goes away (an `unwrap` on a
/// lost connection: a killed window, a closed Xvfb): the same line as Xlib's I/O error handler
/// prints (platform/x11.rs), whichever of the two notices first, winit's place in the log
/// (`RUST_LOG=debug`); anything else is a bug of ours.
fn panic_line(message: &str) -> String {
    if message.contains("Connection(") || message.contains("X11") || message.contains("xlib") {
        log::debug!("the X connection's loss as winit met it: {message}");
        "lost the connection to the X server (the window was killed or the display closed)".into()
    } else {
        format!("internal error (a bug; please report it): {message}")
    }
}

// Long: the command line's outcomes in the order they are decided (config, parse, list, the
// run, the validation summary); each arm maps one outcome to its exit code.
fn run(user_args: Vec<std::ffi::OsString>) -> ExitCode {
    let args = match vkocean::cli::with_config(user_args.clone()) {
        Ok(args) => args,
        Err(e) => return fail(&e.into()),
    };
    let parsed = vkocean::cli::command()
        .try_get_matches_from(args)
        .and_then(|m| <Cli as clap::FromArgMatches>::from_arg_matches(&m));
    let mut cli = match parsed {
        Ok(cli) => cli,
        Err(e) => return clap_failure(&e),
    };

    if let Err(e) = vkocean::ocean::fft::check_env() {
        return fail(&UsageError(e).into());
    }

    if cli.list_gpus {
        let outcome = match context::list_devices() {
            Ok(devices) if devices.is_empty() => Err(GpuError::NoDevice.into()),
            Ok(devices) => {
                for d in devices {
                    vkocean::outln!("{d}");
                }
                vkocean::output::stdout_status()
            }
            Err(e) => Err(e.into()),
        };
        return match outcome {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => fail(&e),
        };
    }

    // Without --quality the level follows the device the run will use (bench fft has none),
    // as does the upscale without --upscale.
    let fft_bench = matches!(cli.command, Some(Command::Bench(BenchCommand::Fft(_))));
    if fft_bench {
        if let Err(e) = vkocean::cli::check_bench_fft_flags(&user_args) {
            return fail(&e.into());
        }
    }
    if (cli.quality.is_none() || cli.upscale.is_none()) && !fft_bench {
        cli.cpu_device = context::chosen_device_is_cpu(cli.gpu, cli.device_needs());
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
    match outcome.and_then(|o| vkocean::output::stdout_status().map(|_| o)) {
        Ok(outcome) => {
            if cli.validation_on() {
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

/// clap's verdict: help and version are printed whole (exit 0); an error is one line (exit 2).
fn clap_failure(e: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand | ErrorKind::MissingSubcommand => {
            eprintln!(
                "vkocean: bench needs a subcommand: fft, frames or gerstner (see vkocean bench --help)"
            );
            return ExitCode::from(2);
        }
        _ => {}
    }
    // clap's first line ("error: invalid value ... for '--frames <N>': ...") is the message; the
    // list of possible values, when clap gives one, joins it.
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
    ExitCode::from(2)
}

/// Prints the error (with its causes) on one line; exit 2 for usage errors, 1 otherwise.
fn fail(e: &anyhow::Error) -> ExitCode {
    if let Some(interrupted) = e.downcast_ref::<vkocean::interrupt::Interrupted>() {
        eprintln!("vkocean: {interrupted}");
        return ExitCode::from(interrupted.exit_code());
    }
    let usage = e.downcast_ref::<UsageError>().is_some()
        || e.downcast_ref::<vkocean::input::InputError>().is_some()
        || e.downcast_ref::<GpuError>().is_some_and(GpuError::is_usage);
    let message: Vec<String> = e.chain().map(|c| c.to_string()).collect();
    eprintln!("vkocean: {}", message.join(": ").replace('\n', " "));
    ExitCode::from(if usage { 2 } else { 1 })
}
