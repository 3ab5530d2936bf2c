//! The bytes of a glTF file's buffers, resolved without trusting the file.
//!
//! A buffer is the GLB binary chunk, a `data:` URI, or a relative path to a regular file inside
//! the folder of the `.gltf`/`.glb` (after resolving `..` and symbolic links). Anything else is
//! refused: absolute paths, `file:` and other schemes, paths leaving the folder, devices, FIFOs
//! and folders. At most `byteLength` bytes are read from a file, so `/dev/zero`-like or huge
//! files cannot exhaust memory. Every error names the buffer's URI.

use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// Longest part of a URI quoted in an error message (data URIs can be megabytes long).
const QUOTED_URI_CHARS: usize = 80;

/// The data of every buffer of `document`, in buffer order, each exactly `byteLength` long.
///
/// `gltf_path` is the file being read (its folder is the only place external buffers may
/// come from); `blob` is the GLB binary chunk, if any.
///
/// # Errors
/// A message naming the buffer and its URI: a refused URI (see the module docs), a file that
/// cannot be opened or read, invalid base64, or fewer bytes than `byteLength`.
pub(super) fn buffers(
    document: &gltf::Document,
    gltf_path: &Path,
    mut blob: Option<Vec<u8>>,
) -> Result<Vec<Vec<u8>>, String> {
    let mut folder: Option<PathBuf> = None;
    let mut out = Vec::new();
    for buffer in document.buffers() {
        let length = buffer.length();
        let (data, uri) = match buffer.source() {
            gltf::buffer::Source::Bin => {
                let data = blob.take().ok_or_else(|| {
                    format!(
                        "buffer {} has no uri and there is no (further) GLB binary chunk",
                        buffer.index()
                    )
                })?;
                (data, None)
            }
            gltf::buffer::Source::Uri(uri) => {
                let data = if let Some(data) = uri.strip_prefix("data:") {
                    data_uri(data)
                } else {
                    let folder = match &folder {
                        Some(f) => f,
                        None => folder.insert(folder_of(gltf_path)?),
                    };
                    file_uri(uri, folder, length)
                };
                let data = data.map_err(|reason| {
                    format!(
                        "buffer {} (uri \"{}\") {reason}",
                        buffer.index(),
                        quoted(uri)
                    )
                })?;
                (data, Some(uri))
            }
        };
        if data.len() < length {
            let source = match uri {
                Some(uri) => format!("(uri \"{}\")", quoted(uri)),
                None => "(GLB binary chunk)".to_string(),
            };
            return Err(format!(
                "buffer {} {source} holds {} bytes but its byteLength is {length}",
                buffer.index(),
                data.len()
            ));
        }
        let mut data = data;
        data.truncate(length);
        out.push(data);
    }
    Ok(out)
}

/// The canonical folder of the glTF file.
pub(super) fn folder_of(gltf_path: &Path) -> Result<PathBuf, String> {
    let folder = match gltf_path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    folder
        .canonicalize()
        .map_err(|e| format!("cannot resolve the folder {}: {e}", folder.display()))
}

/// At most [`QUOTED_URI_CHARS`] characters of `uri`, with an ellipsis when cut.
fn quoted(uri: &str) -> String {
    match uri.char_indices().nth(QUOTED_URI_CHARS) {
        Some((cut, _)) => format!("{}...", &uri[..cut]),
        None => uri.to_string(),
    }
}

/// Decodes the part of a `data:` URI after `data:`: `[<media type>][;base64],<data>`.
fn data_uri(rest: &str) -> Result<Vec<u8>, String> {
    let (header, payload) = rest
        .split_once(',')
        .ok_or("is a data URI without a ',' before its data")?;
    if header.ends_with(";base64") {
        base64(payload)
    } else {
        percent_decoded(payload)
    }
}

/// Standard base64 (RFC 4648 section 4), padding optional, ASCII whitespace ignored.
fn base64(text: &str) -> Result<Vec<u8>, String> {
    fn value(c: u8) -> Option<u32> {
        match c {
            b'A'..=b'Z' => Some(u32::from(c - b'A')),
            b'a'..=b'z' => Some(u32::from(c - b'a') + 26),
            b'0'..=b'9' => Some(u32::from(c - b'0') + 52),
            b'+' => Some(62),
            b'/' => Some(63),
            _ => None,
        }
    }
    let digits: Vec<u8> = text.bytes().filter(|c| !c.is_ascii_whitespace()).collect();
    let unpadded = digits
        .iter()
        .rposition(|&c| c != b'=')
        .map_or(0, |last| last + 1);
    if digits.len() - unpadded > 2 || unpadded % 4 == 1 {
        return Err("has invalid base64 data (wrong length or padding)".into());
    }
    let mut out = Vec::with_capacity(unpadded / 4 * 3 + 2);
    for (n, chunk) in digits[..unpadded].chunks(4).enumerate() {
        let mut bits = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            let v = value(c).ok_or_else(|| {
                format!(
                    "has invalid base64 data: byte {c:#04x} at digit {}",
                    4 * n + k
                )
            })?;
            bits |= v << (18 - 6 * k);
        }
        let bytes = bits.to_be_bytes();
        out.extend_from_slice(&bytes[1..chunk.len()]);
    }
    Ok(out)
}

/// The bytes of a percent-encoded string (`%41` is `A`; other bytes stay as they are).
fn percent_decoded(text: &str) -> Result<Vec<u8>, String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or("has a '%' not followed by two hexadecimal digits")?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    Ok(out)
}

/// Reads at most `length` bytes of the file a relative URI names inside `folder` (canonical).
fn file_uri(uri: &str, folder: &Path, length: usize) -> Result<Vec<u8>, String> {
    let target = resolve_file(uri, folder)?;
    let metadata = std::fs::metadata(&target).map_err(|e| format!("cannot be opened: {e}"))?;
    if metadata.len() < length as u64 {
        return Err(format!(
            "holds {} bytes but its byteLength is {length}",
            metadata.len()
        ));
    }
    read_at_most(&target, length as u64)
}

/// The canonical path of the regular file a relative URI names inside `folder` (canonical):
/// schemes, absolute paths, paths leading outside the folder (after `..` and symbolic links)
/// and anything but a regular file are refused, with a message saying why.
pub(super) fn resolve_file(uri: &str, folder: &Path) -> Result<PathBuf, String> {
    const ONLY: &str = "files must be data: URIs or relative paths to files in the folder of \
                        the input file";
    let first_segment = uri.split(['/', '\\', '?', '#']).next().unwrap_or("");
    if first_segment.contains(':') {
        return Err(format!(
            "is refused: URI schemes such as file: are not read; {ONLY}"
        ));
    }
    let decoded = String::from_utf8(percent_decoded(uri)?)
        .map_err(|_| "is not UTF-8 after percent-decoding".to_string())?;
    let relative = Path::new(&decoded);
    if decoded.is_empty()
        || decoded.contains('\0')
        || decoded.starts_with(['/', '\\'])
        || relative.is_absolute()
        || relative
            .components()
            .any(|c| matches!(c, Component::RootDir | Component::Prefix(_)))
    {
        return Err(format!("is refused: absolute paths are not read; {ONLY}"));
    }
    let target = folder
        .join(relative)
        .canonicalize()
        .map_err(|e| format!("cannot be opened: {e}"))?;
    if !target.starts_with(folder) {
        return Err(format!(
            "is refused: it leads outside {} (to {}); {ONLY}",
            folder.display(),
            target.display()
        ));
    }
    let metadata = std::fs::metadata(&target).map_err(|e| format!("cannot be opened: {e}"))?;
    if !metadata.is_file() {
        return Err(format!(
            "is refused: {} is not a regular file",
            target.display()
        ));
    }
    Ok(target)
}

/// Reads at most `limit` bytes of the regular file `target`; more is an error when the file
/// was not expected to be longer (`limit` is a cap, not a length).
pub(super) fn read_at_most(target: &Path, limit: u64) -> Result<Vec<u8>, String> {
    let file = std::fs::File::open(target).map_err(|e| format!("cannot be opened: {e}"))?;
    // The file may have been replaced between the check and the opening.
    let metadata = file
        .metadata()
        .map_err(|e| format!("cannot be opened: {e}"))?;
    if !metadata.is_file() {
        return Err(format!(
            "is refused: {} is not a regular file",
            target.display()
        ));
    }
    let mut data = Vec::with_capacity(metadata.len().min(limit) as usize);
    file.take(limit)
        .read_to_end(&mut data)
        .map_err(|e| format!("cannot be read: {e}"))?;
    Ok(data)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_padded_unpadded_and_rejects_garbage() {
        assert_eq!(base64("TWFu").unwrap(), b"Man");
        assert_eq!(base64("TWE=").unwrap(), b"Ma");
        assert_eq!(base64("TQ==").unwrap(), b"M");
        assert_eq!(base64("TQ").unwrap(), b"M");
        assert_eq!(base64("").unwrap(), b"");
        assert_eq!(base64("AAEC/w==").unwrap(), [0, 1, 2, 255]);
        assert!(base64("T").is_err());
        assert!(base64("TW!u").is_err());
        assert!(base64("TQ===").is_err());
    }

    #[test]
    fn data_uris_decode_base64_and_percent_encoding() {
        assert_eq!(
            data_uri("application/octet-stream;base64,AAEC").unwrap(),
            [0, 1, 2]
        );
        assert_eq!(data_uri(",a%20b").unwrap(), b"a b");
        assert!(data_uri("no comma").is_err());
    }

    #[test]
    fn long_uris_are_cut_in_messages() {
        let long = "x".repeat(1000);
        assert_eq!(quoted(&long).len(), QUOTED_URI_CHARS + 3);
        assert_eq!(quoted("a.bin"), "a.bin");
    }
}
