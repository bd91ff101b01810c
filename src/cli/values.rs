//! Parsers of command-line values (clap `value_parser`s): each returns a short reason that clap
//! puts after the flag's name, e.g. `invalid value '0' for '--cascades <K>': must be ...`.

use clap::ValueEnum;

use super::{UsageError, MAX_SIDE};

/// A feature turned on or off (`--spray`, `--foam-sim`, `--gusts`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Switch {
    On,
    Off,
}

pub fn parse_whole(s: &str, lo: u64, hi: u64) -> Result<u64, String> {
    match s.trim().parse::<i128>() {
        Ok(n) if n >= lo as i128 && n <= hi as i128 => Ok(n as u64),
        Ok(_) => Err(format!("must be a whole number from {lo} to {hi}")),
        Err(_) => Err("not a whole number".to_string()),
    }
}

/// A power of two from 64 to 1024.
pub fn parse_fft_size(s: &str) -> Result<usize, String> {
    let n = parse_whole(s, 1, 1 << 20)?;
    if !n.is_power_of_two() || !(64..=1024).contains(&n) {
        return Err("must be a power of two from 64 to 1024".to_string());
    }
    Ok(n as usize)
}

pub fn parse_batch(s: &str) -> Result<usize, String> {
    parse_whole(s, 1, 64).map(|n| n as usize)
}

pub fn parse_runs(s: &str) -> Result<usize, String> {
    parse_whole(s, 1, 10_000).map(|n| n as usize)
}

/// A finite real number in [lo, hi].
pub fn parse_in(s: &str, lo: f64, hi: f64) -> Result<f64, String> {
    let v = parse_number(s)?;
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(format!("must be a number from {lo} to {hi}"))
    }
}

/// A finite real number in (lo, hi].
pub fn parse_above(s: &str, lo: f64, hi: f64) -> Result<f64, String> {
    let v = parse_number(s)?;
    if v.is_finite() && v > lo && v <= hi {
        Ok(v)
    } else {
        Err(format!(
            "must be a number greater than {lo} and at most {hi}"
        ))
    }
}

fn parse_number(s: &str) -> Result<f64, String> {
    s.trim().parse().map_err(|_| "not a number".to_string())
}

/// `N,N,...`: exactly `len` finite numbers.
pub fn parse_list(s: &str, len: usize) -> Result<Vec<f32>, String> {
    let values: Vec<&str> = s.split(',').collect();
    let expected = || {
        format!(
            "expected {len} comma-separated numbers, e.g. {}",
            ["10", "-5", "2"][..len].join(",")
        )
    };
    if values.len() != len {
        return Err(expected());
    }
    values
        .iter()
        .map(|v| match v.trim().parse::<f32>() {
            Ok(x) if x.is_finite() && x.abs() <= 1.0e6 => Ok(x),
            Ok(_) => Err("each number must be finite and at most 1e6 in size".to_string()),
            Err(_) => Err(expected()),
        })
        .collect()
}

pub fn parse_vec3(s: &str) -> Result<[f32; 3], String> {
    let v = parse_list(s, 3)?;
    Ok([v[0], v[1], v[2]])
}

pub fn parse_vec2(s: &str) -> Result<[f32; 2], String> {
    let v = parse_list(s, 2)?;
    Ok([v[0], v[1]])
}

/// `--boat SPEED,HEADING`: a speed within the wake model's range, any heading.
pub fn parse_boat(s: &str) -> Result<[f64; 2], String> {
    use crate::ocean::wake::{MAX_SPEED_M_S, MIN_SPEED_M_S};
    let v = parse_list(s, 2)?;
    let speed = f64::from(v[0]);
    if !(MIN_SPEED_M_S..=MAX_SPEED_M_S).contains(&speed) {
        return Err(format!(
            "the speed must be from {MIN_SPEED_M_S} to {MAX_SPEED_M_S} m/s"
        ));
    }
    Ok([speed, f64::from(v[1])])
}

pub fn parse_sun(s: &str) -> Result<[f32; 2], String> {
    let v = parse_list(s, 2)?;
    if !(-10.0..=90.0).contains(&v[1]) {
        return Err("the elevation must be from -10 to 90 degrees".to_string());
    }
    Ok([v[0], v[1]])
}

pub fn parse_frames(s: &str) -> Result<u64, String> {
    parse_whole(s, 1, u32::MAX as u64)
}

pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or("expected WIDTHxHEIGHT, e.g. 1280x720")?;
    let side = |v: &str| -> Result<u32, String> {
        let n: u64 = v
            .trim()
            .parse()
            .map_err(|_| "expected WIDTHxHEIGHT with whole numbers, e.g. 1280x720".to_string())?;
        if n == 0 || n > MAX_SIDE as u64 {
            return Err(format!("each side must be from 1 to {MAX_SIDE} pixels"));
        }
        Ok(n as u32)
    };
    Ok((side(w)?, side(h)?))
}

/// `flag PATH` must name a `.want` file (any case), when given.
pub fn require_extension(
    flag: &str,
    path: Option<&std::path::Path>,
    want: &str,
) -> Result<(), UsageError> {
    let Some(path) = path else { return Ok(()) };
    let ext = path.extension().and_then(|e| e.to_str());
    if ext.is_some_and(|e| e.eq_ignore_ascii_case(want)) {
        Ok(())
    } else {
        Err(UsageError(format!(
            "{flag} {}: the file name must end in .{want}",
            path.display()
        )))
    }
}

/// `--validation-extra`: a comma list of the layer's extra checks.
pub fn parse_validation_extras(s: &str) -> Result<crate::gpu::ValidationExtras, String> {
    crate::gpu::ValidationExtras::parse(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes() {
        assert_eq!(parse_size("1280x720"), Ok((1280, 720)));
        assert_eq!(parse_size("64X32"), Ok((64, 32)));
        assert!(parse_size("0x0").is_err());
        assert!(parse_size("100000x10").is_err());
        assert!(parse_size("12x").is_err());
        assert!(parse_size("axb").is_err());
        assert!(parse_size("1280").is_err());
    }

    #[test]
    fn frames() {
        assert_eq!(parse_frames("60"), Ok(60));
        assert!(parse_frames("0").is_err());
        assert!(parse_frames("-3").is_err());
        assert!(parse_frames("1.5").is_err());
        assert!(parse_frames("99999999999").is_err());
    }
}
