//! Issue 19's cases: signals (Ctrl-C, SIGTERM) stop a run with its exit code, one line and no
//! file; hostile input files (PNG headers claiming huge pictures, FIFOs, directories) are one
//! line before any large allocation; memory under a `ulimit -v` stays within the picture plus a
//! fixed margin; misleading messages name the real problem.

mod common;

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Command, Output, Stdio};

use common::{assert_one_line, bin, entries, png_header_only, run, run_with_env, scratch, stderr};

/// Spawns vkocean in `dir`, waits until it printed `frames` lines on stdout (`--stats`: one per
/// finished frame), sends `signal` (kill's name, e.g. "INT"), and returns its output.
fn signal_after_frames(dir: &Path, args: &[&str], frames: usize, signal: &str) -> Output {
    let mut child = Command::new(bin())
        .args(args)
        .current_dir(dir)
        .env_remove("RUST_LOG")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("vkocean runs");
    let mut stdout = BufReader::new(child.stdout.take().expect("piped"));
    let mut line = String::new();
    for i in 0..frames {
        line.clear();
        let n = stdout.read_line(&mut line).expect("stdout readable");
        assert!(n > 0, "vkocean ended before frame {}", i + 1);
    }
    // bash's own kill: Debian 13's bare root (tools/debian13) has no kill(1).
    let status = Command::new("bash")
        .args(["-c", &format!("kill -{signal} {}", child.id())])
        .status()
        .expect("bash runs");
    assert!(status.success());
    let mut rest = Vec::new();
    let _ = stdout.read_to_end(&mut rest);
    child.wait_with_output().expect("vkocean ends")
}

/// Ctrl-C while the last frame is read back and its 4096x4096 PNG encoded and written: exit
/// 130, one line, and the directory holds nothing (no `.shot.png.PID.partial`).
#[test]
fn ctrl_c_while_the_screenshot_is_written_leaves_nothing() {
    let dir = scratch("robust-sigint-png");
    let args = [
        "--headless",
        "--stats",
        "--quality",
        "low",
        "--frames",
        "2",
        "--size",
        "4096x4096",
        "--screenshot",
        "shot.png",
    ];
    let out = signal_after_frames(&dir, &args, 2, "INT");
    // Two 4096² frames take over 5 s on a loaded machine: a progress line may come first.
    assert!(common::is_progress("vkocean: frame 2/2 (5.3 s)"));
    assert!(!common::is_progress(
        "vkocean: stopped by SIGINT (Ctrl-C); no output was written"
    ));
    assert_one_line(&out, 130, "stopped by SIGINT", "Ctrl-C during the PNG");
    assert_eq!(entries(&dir), Vec::<String>::new());
    let _ = std::fs::remove_dir_all(&dir);
}

/// SIGTERM during a `--dump` run (after its first frame): exit 143, no dump directory, no
/// screenshot, no temporary.
#[test]
fn sigterm_during_a_dump_run_leaves_no_directory() {
    let dir = scratch("robust-sigterm-dump");
    let args = [
        "--headless",
        "--stats",
        "--quality",
        "low",
        "--frames",
        "100000",
        "--size",
        "64x64",
        "--dump",
        "dump",
        "--screenshot",
        "shot.png",
        "--profile",
        "p.json",
    ];
    let out = signal_after_frames(&dir, &args, 1, "TERM");
    assert_one_line(&out, 143, "stopped by SIGTERM", "SIGTERM during --dump");
    assert_eq!(entries(&dir), Vec::<String>::new());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A valid PNG (16x16 RGBA) with one byte of its picture data flipped: the header reads, the
/// decoding fails (CRC).
fn corrupt_png(path: &Path) {
    let texels = vec![90u8; 16 * 16 * 4];
    image::save_buffer(path, &texels, 16, 16, image::ColorType::Rgba8).unwrap();
    let mut bytes = std::fs::read(path).unwrap();
    let idat = bytes.windows(4).position(|w| w == b"IDAT").unwrap();
    bytes[idat + 6] ^= 0x55;
    std::fs::write(path, bytes).unwrap();
}

/// Six faces in `dir` made by `face`.
fn skybox(dir: &Path, face: impl Fn(&Path)) {
    std::fs::create_dir_all(dir).unwrap();
    for name in ["px", "nx", "py", "ny", "pz", "nz"] {
        face(&dir.join(format!("{name}.png")));
    }
}

/// `--dump DIR` in a run that fails after the start (a skybox face that does not decode): no
/// DIR is created, nothing else is left.
#[test]
fn a_run_that_fails_later_leaves_no_dump_directory() {
    let dir = scratch("robust-dump-fail");
    let sky = dir.join("sky");
    skybox(&sky, corrupt_png);
    let dump = dir.join("dump");
    let out = run(&[
        "--headless",
        "--size",
        "32x32",
        "--skybox",
        sky.to_str().unwrap(),
        "--dump",
        dump.to_str().unwrap(),
    ]);
    assert_one_line(&out, 2, "--skybox", "corrupt skybox with --dump");
    assert_eq!(entries(&dir), vec!["sky".to_string()]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// PNG headers claiming pictures larger than the device's largest image are refused before a
/// byte is decoded (the old loader decoded six 16385² faces, 8.6 GB, and aborted): exit 2, one
/// line, under a 1.5 GiB address-space limit.
#[test]
fn oversized_png_headers_are_refused_before_decoding() {
    let dir = scratch("robust-huge-png");
    let sky = dir.join("sky");
    skybox(&sky, |p| {
        std::fs::write(p, png_header_only(16385, 16385)).unwrap()
    });
    let dudv = dir.join("dudv.png");
    std::fs::write(&dudv, png_header_only(20000, 20000)).unwrap();
    let limited = |flag: &str, path: &Path| {
        Command::new("bash")
            .args([
                "-c",
                "ulimit -v 1572864; exec \"$0\" --headless --size 32x32 \"$1\" \"$2\"",
                bin(),
                flag,
                path.to_str().unwrap(),
            ])
            .output()
            .unwrap()
    };
    let out = limited("--skybox", &sky);
    assert_one_line(&out, 2, "16385x16385 is larger than", "16385² skybox");
    let out = limited("--dudv", &dudv);
    assert_one_line(&out, 2, "20000x20000 is larger than", "20000² dudv");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Address-space limit (KiB) a plain run needs, to 32 MiB: the smallest of 512 MiB + k·32 MiB
/// under which `args` succeed.
fn needed_kib(args: &[&str]) -> u64 {
    let ok = |kib: u64| {
        let mut cmd = Command::new("bash");
        cmd.env("MALLOC_ARENA_MAX", "1");
        cmd.args(["-c", &format!("ulimit -v {kib}; exec \"$0\" \"$@\""), bin()]);
        cmd.args(args).output().unwrap().status.success()
    };
    let (mut lo, mut hi) = (512 * 1024, 3 * 1024 * 1024);
    assert!(ok(hi), "a plain run fails under {hi} KiB");
    while hi - lo > 32 * 1024 {
        let mid = (lo + hi) / 2;
        if ok(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// Memory is bounded by the picture: a 4096² grey DU/DV map (64 MiB as RGBA8 on the device,
/// 64 MiB of staging) runs under the limit a run without it needs plus 2 × 64 MiB plus the
/// stated margin (`vkocean::input::PNG_DECODER_BYTES`, 64 MiB, and 32 MiB of search step).
/// Hostile headers (16384² faces with no data: 6 GiB each for the cube and its staging) under
/// the plain limit + 512 MiB fail with one line (exit 1: out of memory), no abort. glibc's
/// allocation arenas (64 MiB of address space each, made when threads contend) would make the
/// need vary from run to run: every run here has MALLOC_ARENA_MAX=1.
#[test]
fn memory_under_hostile_input_is_the_picture_plus_a_fixed_margin() {
    let dir = scratch("robust-memory");
    let base = ["--headless", "--size", "64x64", "--quality", "low"];
    let plain = needed_kib(&base);
    let dudv = dir.join("grey.png");
    let side = 4096u32;
    let grey: Vec<u8> = (0..side * side).map(|i| (i % 251) as u8).collect();
    image::save_buffer(&dudv, &grey, side, side, image::ColorType::L8).unwrap();
    let picture_kib = (side as u64 * side as u64 * 4) / 1024;
    let margin_kib = (vkocean::input::PNG_DECODER_BYTES as u64) / 1024 + 32 * 1024;
    let limit = plain + 2 * picture_kib + margin_kib;
    eprintln!("plain run: {plain} KiB; with the 4096² map: limit {limit} KiB");
    let script = format!("ulimit -v {limit}; exec \"$0\" \"$@\"");
    let out = Command::new("bash")
        .env("MALLOC_ARENA_MAX", "1")
        .args(["-c", &script, bin()])
        .args(base)
        .args(["--dudv", dudv.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "a 4096² DU/DV map under {limit} KiB (plain run: {plain} KiB): {}",
        stderr(&out)
    );

    let sky = dir.join("sky");
    skybox(&sky, |p| {
        std::fs::write(p, png_header_only(16384, 16384)).unwrap()
    });
    // The hostile faces under the plain limit plus 512 MiB: far below their 12 GiB.
    let script = format!("ulimit -v {}; exec \"$0\" \"$@\"", plain + 512 * 1024);
    let out = Command::new("bash")
        .env("MALLOC_ARENA_MAX", "1")
        .args(["-c", &script, bin()])
        .args(base)
        .args(["--skybox", sky.to_str().unwrap()])
        .output()
        .unwrap();
    let err = stderr(&out);
    assert!(
        matches!(out.status.code(), Some(1) | Some(2)),
        "16384² faces without data: {err}"
    );
    assert_one_line(&out, out.status.code().unwrap(), "skybox", "16384² faces");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A FIFO as --config (it would block forever), a directory, a device: one line, exit 2, at
/// once (the run is killed after 20 s if it hangs: SIGTERM, which vkocean catches, then SIGKILL).
#[test]
fn config_must_be_a_regular_file() {
    let dir = scratch("robust-fifo");
    let fifo = dir.join("settings.toml");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let out = Command::new("timeout")
        .args([
            "-k",
            "5",
            "20",
            bin(),
            "--headless",
            "--config",
            fifo.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_one_line(&out, 2, "not a regular file", "FIFO --config");
    let as_dir = dir.join("d.toml");
    std::fs::create_dir(&as_dir).unwrap();
    let out = run(&["--headless", "--config", as_dir.to_str().unwrap()]);
    assert_one_line(&out, 2, "is a directory", "directory --config");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Inputs whose old messages misled (or that were silently accepted): each is one line naming
/// the real problem, with the exit code of its kind.
#[test]
fn misleading_inputs_get_messages_that_name_the_problem() {
    let dir = scratch("robust-messages");
    let d = |name: &str| dir.join(name).to_str().unwrap().to_string();
    std::fs::create_dir_all(dir.join("adir.png")).unwrap();
    // A skybox whose nz.png is a directory; one with a wrong-size face; one missing a face.
    skybox(&dir.join("sky-dir"), |p| {
        std::fs::write(p, png_header_only(8, 8)).unwrap()
    });
    std::fs::remove_file(dir.join("sky-dir/nz.png")).unwrap();
    std::fs::create_dir(dir.join("sky-dir/nz.png")).unwrap();
    skybox(&dir.join("sky-size"), |p| {
        std::fs::write(p, png_header_only(8, 8)).unwrap()
    });
    std::fs::write(dir.join("sky-size/py.png"), png_header_only(16, 16)).unwrap();
    skybox(&dir.join("sky-missing"), |p| {
        std::fs::write(p, png_header_only(8, 8)).unwrap()
    });
    std::fs::remove_file(dir.join("sky-missing/ny.png")).unwrap();
    std::fs::write(dir.join("face.png"), png_header_only(8, 8)).unwrap();
    std::fs::write(dir.join("a.toml"), "wind-speed = 3\n").unwrap();
    std::fs::write(dir.join("b.toml"), "fetch = 30\n").unwrap();
    std::fs::write(dir.join("big-k.csv"), "1e30,0,1,0\n").unwrap();
    std::fs::write(dir.join("steep.csv"), "0.3,0.4,0.001,0,50\n").unwrap();
    std::fs::write(
        dir.join("icd.json"),
        "{ \"file_format_version\": \"1.0.0\", \"ICD\": { \"library_path\": ",
    )
    .unwrap();
    let g = |file: &str| {
        vec!["--headless", "--waves", "gerstner", "--gerstner-waves"]
            .into_iter()
            .map(String::from)
            .chain([d(file)])
            .collect::<Vec<_>>()
    };
    let cases: Vec<Case> = vec![
        (
            s(&["--headless", "--gpu", "-1"]),
            vec![],
            2,
            "'--gpu <N>': must be a whole number from 0 to 255",
        ),
        (
            s(&["--headless", "--size", "32x32"]),
            vec![("VK_ICD_FILENAMES", d("icd.json"))],
            1,
            // The loader of Debian 12 fails on the manifest, Debian 13's skips it.
            "JSON naming an installed driver",
        ),
        (
            s(&["--headless", "--dudv", &d("adir.png")]),
            vec![],
            2,
            "is a directory, not a file",
        ),
        (
            s(&["--headless", "--skybox", &d("sky-dir")]),
            vec![],
            2,
            "nz.png: is a directory, not a file",
        ),
        (
            s(&["--headless", "--skybox", &d("face.png")]),
            vec![],
            2,
            "not a directory (it takes a directory of six faces",
        ),
        (
            s(&["--headless", "--skybox", &d("sky-size")]),
            vec![],
            2,
            "the six faces must be square and the same size",
        ),
        (
            s(&["--headless", "--skybox", &d("sky-missing")]),
            vec![],
            2,
            "missing face",
        ),
        (
            s(&["bench", "fft", "--wind-speed", "3"]),
            vec![],
            2,
            "--wind-speed does not apply to bench fft",
        ),
        (
            s(&["--preset", "storm", "bench", "fft"]),
            vec![],
            2,
            "--preset does not apply to bench fft",
        ),
        (
            s(&["bench"]),
            vec![],
            2,
            "bench needs a subcommand: fft, frames or gerstner",
        ),
        (
            s(&[
                "--headless",
                "--config",
                &d("a.toml"),
                "--config",
                &d("b.toml"),
            ]),
            vec![],
            2,
            "--config given more than once",
        ),
        (
            s(&["--headless"]),
            vec![("VKOCEAN_FFT_KERNEL", "bogus".into())],
            2,
            "VKOCEAN_FFT_KERNEL=bogus: must be shared or registers",
        ),
        (
            s(&["--headless"]),
            vec![("VKOCEAN_FFT_THREADS", "0".into())],
            2,
            "VKOCEAN_FFT_THREADS=0: must be a power of two",
        ),
        (
            s(&["--headless"]),
            vec![("VKOCEAN_FFT_THREADS", "3".into())],
            2,
            "VKOCEAN_FFT_THREADS=3",
        ),
        (
            s(&["--headless"]),
            vec![("VKOCEAN_FFT_THREADS", "100000".into())],
            2,
            "VKOCEAN_FFT_THREADS=100000",
        ),
        (
            g("big-k.csv"),
            vec![],
            2,
            "the wave number |(kx, kz)| = 1.000e30 rad/m must be from",
        ),
        (
            g("steep.csv"),
            vec![],
            2,
            "the steepness Q must be from 0 to 10",
        ),
    ];
    for (args, env, code, needle) in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let env: Vec<(&str, &str)> = env.iter().map(|(k, v)| (*k, v.as_str())).collect();
        let out = run_with_env(&args, &env);
        assert_one_line(&out, *code, needle, &format!("{args:?} {env:?}"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Arguments, environment, exit code, what the one line says.
type Case = (Vec<String>, Vec<(&'static str, String)>, i32, &'static str);

fn s(args: &[&str]) -> Vec<String> {
    args.iter().map(|a| a.to_string()).collect()
}

/// stdout on a full device: the write error is the run's error (exit 1, one line), for
/// `--list-gpus` and for `--stats`.
#[test]
fn a_failed_stdout_write_fails_the_run() {
    for args in [
        &["--list-gpus"][..],
        &["--headless", "--size", "32x32", "--stats"][..],
    ] {
        let out = Command::new(bin())
            .args(args)
            .stdout(std::fs::File::create("/dev/full").unwrap())
            .output()
            .unwrap();
        assert_one_line(
            &out,
            1,
            "cannot write to stdout",
            &format!("{args:?} > /dev/full"),
        );
    }
}

/// `--help` states the ranges README states; `bench fft --help` lists only the flags it takes.
#[test]
fn help_states_ranges_and_bench_fft_help_lists_its_own_flags() {
    let out = run(&["--help"]);
    let help = String::from_utf8_lossy(&out.stdout);
    for range in [
        "(-360 to 360)",
        "(s, 0 to 1e6)",
        "y >= -60",
        "0 < DT <= 10",
        "0 to 255",
    ] {
        assert!(help.contains(range), "--help lacks {range:?}");
    }
    let out = run(&["bench", "fft", "--help"]);
    let help = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0));
    for flag in [
        "--sizes",
        "--batch",
        "--runs",
        "--json",
        "--gpu",
        "--validation",
    ] {
        assert!(help.contains(flag), "bench fft --help lacks {flag}: {help}");
    }
    for flag in ["--wind-speed", "--preset", "--camera", "--quality"] {
        assert!(
            !help.contains(flag),
            "bench fft --help lists {flag}: {help}"
        );
    }
}
