//! A deterministic fuzz pass over the command line, `--config` files and every input file kind
//! (`--dudv`, `--skybox`, `--gerstner-waves`): 180 generated cases, each run in an empty
//! directory of its own. Every case must end within 60 s with exit 0, 1, 2 or 3; a failure is at
//! most one stderr line, starting `vkocean:`; no output mentions a panic or RUST_BACKTRACE; and
//! a failed run leaves its directory empty (no screenshot, profile, dump or temporary file).

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;

use common::{bin, entries, png_header_only, scratch};

/// xorshift64*: the same cases on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[(self.next() % items.len() as u64) as usize]
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// Values that are wrong, extreme or odd for most flags.
const VALUES: [&str; 26] = [
    "0",
    "-1",
    "1",
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "",
    " ",
    "18446744073709551616",
    "99999999999999999999999",
    "0x10",
    "1,2",
    "1,2,3",
    "1,2,3,4",
    "ﬀ",
    "\u{202e}12",
    "--",
    "-",
    "64x64",
    "0x0",
    "16385x2",
    "2.5",
    "abc",
    "%s%n",
];

/// Flags of every kind (numbers, lists, enums, paths, switches).
const FLAGS: [&str; 34] = [
    "--frames",
    "--size",
    "--wind-speed",
    "--wind-dir",
    "--fetch",
    "--depth",
    "--fft-size",
    "--patch-size",
    "--choppiness",
    "--cascades",
    "--seed",
    "--time",
    "--dt",
    "--time-scale",
    "--camera",
    "--look-at",
    "--view",
    "--fresnel",
    "--aa",
    "--rtt-scale",
    "--render-scale",
    "--terrain-grid",
    "--tess-edge",
    "--sun",
    "--clouds",
    "--buoy",
    "--sea-floor",
    "--gpu",
    "--quality",
    "--preset",
    "--spectrum",
    "--waves",
    "--present-mode",
    "--log-resources",
];

/// A value each of [`FLAGS`] accepts (two picks in three), so that many cases run.
const GOOD: [&str; 34] = [
    "2",
    "48x24",
    "30",
    "-45",
    "5",
    "12",
    "64",
    "150",
    "1.5",
    "2",
    "18446744073709551615",
    "1e6",
    "0.1",
    "0",
    "0,-60,0",
    "5,0,-40",
    "normals",
    "schlick",
    "none",
    "0.1",
    "0.25",
    "16",
    "256",
    "120,-10",
    "1",
    "-3,7",
    "500",
    "0",
    "medium",
    "storm",
    "pierson-moskowitz",
    "gerstner",
    "mailbox",
    "1",
];

/// Every run starts from a small, fast sample; the fuzzed flags come after and win.
const BASE: [&str; 5] = ["--headless", "--size", "32x32", "--quality", "low"];

/// A case: arguments (inputs as absolute paths) and a name for failure messages.
struct Case {
    name: String,
    args: Vec<String>,
}

/// Outputs a case may ask for, into its own directory.
fn outputs(rng: &mut Rng) -> Vec<String> {
    let mut out = Vec::new();
    match rng.below(5) {
        0 => out.extend(["--screenshot".into(), "out.png".into()]),
        4 => out.extend(["--screenshot".into(), "/proc/vkocean.png".into()]),
        1 => out.extend(["--dump".into(), "dump".into()]),
        2 => out.extend([
            "--profile".into(),
            "p.json".into(),
            "--frames".into(),
            "6".into(),
        ]),
        _ => {}
    }
    out
}

fn cli_cases(rng: &mut Rng, n: usize) -> Vec<Case> {
    (0..n)
        .map(|i| {
            let mut args: Vec<String> = BASE.iter().map(|s| s.to_string()).collect();
            for _ in 0..1 + rng.below(3) {
                let k = rng.below(FLAGS.len() as u64) as usize;
                let flag = FLAGS[k];
                let value = match rng.below(3) {
                    0 => rng.pick(&VALUES),
                    _ => GOOD[k],
                };
                // Both spellings clap accepts.
                if rng.below(2) == 0 {
                    args.push(format!("{flag}={value}"));
                } else {
                    args.extend([flag.to_string(), value.to_string()]);
                }
            }
            args.extend(outputs(rng));
            if rng.below(6) == 0 {
                args.extend([
                    "bench".into(),
                    rng.pick(&["fft", "frames", "gerstner", "x"]).to_string(),
                ]);
            }
            Case {
                name: format!("cli {i}"),
                args,
            }
        })
        .collect()
}

/// TOML fragments: good keys with bad values, bad syntax, deep nesting, huge numbers, bytes.
fn config_text(rng: &mut Rng) -> Vec<u8> {
    const LINES: [&str; 24] = [
        "wind-speed = 12",
        "wind_speed = 13",
        "fetch = -1",
        "seed = 18446744073709551615",
        "seed = \"18446744073709551615\"",
        "seed = 9223372036854775807",
        "camera = [0, 12, 0]",
        "camera = [0, 1e400, 0]",
        "camera = [[1]]",
        "quality = \"ultra\"",
        "preset = \"storm\"",
        "validation = \"yes\"",
        "headless = true",
        "frames = 2",
        "size = \"16x16\"",
        "[table]",
        "a.b.c = 1",
        "x = {",
        "= 3",
        "config = \"x.toml\"",
        "dudv = \"/dev/zero\"",
        "time = 1e6",
        "gerstner-waves = \"/\"",
        "\"wind-speed\" = 4",
    ];
    let mut text = Vec::new();
    for _ in 0..1 + rng.below(4) {
        match rng.below(10) {
            0 => text.extend("a = ".bytes().chain(std::iter::repeat_n(b'[', 300))),
            1 => text.extend((0..64).map(|_| rng.next() as u8)),
            _ => text.extend(rng.pick(&LINES).bytes()),
        }
        text.push(b'\n');
    }
    text
}

fn config_cases(rng: &mut Rng, n: usize, inputs: &Path) -> Vec<Case> {
    (0..n)
        .map(|i| {
            let path = inputs.join(format!("config-{i}.toml"));
            std::fs::write(&path, config_text(rng)).unwrap();
            let mut args: Vec<String> = BASE.iter().map(|s| s.to_string()).collect();
            args.extend(["--config".into(), path.to_string_lossy().into_owned()]);
            args.extend(outputs(rng));
            Case {
                name: format!("config {i}"),
                args,
            }
        })
        .collect()
}

/// A PNG of some kind: valid small ones (RGBA, grey, 16-bit), truncated, corrupt, header-only
/// with a huge or odd size, random bytes, empty.
fn png_bytes(rng: &mut Rng, side: u32) -> Vec<u8> {
    let encode = |colour: image::ExtendedColorType, bytes_per: usize| {
        use image::ImageEncoder;
        let data: Vec<u8> = (0..side as usize * side as usize * bytes_per)
            .map(|i| (i * 7) as u8)
            .collect();
        let mut out = Vec::new();
        image::codecs::png::PngEncoder::new(&mut out)
            .write_image(&data, side, side, colour)
            .unwrap();
        out
    };
    match rng.below(9) {
        0 => encode(image::ExtendedColorType::Rgba8, 4),
        1 => encode(image::ExtendedColorType::L8, 1),
        2 => encode(image::ExtendedColorType::Rgb16, 6),
        3 => {
            let mut p = encode(image::ExtendedColorType::Rgba8, 4);
            let cut = p.len() / 2;
            p.truncate(cut);
            p
        }
        4 => {
            let mut p = encode(image::ExtendedColorType::La8, 2);
            let at = p.len() - 20;
            p[at] ^= 0xff;
            p
        }
        5 => png_header_only(*rng.pick(&[16385, 20000, 65535, u32::MAX]), side),
        6 => png_header_only(0, 0),
        7 => (0..rng.below(200)).map(|_| rng.next() as u8).collect(),
        _ => Vec::new(),
    }
}

/// A path of an odd kind: a directory, a FIFO, a device, a dangling or looping link, a file.
fn odd_path(rng: &mut Rng, inputs: &Path, i: usize, ext: &str) -> PathBuf {
    let path = inputs.join(format!("odd-{i}.{ext}"));
    match rng.below(5) {
        0 => std::fs::create_dir(&path).unwrap(),
        1 => assert!(Command::new("mkfifo")
            .arg(&path)
            .status()
            .unwrap()
            .success()),
        2 => symlink(Path::new("/dev/zero"), &path),
        3 => symlink(&path, &path),
        _ => symlink(&inputs.join("missing"), &path),
    }
    path
}

/// A symbolic link at `path` to `target` (the suite runs on Linux; on Windows it compiles, with
/// the file links that need no administrator in developer mode).
fn symlink(target: &Path, path: &Path) {
    #[cfg(unix)]
    std::os::unix::fs::symlink(target, path).unwrap();
    #[cfg(windows)]
    std::os::windows::fs::symlink_file(target, path).unwrap();
}

fn file_cases(rng: &mut Rng, n: usize, inputs: &Path) -> Vec<Case> {
    (0..n)
        .map(|i| {
            let mut args: Vec<String> = BASE.iter().map(|s| s.to_string()).collect();
            let odd = rng.below(5) == 0;
            match rng.below(3) {
                0 => {
                    let path = if odd {
                        odd_path(rng, inputs, i, "png")
                    } else {
                        let p = inputs.join(format!("dudv-{i}.png"));
                        let side = *rng.pick(&[1, 8, 64]);
                        std::fs::write(&p, png_bytes(rng, side)).unwrap();
                        p
                    };
                    args.extend(["--dudv".into(), path.to_string_lossy().into_owned()]);
                }
                1 => {
                    let dir = inputs.join(format!("sky-{i}"));
                    std::fs::create_dir(&dir).unwrap();
                    let side = *rng.pick(&[1, 4, 16]);
                    for face in ["px", "nx", "py", "ny", "pz", "nz"] {
                        let face = dir.join(format!("{face}.png"));
                        match rng.below(8) {
                            0 => {}
                            1 => std::fs::create_dir(&face).unwrap(),
                            2 => std::fs::write(&face, png_bytes(rng, side)).unwrap(),
                            _ => std::fs::write(&face, png_bytes(&mut Rng(side as u64 + 3), side))
                                .unwrap(),
                        }
                    }
                    args.extend(["--skybox".into(), dir.to_string_lossy().into_owned()]);
                }
                _ => {
                    let toml = rng.below(2) == 0;
                    let ext = if toml { "toml" } else { "csv" };
                    let path = if odd {
                        odd_path(rng, inputs, i, ext)
                    } else {
                        let p = inputs.join(format!("waves-{i}.{ext}"));
                        std::fs::write(&p, wave_table(rng, toml)).unwrap();
                        p
                    };
                    args.extend([
                        "--waves".into(),
                        "gerstner".into(),
                        "--gerstner-waves".into(),
                        path.to_string_lossy().into_owned(),
                    ]);
                }
            }
            args.extend(outputs(rng));
            Case {
                name: format!("file {i}"),
                args,
            }
        })
        .collect()
}

/// A Gerstner table with odd numbers in it.
fn wave_table(rng: &mut Rng, toml: bool) -> String {
    const NUMBERS: [&str; 14] = [
        "0.3", "-0.46", "0", "1e30", "-1e-30", "50", "1000", "0.001", "nan", "inf", "1e400", "x",
        "", "2",
    ];
    let mut text = String::new();
    for _ in 0..1 + rng.below(4) {
        let v: Vec<&str> = (0..5).map(|_| *rng.pick(&NUMBERS)).collect();
        if toml {
            text += &format!(
                "[[wave]]\nkx = {}\nkz = {}\namplitude = {}\nphase = {}\nsteepness = {}\n",
                v[0], v[1], v[2], v[3], v[4]
            );
        } else {
            let fields = 3 + rng.below(4) as usize;
            text += &(v[..fields.min(5)].join(",") + "\n");
        }
    }
    text
}

/// Runs one case in an empty directory: its exit code and a description of what broke, if
/// anything.
fn check(case: &Case, work: &Path) -> (Option<i32>, Option<String>) {
    // -k: vkocean catches SIGTERM (it stops between frames), so a hang needs SIGKILL after it.
    let out = Command::new("timeout")
        .args(["-k", "5", "60"])
        .arg(bin())
        .args(&case.args)
        .current_dir(work)
        .env_remove("RUST_LOG")
        .output()
        .expect("timeout runs");
    let err = String::from_utf8_lossy(&out.stderr);
    let all = format!("{err}{}", String::from_utf8_lossy(&out.stdout));
    let code = out.status.code();
    let problem = if code == Some(124) {
        Some("did not end within 60 s".to_string())
    } else if !matches!(code, Some(0..=3)) {
        Some(format!("exit {code:?}"))
    } else if all.contains("panicked") || all.contains("RUST_BACKTRACE") {
        Some("a panic".to_string())
    } else if code != Some(0) && code != Some(3) {
        let lines: Vec<&str> = err.lines().collect();
        if lines.len() > 1 || lines.first().is_some_and(|l| !l.starts_with("vkocean: ")) {
            Some("more than one stderr line, or one not starting vkocean:".to_string())
        } else if !entries(work).is_empty() {
            Some(format!("left {:?}", entries(work)))
        } else {
            None
        }
    } else {
        None
    };
    let problem =
        problem.map(|p| format!("{}: {p}\n  args {:?}\n  stderr {err}", case.name, case.args));
    (code, problem)
}

#[test]
fn generated_inputs_end_cleanly() {
    let root = scratch("fuzz");
    let inputs = root.join("inputs");
    std::fs::create_dir_all(&inputs).unwrap();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut cases = cli_cases(&mut rng, 70);
    cases.extend(config_cases(&mut rng, 50, &inputs));
    cases.extend(file_cases(&mut rng, 60, &inputs));
    assert!(cases.len() >= 150);

    let next = Mutex::new(0usize);
    let problems = Mutex::new(Vec::new());
    let codes = Mutex::new(std::collections::BTreeMap::new());
    std::thread::scope(|scope| {
        for _ in 0..2 {
            scope.spawn(|| loop {
                let i = {
                    let mut n = next.lock().unwrap();
                    *n += 1;
                    *n - 1
                };
                let Some(case) = cases.get(i) else { break };
                let work = root.join(format!("run-{i}"));
                std::fs::create_dir_all(&work).unwrap();
                let (code, problem) = check(case, &work);
                *codes.lock().unwrap().entry(code).or_insert(0usize) += 1;
                problems.lock().unwrap().extend(problem);
                let _ = std::fs::remove_dir_all(&work);
            });
        }
    });
    let problems = problems.into_inner().unwrap();
    eprintln!(
        "exit codes of {} cases: {:?}",
        cases.len(),
        codes.into_inner().unwrap()
    );
    let _ = std::fs::remove_dir_all(&root);
    assert!(
        problems.is_empty(),
        "{} of {} cases broke:\n{}",
        problems.len(),
        cases.len(),
        problems.join("\n")
    );
}
