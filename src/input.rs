//! Input files (`--config`, `--gerstner-waves`, `--dudv`, `--skybox`) read defensively: only
//! regular files (a FIFO or a device would block or never end), text files up to a size cap,
//! and PNGs by their header first, so a picture's size is checked before a byte of it is
//! decoded, then decoded straight into the buffer that uploads it (no second copy).
//! Every problem is an [`InputError`]: bad usage, exit code 2.

use std::io::Read;
use std::path::Path;

/// A bad input file (exit code 2), with the flag and the path in its message.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct InputError(pub String);

/// Bytes the PNG decoder may allocate for itself (rows, chunks such as iCCP or text) besides
/// the picture: the fixed margin of an input's memory (the `png` crate's default).
pub const PNG_DECODER_BYTES: usize = 64 << 20;

/// `path` must be an existing regular file (symbolic links followed); returns its size.
pub fn regular_file(what: &str, path: &Path) -> Result<u64, InputError> {
    let shown = path.display();
    let meta = std::fs::metadata(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => InputError(format!("{what} {shown}: no such file")),
        _ => InputError(format!("{what} {shown}: {e}")),
    })?;
    if meta.is_dir() {
        return Err(InputError(format!(
            "{what} {shown}: is a directory, not a file"
        )));
    }
    if !meta.is_file() {
        return Err(InputError(format!(
            "{what} {shown}: not a regular file (FIFOs, sockets and devices are not read)"
        )));
    }
    Ok(meta.len())
}

/// Reads a UTF-8 text file of at most `max_bytes`.
pub fn read_text(what: &str, path: &Path, max_bytes: u64) -> Result<String, InputError> {
    let shown = path.display();
    let size = regular_file(what, path)?;
    if size > max_bytes {
        return Err(InputError(format!(
            "{what} {shown}: {size} bytes; at most {max_bytes} are read"
        )));
    }
    let file = std::fs::File::open(path).map_err(|e| InputError(format!("{what} {shown}: {e}")))?;
    let mut bytes = Vec::new();
    // `take`: the file may have grown since `metadata`.
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| InputError(format!("{what} {shown}: {e}")))?;
    if bytes.len() as u64 > max_bytes {
        return Err(InputError(format!(
            "{what} {shown}: more than {max_bytes} bytes"
        )));
    }
    String::from_utf8(bytes).map_err(|_| InputError(format!("{what} {shown}: not UTF-8 text")))
}

fn png_reader(
    what: &str,
    path: &Path,
    transformations: png::Transformations,
) -> Result<png::Reader<std::io::BufReader<std::fs::File>>, InputError> {
    let shown = path.display();
    regular_file(what, path)?;
    let file = std::fs::File::open(path).map_err(|e| InputError(format!("{what} {shown}: {e}")))?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_limits(png::Limits {
        bytes: PNG_DECODER_BYTES,
    });
    decoder.set_transformations(transformations);
    decoder
        .read_info()
        .map_err(|e| InputError(format!("{what} {shown}: not a readable PNG file ({e})")))
}

/// The (width, height) in a PNG's header; nothing else is read.
pub fn png_size(what: &str, path: &Path) -> Result<(u32, u32), InputError> {
    Ok(png_reader(what, path, png::Transformations::IDENTITY)?
        .info()
        .size())
}

/// Decodes the PNG at `path` as 8-bit RGBA into `out`, which holds exactly width × height × 4
/// bytes for the `size` its header gave. Palette, grey and 16-bit pictures are converted in
/// place (expanded from the back), so no second buffer of the picture's size is allocated.
pub fn decode_png_rgba8(
    what: &str,
    path: &Path,
    size: (u32, u32),
    out: &mut [u8],
) -> Result<(), InputError> {
    let shown = path.display();
    let mut reader = png_reader(
        what,
        path,
        png::Transformations::EXPAND | png::Transformations::STRIP_16,
    )?;
    if reader.info().size() != size {
        return Err(InputError(format!(
            "{what} {shown}: the file changed while it was read"
        )));
    }
    let texels = size.0 as usize * size.1 as usize;
    let (colour, depth) = reader.output_color_type();
    let channels = match colour {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => 0,
    };
    if depth != png::BitDepth::Eight || channels == 0 || out.len() != texels * 4 {
        return Err(InputError(format!(
            "{what} {shown}: unsupported PNG colour type {colour:?} at {depth:?} bits"
        )));
    }
    reader
        .next_frame(&mut out[..texels * channels])
        .map_err(|e| InputError(format!("{what} {shown}: {e}")))?;
    expand_to_rgba(out, texels, channels);
    Ok(())
}

/// Spreads `texels` pixels of `channels` bytes at the start of `buf` to RGBA in place, from the
/// last pixel back, so no source byte is overwritten before it is read.
fn expand_to_rgba(buf: &mut [u8], texels: usize, channels: usize) {
    for i in (0..texels).rev() {
        let src = i * channels;
        let px = match channels {
            1 => [buf[src], buf[src], buf[src], 255],
            2 => [buf[src], buf[src], buf[src], buf[src + 1]],
            3 => [buf[src], buf[src + 1], buf[src + 2], 255],
            _ => return,
        };
        buf[i * 4..i * 4 + 4].copy_from_slice(&px);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expansion_in_place_matches_a_copy() {
        for channels in 1..=4 {
            let texels = 7;
            let src: Vec<u8> = (0..texels * channels).map(|i| i as u8 * 3 + 1).collect();
            let mut buf = vec![0u8; texels * 4];
            buf[..src.len()].copy_from_slice(&src);
            expand_to_rgba(&mut buf, texels, channels);
            for i in 0..texels {
                let p = &src[i * channels..(i + 1) * channels];
                let want = match channels {
                    1 => [p[0], p[0], p[0], 255],
                    2 => [p[0], p[0], p[0], p[1]],
                    3 => [p[0], p[1], p[2], 255],
                    _ => [p[0], p[1], p[2], p[3]],
                };
                assert_eq!(
                    buf[i * 4..i * 4 + 4],
                    want,
                    "channels {channels}, texel {i}"
                );
            }
        }
    }
}
