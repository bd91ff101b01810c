//! Gerstner waves, analytic (seed 000, section 2; steepness from seed 004). A point (α, β) of the
//! mean surface moves to
//!
//! ```text
//! x = α − Σ Q_m (k_x,m/k_m) a_m sin θ_m,   z = β − Σ Q_m (k_z,m/k_m) a_m sin θ_m,   y = Σ a_m cos θ_m,
//! θ_m = k_x,m α + k_z,m β − ω_m t − φ_m,   ω_m = √(g k_m), g = 9.8 (seed 000's constant).
//! ```
//! Q_m = 1 is seed 000's wave, Q_m = 0 a plain sine (seed 004). [`limit_steepness`] scales the
//! Q of a table whose Σ Q_m k_m a_m exceeds 1, where the surface could fold over. The normal is the cross product of
//! the surface tangents; seed 000 writes ∂r/∂α × ∂r/∂β in Direct3D's left-handed (x, z, y) order,
//! which in our right-handed (x, y, z) is n = ∂r/∂β × ∂r/∂α (pointing up).

/// Gravity in seed 000's dispersion relation.
pub const G_SEED: f64 = 9.8;

/// One wave: wave vector (rad/m), amplitude (m), phase (rad), steepness Q.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wave {
    pub kx: f64,
    pub kz: f64,
    pub amplitude: f64,
    pub phase: f64,
    pub steepness: f64,
}

/// Seed 000's table of 13 waves (k_x, k_z, a, φ), Q = 1.
pub const SEED_000_WAVES: [(f64, f64, f64, f64); 13] = [
    (0.3, -0.46, 0.2, 0.0),
    (-0.33, 0.40, 0.12, 0.0),
    (0.0, 0.56, 0.2, 0.2),
    (-0.33, 0.0, 0.12, 0.3),
    (0.3, -0.26, 0.2, 0.7),
    (-0.33, 0.20, 0.12, 0.9),
    (0.17, 0.3, 0.3, -1.0),
    (-0.15, -0.1, 0.7, 0.6),
    (-0.15, 0.1, 0.6, 0.5),
    (0.15, -0.1, 0.8, 0.4),
    (0.15, 0.1, 0.3, 0.3),
    (-0.25, -0.1, 0.2, 0.2),
    (-0.15, -0.25, 0.4, 0.1),
];

/// The default wave table.
pub fn default_waves() -> Vec<Wave> {
    SEED_000_WAVES
        .iter()
        .map(|&(kx, kz, amplitude, phase)| Wave {
            kx,
            kz,
            amplitude,
            phase,
            steepness: 1.0,
        })
        .collect()
}

/// How a wave table file is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableFormat {
    /// Lines `kx,kz,amplitude,phase[,steepness]`; blank lines, `#` comments and a header line
    /// are skipped.
    Csv,
    /// A list of `[[wave]]` tables with the keys `kx`, `kz`, `amplitude`, `phase` and optional
    /// `steepness` (default 1).
    Toml,
}

impl TableFormat {
    /// By the file's extension: `.toml` (any case) is TOML, anything else CSV.
    pub fn of_path(path: &std::path::Path) -> TableFormat {
        if path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
        {
            TableFormat::Toml
        } else {
            TableFormat::Csv
        }
    }
}

/// Largest wave table file read (bytes): 10 000 waves of 80 characters fit with room to spare.
pub const MAX_TABLE_BYTES: u64 = 4 << 20;
/// Accepted wave numbers |k| (rad/m): wavelengths 2π/|k| from 6.3 mm (capillary ripples) to
/// 6.3 km (swell); outside, a wave is finer than any texel or a flat tilt of the whole sea.
pub const K_RANGE: (f64, f64) = (1.0e-3, 1.0e3);
/// Largest accepted amplitude (m): beyond any sea wave (the highest measured is 30 m).
pub const MAX_AMPLITUDE_M: f64 = 100.0;
/// Largest accepted steepness Q. The surface folds once Σ Q·k·a > 1 (then every Q is scaled
/// down, `limit_steepness`); a Q far above 1 only means a wave of tiny k·a, so 10 bounds it.
pub const MAX_STEEPNESS: f64 = 10.0;
/// Largest accepted |phase| (rad): f32 keeps the phase's fraction of a cycle to 1e-4 there.
pub const MAX_PHASE_RAD: f64 = 1000.0;

/// Parses a wave table written in `format`. Errors name the line.
pub fn parse_waves(text: &str, format: TableFormat) -> Result<Vec<Wave>, String> {
    let number = |v: &str, line: usize| -> Result<f64, String> {
        let x: f64 = v
            .trim()
            .parse()
            .map_err(|_| format!("line {line}: '{}' is not a number", v.trim()))?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(format!("line {line}: '{}' is not finite", v.trim()))
        }
    };
    let check = |w: Wave, line: usize| -> Result<Wave, String> {
        let k = w.kx.hypot(w.kz);
        if !(K_RANGE.0..=K_RANGE.1).contains(&k) {
            return Err(format!(
                "line {line}: the wave number |(kx, kz)| = {k:.3e} rad/m must be from {} to {} (wavelengths 6.3 mm to 6.3 km)",
                K_RANGE.0, K_RANGE.1
            ));
        }
        if !(0.0..=MAX_AMPLITUDE_M).contains(&w.amplitude) {
            return Err(format!(
                "line {line}: the amplitude must be from 0 to {MAX_AMPLITUDE_M} m"
            ));
        }
        if !(0.0..=MAX_STEEPNESS).contains(&w.steepness) {
            return Err(format!(
                "line {line}: the steepness Q must be from 0 to {MAX_STEEPNESS}"
            ));
        }
        if w.phase.abs() > MAX_PHASE_RAD {
            return Err(format!(
                "line {line}: the phase must be from -{MAX_PHASE_RAD} to {MAX_PHASE_RAD} rad"
            ));
        }
        Ok(w)
    };
    let mut waves = Vec::new();
    if format == TableFormat::Toml {
        waves = parse_toml_waves(text, check)?;
    } else {
        for (i, raw) in text.lines().enumerate() {
            let line = raw.split('#').next().unwrap_or("").trim();
            if line.is_empty()
                || (waves.is_empty() && line.starts_with(|c: char| c.is_ascii_alphabetic()))
            {
                continue;
            }
            let fields: Vec<&str> = line.split(',').collect();
            if !(4..=5).contains(&fields.len()) {
                return Err(format!(
                    "line {}: expected kx,kz,amplitude,phase[,steepness]",
                    i + 1
                ));
            }
            let w = Wave {
                kx: number(fields[0], i + 1)?,
                kz: number(fields[1], i + 1)?,
                amplitude: number(fields[2], i + 1)?,
                phase: number(fields[3], i + 1)?,
                steepness: if fields.len() == 5 {
                    number(fields[4], i + 1)?
                } else {
                    1.0
                },
            };
            waves.push(check(w, i + 1)?);
        }
    }
    if waves.is_empty() {
        return Err("no waves in the table".to_string());
    }
    Ok(waves)
}

/// The `[[wave]]` tables of a TOML wave table (parsed by toml_edit), each checked by `check`.
fn parse_toml_waves(
    text: &str,
    check: impl Fn(Wave, usize) -> Result<Wave, String>,
) -> Result<Vec<Wave>, String> {
    let doc = toml_edit::Document::parse(text).map_err(|e| toml_error_line(&e))?;
    let line_at = |span: Option<std::ops::Range<usize>>| {
        span.map_or(0, |s| text[..s.start].matches('\n').count() + 1)
    };
    let mut waves = Vec::new();
    for (key, item) in doc.as_table().iter() {
        let line = line_at(doc.as_table().key(key).and_then(|k| k.span()));
        let tables = match (key, item.as_array_of_tables()) {
            ("wave", Some(tables)) => tables,
            ("wave", None) => return Err(format!("line {line}: 'wave' must be [[wave]] tables")),
            _ => {
                return Err(format!(
                    "line {line}: unknown key '{key}' (expected [[wave]] tables)"
                ))
            }
        };
        for table in tables.iter() {
            let line = line_at(table.span());
            let mut values = [None; 5];
            for (key, item) in table.iter() {
                let at = line_at(table.key(key).and_then(|k| k.span()));
                let slot = ["kx", "kz", "amplitude", "phase", "steepness"]
                    .iter()
                    .position(|k| *k == key)
                    .ok_or(format!("line {at}: unknown key '{key}'"))?;
                let value = item
                    .as_float()
                    .or(item.as_integer().map(|i| i as f64))
                    .ok_or(format!("line {at}: '{key}' must be a number"))?;
                if !value.is_finite() {
                    return Err(format!("line {at}: '{key}' is not finite"));
                }
                values[slot] = Some(value);
            }
            let get = |i: usize, name: &str| {
                values[i].ok_or(format!("the [[wave]] at line {line} lacks {name}"))
            };
            let wave = Wave {
                kx: get(0, "kx")?,
                kz: get(1, "kz")?,
                amplitude: get(2, "amplitude")?,
                phase: get(3, "phase")?,
                steepness: values[4].unwrap_or(1.0),
            };
            waves.push(check(wave, line)?);
        }
    }
    Ok(waves)
}

/// A TOML error on one line: "line L, column C: what is wrong" (toml_edit's message spans
/// several lines with a picture of the input).
pub fn toml_error_line(e: &toml_edit::TomlError) -> String {
    let text = e.to_string();
    let mut lines = text.lines();
    let place = lines
        .next()
        .unwrap_or("")
        .trim_start_matches("TOML parse error at ")
        .to_string();
    let reason: Vec<&str> = lines
        .filter(|l| !l.trim_start().starts_with('|') && !l.contains(" | "))
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    match reason.is_empty() {
        true => place,
        false => format!("{place}: {}", reason.join("; ")),
    }
}

/// Σ Q_m k_m a_m over the table: the horizontal displacement's largest possible gradient. The
/// Jacobian of the map (α, β) → (x, z) is det(I − Σ Q_m k_m a_m cos θ_m k̂_m k̂_mᵀ) ≥ (1 − Σ)²
/// when Σ ≤ 1, so the surface never folds over, whatever the phases (GPU Gems 1, ch. 1 (Finch
/// 2004): Q_i = Q / (w_i A_i · numWaves); seed 004: Q_i = 1 / (w_i A_i) is one wave's sharpest
/// crest). Above 1 the crests of waves in phase loop over themselves.
pub fn fold_sum(waves: &[Wave]) -> f64 {
    waves
        .iter()
        .map(|w| w.steepness * w.amplitude * (w.kx * w.kx + w.kz * w.kz).sqrt())
        .sum()
}

/// Scales every wave's steepness Q by one factor so that [`fold_sum`] is at most 1 (the
/// surface cannot fold). Returns (factor, the sum before) when it scaled, `None` when the table
/// was within the limit. Seed 000's table at Q = 1 sums to 1.155, so its Q becomes 0.866.
pub fn limit_steepness(waves: &mut [Wave]) -> Option<(f64, f64)> {
    let sum = fold_sum(waves);
    if sum <= 1.0 {
        return None;
    }
    let factor = 1.0 / sum;
    for w in waves.iter_mut() {
        w.steepness *= factor;
    }
    Some((factor, sum))
}

/// Displaced position (x, y, z) and unit normal of the surface point (α, β) at time t.
pub fn evaluate(waves: &[Wave], alpha: f64, beta: f64, t: f64) -> ([f64; 3], [f64; 3]) {
    let mut p = [alpha, 0.0, beta];
    // Tangents ∂r/∂α and ∂r/∂β, in (x, y, z).
    let mut ta = [1.0, 0.0, 0.0];
    let mut tb = [0.0, 0.0, 1.0];
    for w in waves {
        let k = (w.kx * w.kx + w.kz * w.kz).sqrt();
        if k == 0.0 {
            continue;
        }
        let omega = (G_SEED * k).sqrt();
        let theta = w.kx * alpha + w.kz * beta - omega * t - w.phase;
        let (s, c) = theta.sin_cos();
        let qa = w.steepness * w.amplitude / k;
        p[0] -= w.kx * qa * s;
        p[2] -= w.kz * qa * s;
        p[1] += w.amplitude * c;
        ta[0] -= w.kx * w.kx * qa * c;
        ta[1] -= w.kx * w.amplitude * s;
        ta[2] -= w.kx * w.kz * qa * c;
        tb[0] -= w.kx * w.kz * qa * c;
        tb[1] -= w.kz * w.amplitude * s;
        tb[2] -= w.kz * w.kz * qa * c;
    }
    let n = [
        tb[1] * ta[2] - tb[2] * ta[1],
        tb[2] * ta[0] - tb[0] * ta[2],
        tb[0] * ta[1] - tb[1] * ta[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-12);
    (p, [n[0] / len, n[1] / len, n[2] / len])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    #[test]
    fn normals_match_finite_differences() {
        let waves = default_waves();
        let h = 1e-5;
        for &(a, b, t) in &[(0.0, 0.0, 0.0), (3.7, -12.1, 1.3), (-40.0, 22.5, 7.9)] {
            let (_, n) = evaluate(&waves, a, b, t);
            let d = |da: f64, db: f64| evaluate(&waves, a + da, b + db, t).0;
            let sub = |p: [f64; 3], q: [f64; 3]| {
                [
                    (p[0] - q[0]) / (2.0 * h),
                    (p[1] - q[1]) / (2.0 * h),
                    (p[2] - q[2]) / (2.0 * h),
                ]
            };
            let ta = sub(d(h, 0.0), d(-h, 0.0));
            let tb = sub(d(0.0, h), d(0.0, -h));
            let fd = cross(tb, ta);
            let len = (fd[0] * fd[0] + fd[1] * fd[1] + fd[2] * fd[2]).sqrt();
            for i in 0..3 {
                assert!(
                    (n[i] - fd[i] / len).abs() < 1e-6,
                    "at ({a},{b},{t}): {n:?} vs {fd:?}"
                );
            }
            assert!(n[1] > 0.0, "normal points up");
        }
    }

    /// The smallest Jacobian of (α, β) → (x, z) over a grid of the window and a few times
    /// (central differences of `evaluate`).
    fn min_jacobian(waves: &[Wave]) -> f64 {
        let h = 1e-4;
        let mut min = f64::MAX;
        for t in [0.0, 3.1, 7.7, 12.9, 40.3] {
            for i in 0..80 {
                for j in 0..80 {
                    let (a, b) = (-60.0 + 1.5 * i as f64, -60.0 + 1.5 * j as f64);
                    let p = |da: f64, db: f64| evaluate(waves, a + da, b + db, t).0;
                    let (xa, xb) = (p(h, 0.0), p(-h, 0.0));
                    let (za, zb) = (p(0.0, h), p(0.0, -h));
                    let dxda = (xa[0] - xb[0]) / (2.0 * h);
                    let dzda = (xa[2] - xb[2]) / (2.0 * h);
                    let dxdb = (za[0] - zb[0]) / (2.0 * h);
                    let dzdb = (za[2] - zb[2]) / (2.0 * h);
                    min = min.min(dxda * dzdb - dxdb * dzda);
                }
            }
        }
        min
    }

    #[test]
    fn steepness_is_limited_so_the_surface_cannot_fold() {
        // Seed 000's table: Σ k·a = 1.155 at Q = 1.
        let mut waves = default_waves();
        assert!(
            (fold_sum(&waves) - 1.155).abs() < 0.001,
            "{}",
            fold_sum(&waves)
        );
        // Q = 3 folds (the Jacobian goes negative) ...
        for w in waves.iter_mut() {
            w.steepness = 3.0;
        }
        assert!(min_jacobian(&waves) < 0.0, "Q = 3 should fold");
        // ... and the limit scales every Q by 1 / Σ, after which it cannot (J ≥ (1 − Σ)² = 0).
        let (factor, before) = limit_steepness(&mut waves).expect("Q = 3 is over the limit");
        assert!((before - 3.0 * 1.155).abs() < 0.005 && (factor * before - 1.0).abs() < 1e-12);
        assert!((fold_sum(&waves) - 1.0).abs() < 1e-12);
        assert!(waves
            .iter()
            .all(|w| (w.steepness - 3.0 * factor).abs() < 1e-12));
        let min = min_jacobian(&waves);
        assert!(min > 0.0, "limited table folds: min Jacobian {min}");
        // A table within the limit is left alone.
        let mut calm = default_waves();
        for w in calm.iter_mut() {
            w.steepness = 0.5;
        }
        assert_eq!(limit_steepness(&mut calm), None);
        assert!(calm.iter().all(|w| w.steepness == 0.5));
    }

    #[test]
    fn wave_tables_parse_and_errors_name_the_line() {
        let csv = "kx,kz,amplitude,phase\n# comment\n0.3,-0.46,0.2,0\n0.1, 0.2, 0.5, 1.0, 0.5\n";
        let w = parse_waves(csv, TableFormat::Csv).unwrap();
        assert_eq!(w.len(), 2);
        assert_eq!((w[1].kz, w[1].steepness), (0.2, 0.5));
        let toml = "[[wave]]\nkx = 0.3\nkz = -0.46\namplitude = 0.2\nphase = 0\n\n[[wave]]\nkx=1\nkz=0\namplitude=0.1\nphase=0.5\nsteepness=0\n";
        let t = parse_waves(toml, TableFormat::Toml).unwrap();
        assert_eq!(t.len(), 2);
        assert_eq!((t[0].steepness, t[1].steepness), (1.0, 0.0));
        assert!(parse_waves("1,2,3\n", TableFormat::Csv)
            .unwrap_err()
            .contains("line 1"));
        assert!(parse_waves("1,2,x,4\n", TableFormat::Csv)
            .unwrap_err()
            .contains("line 1"));
        assert!(parse_waves("0,0,1,0\n", TableFormat::Csv)
            .unwrap_err()
            .contains("line 1: the wave number |(kx, kz)| = 0.000e0 rad/m must be from 0.001"));
        // The bounds themselves are accepted; just beyond them is not.
        assert!(parse_waves("1000,0,100,1000,10\n0.001,0,0,-1000,0\n", TableFormat::Csv).is_ok());
        for bad in [
            "1000.1,0,1,0",
            "0,0.0009,1,0",
            "1,0,100.1,0",
            "1,0,1,0,10.1",
            "1,0,1,1000.1",
            "1,0,-1,0",
        ] {
            assert!(parse_waves(bad, TableFormat::Csv).is_err(), "{bad}");
        }
        assert!(parse_waves("[[wave]]\nkx=1\n", TableFormat::Toml)
            .unwrap_err()
            .contains("the [[wave]] at line 1 lacks kz"));
        // toml_edit's own errors, on one line, with the reason.
        let duplicate = parse_waves("[[wave]]\nkx = 1\nkx = 2\n", TableFormat::Toml).unwrap_err();
        assert!(
            duplicate.starts_with("line 3, column 1: ") && duplicate.contains("duplicate key"),
            "{duplicate}"
        );
        let unknown = "[[wave]]\nkx = 1\nkz = 0\namplitude = 1\nphase = 0\nspeed = 3\n";
        assert_eq!(
            parse_waves(unknown, TableFormat::Toml).unwrap_err(),
            "line 6: unknown key 'speed'"
        );
        assert_eq!(
            parse_waves("[[wave]]\nkx = \"1\"\n", TableFormat::Toml).unwrap_err(),
            "line 2: 'kx' must be a number"
        );
        assert_eq!(
            parse_waves("[[wave]]\nkx = inf\n", TableFormat::Toml).unwrap_err(),
            "line 2: 'kx' is not finite"
        );
        assert_eq!(
            parse_waves("waves = 3\n", TableFormat::Toml).unwrap_err(),
            "line 1: unknown key 'waves' (expected [[wave]] tables)"
        );
        assert!(parse_waves("", TableFormat::Csv).is_err());
    }

    #[test]
    fn flat_without_waves_and_plain_sine_with_zero_steepness() {
        let (p, n) = evaluate(&[], 1.0, 2.0, 3.0);
        assert_eq!((p, n), ([1.0, 0.0, 2.0], [0.0, 1.0, 0.0]));
        let w = Wave {
            kx: 0.5,
            kz: 0.0,
            amplitude: 0.3,
            phase: 0.0,
            steepness: 0.0,
        };
        let (p, _) = evaluate(&[w], 1.0, 0.0, 0.0);
        assert_eq!((p[0], p[2]), (1.0, 0.0));
        assert!((p[1] - 0.3 * 0.5f64.cos()).abs() < 1e-12);
    }
}
