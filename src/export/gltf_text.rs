//! glTF as JSON text (`.gltf`) with its binary data embedded as a base64 `data:` URI.

use super::ExportError;
use serde_json::{json, Value};

/// The `.gltf` (JSON) form of GLB bytes: the same document, its binary chunk embedded as the
/// first buffer's `data:application/octet-stream;base64,` URI, so the file stands alone. The
/// same GLB gives the same text.
///
/// # Errors
/// [`ExportError::InvalidSource`] when `glb` is not a GLB container (header, JSON chunk,
/// optional BIN chunk) or its JSON is invalid.
///
/// # Example
/// ```
/// use skelfit::export::gltf_text_from_glb;
/// let glb = b"glTF\x02\x00\x00\x00\x2c\x00\x00\x00\x0c\x00\x00\x00JSON{\"asset\":{}}\x04\x00\x00\x00BIN\x00\x01\x02\x03\x04";
/// let text = gltf_text_from_glb(glb).unwrap();
/// let json: serde_json::Value = serde_json::from_slice(&text).unwrap();
/// assert_eq!(json["buffers"][0]["uri"], "data:application/octet-stream;base64,AQIDBA==");
/// ```
pub fn gltf_text_from_glb(glb: &[u8]) -> Result<Vec<u8>, ExportError> {
    let invalid = |message: &str| ExportError::InvalidSource {
        message: format!("not a GLB container: {message}"),
    };
    let word = |at: usize| -> Option<u32> {
        Some(u32::from_le_bytes(glb.get(at..at + 4)?.try_into().ok()?))
    };
    if glb.get(0..4) != Some(b"glTF") {
        return Err(invalid("no glTF magic"));
    }
    let json_len = word(12).ok_or_else(|| invalid("truncated header"))? as usize;
    let json_bytes = glb
        .get(20..20 + json_len)
        .ok_or_else(|| invalid("truncated JSON chunk"))?;
    let mut document: Value =
        serde_json::from_slice(json_bytes).map_err(|e| invalid(&e.to_string()))?;
    let bin_at = 20 + json_len;
    if let Some(bin_len) = word(bin_at) {
        let bin = glb
            .get(bin_at + 8..bin_at + 8 + bin_len as usize)
            .ok_or_else(|| invalid("truncated BIN chunk"))?;
        let length = document
            .get("buffers")
            .and_then(|b| b.get(0))
            .and_then(|b| b.get("byteLength"))
            .and_then(Value::as_u64)
            .map_or(bin.len(), |n| (n as usize).min(bin.len()));
        let embedded = json!({
            "byteLength": length,
            "uri": format!("data:application/octet-stream;base64,{}", base64(&bin[..length])),
        });
        // A document without a buffers array (or with an empty one) gets one for the chunk.
        let Some(map) = document.as_object_mut() else {
            return Err(invalid("the JSON chunk is not an object"));
        };
        match map.get_mut("buffers").and_then(Value::as_array_mut) {
            Some(buffers) if !buffers.is_empty() => buffers[0] = embedded,
            Some(buffers) => buffers.push(embedded),
            None => {
                map.insert("buffers".into(), json!([embedded]));
            }
        }
    }
    serde_json::to_vec(&document).map_err(|e| invalid(&e.to_string()))
}

/// Standard base64 (RFC 4648 section 4) with padding.
fn base64(data: &[u8]) -> String {
    const DIGITS: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(data.len().div_ceil(3) * 4);
    for chunk in data.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let bits = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(DIGITS[(bits >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_examples() {
        for (plain, encoded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), encoded);
        }
    }
}
