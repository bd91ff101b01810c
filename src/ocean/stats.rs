//! Height statistics (`--stats`) and `.npy` encoding (`--dump`).

use serde_json::{json, Value};

use super::cpu::bilinear;
use super::simulation::Texels;

/// mean, standard deviation, significant wave height Hs = 4σ, min, max of a height set.
pub fn height_stats(heights: impl Iterator<Item = f64>) -> Value {
    let (mut n, mut sum, mut sq, mut min, mut max) =
        (0.0, 0.0, 0.0, f64::INFINITY, f64::NEG_INFINITY);
    for h in heights {
        n += 1.0;
        sum += h;
        sq += h * h;
        min = min.min(h);
        max = max.max(h);
    }
    let mean = sum / n;
    let std = (sq / n - mean * mean).max(0.0).sqrt();
    json!({"mean": mean, "std": std, "hs": 4.0 * std, "min": min, "max": max})
}

/// Share of the sea the whitecaps cover: the texels of layer 0 (the whole surface's foam,
/// `ocean::foam`) with foam ≥ `foam::WHITECAP_FOAM`, by area at rest.
pub fn whitecap_fraction(normals: &Texels, n: usize) -> f64 {
    let layer = &normals[..n * n];
    let covered = layer
        .iter()
        .filter(|t| t[3] >= super::foam::WHITECAP_FOAM)
        .count();
    covered as f64 / layer.len() as f64
}

/// One `--stats` line: height statistics per cascade, and for the surface (all cascades summed)
/// sampled on the largest cascade's grid, each cascade read at x mod L_c by bilinear
/// interpolation, with the surface's whitecap fraction; and the spray's counts when the run has
/// spray (`spray`: live particles, puffs born and landed in the frame).
pub fn stats_line(
    frame: u64,
    t: f64,
    (displacement, normals): (&Texels, &Texels),
    n: usize,
    patch_m: &[f64],
    spray: Option<[u32; 3]>,
) -> String {
    let plane = n * n;
    let cascades: Vec<Value> = (0..patch_m.len())
        .map(|c| {
            height_stats(
                displacement[c * plane..(c + 1) * plane]
                    .iter()
                    .map(|d| d[1] as f64),
            )
        })
        .collect();
    let height = |c: usize, x: f64, z: f64| {
        bilinear(
            &displacement[c * plane..(c + 1) * plane],
            n,
            patch_m[c],
            x,
            z,
            1,
        )
    };
    let step = patch_m[0] / n as f64;
    let mut surface = height_stats((0..plane).map(|i| {
        let (x, z) = ((i % n) as f64 * step, (i / n) as f64 * step);
        (0..patch_m.len()).map(|c| height(c, x, z)).sum()
    }));
    surface["whitecap_fraction"] = json!(whitecap_fraction(normals, n));
    let mut line = json!({"frame": frame, "t": t, "cascades": cascades, "surface": surface});
    if let Some([particles, born, landed]) = spray {
        line["spray"] = json!({"particles": particles, "born": born, "landed": landed});
    }
    line.to_string()
}

/// A little-endian `.npy` (format 1.0) file: `descr` e.g. "<f4" or "<c8", row-major `shape`.
pub fn npy(descr: &str, shape: &[usize], data: &[u8]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let shape_text = if dims.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    let mut header =
        format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape_text}, }}");
    // Magic (6) + version (2) + length (2) + header + '\n' is padded to a multiple of 64.
    let total = 10 + header.len() + 1;
    header.push_str(&" ".repeat((64 - total % 64) % 64));
    header.push('\n');
    let mut out = Vec::with_capacity(10 + header.len() + data.len());
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn npy_header_is_aligned_and_describes_the_array() {
        let bytes = npy("<f4", &[2, 3, 4, 4], &[0u8; 2 * 3 * 4 * 4 * 4]);
        assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
        let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
        assert_eq!((10 + len) % 64, 0);
        let header = std::str::from_utf8(&bytes[10..10 + len]).unwrap();
        assert!(
            header.contains("'descr': '<f4'") && header.contains("'shape': (2, 3, 4, 4)"),
            "{header}"
        );
        assert!(header.ends_with('\n'));
        assert_eq!(bytes.len(), 10 + len + 2 * 3 * 4 * 4 * 4);
    }

    #[test]
    fn stats_of_a_known_field() {
        let v = height_stats([1.0, -1.0, 1.0, -1.0].into_iter());
        assert_eq!(v["mean"], 0.0);
        assert_eq!(v["std"], 1.0);
        assert_eq!(v["hs"], 4.0);
        assert_eq!(
            (v["min"].as_f64(), v["max"].as_f64()),
            (Some(-1.0), Some(1.0))
        );
    }
}
