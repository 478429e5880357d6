//! MCAP chunks opened with bounded work. The mcap crate's streaming decompression loop can
//! spin forever on a damaged zstd chunk (one zeroed byte is enough: the decoder stops making
//! progress and the loop asks it again). Here a chunk is decompressed in one call into a
//! buffer of exactly the size its header announces (refused beyond a limit), its CRC is
//! checked, and its records are split with every length checked against what is there.

use mcap::records::ChunkHeader;
use mcap::McapError;

/// Largest decompressed chunk accepted (contrail writes chunks of under 1 MiB).
pub const MAX_CHUNK_BYTES: u64 = 1 << 30;

/// The records of a chunk, decompressed and CRC-checked. `limit` caps the announced
/// decompressed size (besides [`MAX_CHUNK_BYTES`]).
pub fn expand(header: &ChunkHeader, data: &[u8], limit: u64) -> Result<Vec<u8>, McapError> {
    let size = header.uncompressed_size;
    if size > limit.min(MAX_CHUNK_BYTES) {
        return Err(McapError::ChunkTooLarge(size));
    }
    if header.compressed_size != data.len() as u64 {
        return Err(McapError::BadChunkLength {
            header: header.compressed_size,
            available: data.len() as u64,
        });
    }
    let content = match header.compression.as_str() {
        "" => data.to_vec(),
        "zstd" => zstd::bulk::decompress(data, size as usize)
            .map_err(|e| McapError::DecompressionError(format!("zstd: {e}")))?,
        "lz4" => lz4_frame(data, size)?,
        other => return Err(McapError::UnsupportedCompression(other.to_string())),
    };
    if content.len() as u64 != size {
        return Err(McapError::DecompressionError(format!(
            "chunk decompressed to {} bytes, its header says {size}",
            content.len()
        )));
    }
    if header.uncompressed_crc != 0 {
        let calculated = crc32fast::hash(&content);
        if calculated != header.uncompressed_crc {
            return Err(McapError::BadChunkCrc {
                saved: header.uncompressed_crc,
                calculated,
            });
        }
    }
    Ok(content)
}

/// An LZ4 frame decoded into at most `size + 1` bytes (the caller compares the length with
/// the header's): every read consumes input or ends, so a damaged frame is an error.
fn lz4_frame(data: &[u8], size: u64) -> Result<Vec<u8>, McapError> {
    use std::io::Read;
    let mut out = Vec::with_capacity(size as usize);
    lz4_flex::frame::FrameDecoder::new(data)
        .take(size + 1)
        .read_to_end(&mut out)
        .map_err(|e| McapError::DecompressionError(format!("lz4: {e}")))?;
    Ok(out)
}

/// Split a byte range into records `(opcode, body)`; a length that runs past the end is an
/// error. Each step consumes at least 9 bytes, so this always ends.
pub fn split<'a>(mut bytes: &'a [u8]) -> impl Iterator<Item = Result<(u8, &'a [u8]), McapError>> + 'a {
    std::iter::from_fn(move || {
        if bytes.is_empty() {
            return None;
        }
        if bytes.len() < 9 {
            bytes = &[];
            return Some(Err(McapError::UnexpectedEoc));
        }
        let opcode = bytes[0];
        let mut len = [0u8; 8];
        len.copy_from_slice(&bytes[1..9]);
        let len = u64::from_le_bytes(len);
        let rest = &bytes[9..];
        if len > rest.len() as u64 {
            bytes = &[];
            return Some(Err(McapError::RecordTooLarge { opcode, len }));
        }
        let (body, tail) = rest.split_at(len as usize);
        bytes = tail;
        Some(Ok((opcode, body)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use mcap::records::op;

    fn header(content: &[u8], data: &[u8], compression: &str) -> ChunkHeader {
        ChunkHeader {
            message_start_time: 0,
            message_end_time: 0,
            uncompressed_size: content.len() as u64,
            uncompressed_crc: crc32fast::hash(content),
            compression: compression.into(),
            compressed_size: data.len() as u64,
        }
    }

    #[test]
    fn a_damaged_lz4_chunk_is_an_error_not_a_hang() {
        use std::io::Write;
        let content: Vec<u8> = (0..20_000u32).flat_map(|i| (i % 251).to_le_bytes()).collect();
        let mut enc = lz4_flex::frame::FrameEncoder::new(Vec::new());
        enc.write_all(&content).unwrap();
        let data = enc.finish().unwrap();
        let h = header(&content, &data, "lz4");
        assert_eq!(expand(&h, &data, u64::MAX).unwrap(), content);
        for k in (0..data.len()).step_by(5) {
            let mut bad = data.clone();
            bad[k] ^= 0x5a;
            // an error, or (if the byte did not matter) the same content: never other bytes
            if let Ok(c) = expand(&h, &bad, u64::MAX) {
                assert_eq!(c, content, "byte {k}");
            }
        }
        // a frame announcing less than it holds is cut at size + 1 and refused
        let mut short = h.clone();
        short.uncompressed_size = 100;
        assert!(expand(&short, &data, u64::MAX).is_err());
    }

    #[test]
    fn a_damaged_zstd_chunk_is_an_error_not_a_hang() {
        let content: Vec<u8> = (0..20_000u32).flat_map(|i| (i % 251).to_le_bytes()).collect();
        let data = zstd::bulk::compress(&content, 3).unwrap();
        let h = header(&content, &data, "zstd");
        assert_eq!(expand(&h, &data, u64::MAX).unwrap(), content);
        for k in (0..data.len()).step_by(7) {
            let mut bad = data.clone();
            bad[k] = 0;
            if bad == data {
                continue;
            }
            // zero one byte: an error, or (if the byte did not matter) the same content
            if let Ok(c) = expand(&h, &bad, u64::MAX) {
                assert_eq!(c, content, "byte {k}");
            }
        }
        let mut big = h.clone();
        big.uncompressed_size = u64::MAX;
        assert!(matches!(
            expand(&big, &data, u64::MAX),
            Err(McapError::ChunkTooLarge(_))
        ));
    }

    #[test]
    fn split_checks_every_length() {
        let mut b = vec![op::MESSAGE];
        b.extend(3u64.to_le_bytes());
        b.extend([1, 2, 3]);
        let ok: Vec<_> = split(&b).collect::<Result<_, _>>().unwrap();
        assert_eq!(ok, vec![(op::MESSAGE, &[1u8, 2, 3][..])]);
        b[1] = 200;
        assert!(split(&b).any(|r| r.is_err()));
        assert!(split(&b[..5]).any(|r| r.is_err()));
    }
}
