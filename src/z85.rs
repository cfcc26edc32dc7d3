//! Z85 (ZeroMQ RFC 32), the text the web page carries its gzipped bytes in: 5 characters per 4
//! bytes (25 % over the bytes, against base64's 33 %), and none of them a quote or a backslash,
//! so the text sits in a JS string literal as it is. A page opened from `file://` can read no
//! binary file, so the wasm and the bundle travel as such text (`cli/export_web.rs`); the page's
//! decoder is the loop in its `index.html`.
//! RFC 32 wants a multiple of 4 bytes: `encode` pads with zeros and the page is told the true
//! length (gzip refuses trailing bytes).

/// RFC 32's alphabet, digit value = index.
const ALPHABET: &[u8; 85] =
    b"0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.-:+=^!/*?&<>()[]{}@%$#";

/// `bytes` as Z85, zero-padded to a multiple of 4 bytes.
pub fn encode(bytes: &[u8]) -> String {
    let mut text = String::with_capacity(bytes.len().div_ceil(4) * 5);
    for chunk in bytes.chunks(4) {
        let mut word = [0u8; 4];
        word[..chunk.len()].copy_from_slice(chunk);
        let mut value = u32::from_be_bytes(word);
        let mut digits = [0u8; 5];
        for d in digits.iter_mut().rev() {
            *d = ALPHABET[(value % 85) as usize];
            value /= 85;
        }
        text.extend(digits.iter().map(|&c| char::from(c)));
    }
    text
}

/// The bytes of Z85 `text`, the first `len` of them (the rest is `encode`'s padding).
pub fn decode(text: &str, len: usize) -> Result<Vec<u8>, String> {
    let text = text.as_bytes();
    if text.len() % 5 != 0 || len > text.len() / 5 * 4 {
        return Err(format!(
            "{} characters of Z85 cannot hold {len} bytes",
            text.len()
        ));
    }
    let mut bytes = Vec::with_capacity(text.len() / 5 * 4);
    for (i, group) in text.chunks(5).enumerate() {
        let mut value: u64 = 0;
        for (j, &c) in group.iter().enumerate() {
            let digit = ALPHABET
                .iter()
                .position(|&a| a == c)
                .ok_or_else(|| format!("{:?} at {} is not Z85", char::from(c), i * 5 + j))?;
            value = value * 85 + digit as u64;
        }
        let word = u32::try_from(value)
            .map_err(|_| format!("group {} at {} is over 2³² − 1", i, i * 5))?;
        bytes.extend_from_slice(&word.to_be_bytes());
    }
    bytes.truncate(len);
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// RFC 32's own test vector.
    #[test]
    fn rfc_32_hello_world() {
        let bytes = [0x86, 0x4F, 0xD2, 0x6F, 0xB5, 0x59, 0xF7, 0x5B];
        assert_eq!(encode(&bytes), "HelloWorld");
        assert_eq!(decode("HelloWorld", 8).unwrap(), bytes);
    }

    #[test]
    fn every_length_and_byte_round_trips() {
        let all: Vec<u8> = (0..=255u8).chain((0..=255u8).rev()).collect();
        for len in 0..all.len() {
            let text = encode(&all[..len]);
            assert_eq!(text.len(), len.div_ceil(4) * 5);
            assert!(!text.contains(['"', '\\', '\'', '\n']));
            assert_eq!(decode(&text, len).unwrap(), &all[..len], "length {len}");
        }
        // the largest group, 0xFFFFFFFF
        assert_eq!(encode(&[0xFF; 4]), "%nSc0");
    }

    #[test]
    fn damaged_text_is_refused() {
        assert!(decode("Hello", 8).is_err());
        assert!(decode("Hell\"", 4).unwrap_err().contains("not Z85"));
        assert!(decode("#####", 4).unwrap_err().contains("over"));
    }
}
