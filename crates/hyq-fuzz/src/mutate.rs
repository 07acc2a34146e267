//! Mutators of valid-ish inputs: a seed file (a bundled profile, URDF, configuration, policy,
//! record or ledger) with a few edits of the kinds that broke loaders before. Numbers become
//! the awkward ones (±1.7e308, 1e39, subnormals, NaN, huge integers); strings become empty,
//! long or full of control characters; lines and elements are deleted, duplicated, repeated
//! hundreds of times or nested thousands deep; bytes are inserted and files cut short. Every
//! choice comes from a seeded ChaCha8 stream, so a seed replays its input exactly.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Numbers that overflow, underflow or sit on a boundary somewhere in the project.
pub const NUMBERS: [&str; 40] = [
    "0",
    "-0.0",
    "1",
    "-1",
    "2",
    "0.5",
    "1e-3",
    "1e-4",
    "1e-8",
    "1e-12",
    "1e-30",
    "1e-46",
    "5e-324",
    "1e-300",
    "100",
    "-100",
    "100.0000001",
    "99.999",
    "1000",
    "1e4",
    "1e6",
    "1e9",
    "1e12",
    "1e30",
    "3.4028235e38",
    "1e39",
    "-1e39",
    "8.99e307",
    "1.7e308",
    "-1.7e308",
    "1e308",
    "1e400",
    "nan",
    "inf",
    "-inf",
    "9223372036854775807",
    "18446744073709551616",
    "6.283185307179586",
    "-1e308",
    "1e",
];

/// Strings that are empty, long, or hold what a terminal or a parser would act on.
const STRINGS: [&str; 9] = [
    "",
    "x\u{1b}[31mRED\u{1b}[0m",
    "a\nhyq: fake",
    "two words",
    "../../../../etc/passwd",
    "/dev/zero",
    "\u{202e}evil",
    "\"quoted\"",
    "lf_haa",
];

/// The syntax of an input, which decides the structural edits that apply to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Syntax {
    /// TOML (configuration, profile, ledger).
    Toml,
    /// XML (URDF).
    Xml,
    /// JSON lines (step records).
    Jsonl,
}

/// `seed` with one to four random edits (see the module docs).
pub fn mutate_text(seed: &str, syntax: Syntax, rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut text = seed.as_bytes().to_vec();
    let edits = rng.random_range(1..=4);
    for _ in 0..edits {
        text = match rng.random_range(0..12u32) {
            0..=3 => replace_number(&text, rng),
            4 => replace_string(&text, rng),
            5 => delete_line(&text, rng),
            6 => duplicate_line(&text, rng),
            7 => insert_bytes(&text, rng),
            8 => truncate(&text, rng),
            9 if syntax == Syntax::Xml => nest(&text, rng),
            10 if syntax == Syntax::Xml => repeat_element(&text, rng),
            10 if syntax == Syntax::Jsonl => repeat_lines(&text, rng),
            _ => replace_number(&text, rng),
        };
    }
    text
}

/// Where the numbers of `text` are: (start, end) of each run that reads as a number and does
/// not continue a name (`lf_haa2`, `e1`).
pub fn number_spans(text: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let c = text[i];
        let starts = c.is_ascii_digit()
            || ((c == b'-' || c == b'+') && text.get(i + 1).is_some_and(u8::is_ascii_digit));
        let after_name = i > 0 && (text[i - 1].is_ascii_alphanumeric() || text[i - 1] == b'_');
        if starts && !after_name {
            let start = i;
            i += 1;
            while i < text.len()
                && (text[i].is_ascii_digit() || matches!(text[i], b'.' | b'e' | b'E' | b'+' | b'-'))
            {
                i += 1;
            }
            spans.push((start, i));
        } else {
            i += 1;
        }
    }
    spans
}

fn splice(text: &[u8], start: usize, end: usize, with: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(text.len() + with.len());
    out.extend_from_slice(&text[..start]);
    out.extend_from_slice(with);
    out.extend_from_slice(&text[end..]);
    out
}

fn replace_number(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let spans = number_spans(text);
    if spans.is_empty() {
        return text.to_vec();
    }
    let (start, end) = spans[rng.random_range(0..spans.len())];
    let value = NUMBERS[rng.random_range(0..NUMBERS.len())];
    splice(text, start, end, value.as_bytes())
}

fn replace_string(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let quotes: Vec<usize> = text
        .iter()
        .enumerate()
        .filter(|(_, b)| **b == b'"')
        .map(|(i, _)| i)
        .collect();
    if quotes.len() < 2 {
        return text.to_vec();
    }
    // A pair of consecutive quotes: usually a string's two ends.
    let k = rng.random_range(0..quotes.len() - 1);
    let (start, end) = (quotes[k] + 1, quotes[k + 1]);
    let value = match rng.random_range(0..4u32) {
        0 => "a".repeat(rng.random_range(60..3000)),
        _ => STRINGS[rng.random_range(0..STRINGS.len())]
            .replace('\n', "\\n")
            .replace('\u{1b}', "\\u001b"),
    };
    splice(text, start, end, value.as_bytes())
}

/// (start, end) of each line, its newline included.
fn lines(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, b) in text.iter().enumerate() {
        if *b == b'\n' {
            out.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < text.len() {
        out.push((start, text.len()));
    }
    out
}

fn delete_line(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let l = lines(text);
    if l.is_empty() {
        return text.to_vec();
    }
    let (start, end) = l[rng.random_range(0..l.len())];
    splice(text, start, end, b"")
}

fn duplicate_line(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let l = lines(text);
    if l.is_empty() {
        return text.to_vec();
    }
    let (start, end) = l[rng.random_range(0..l.len())];
    let copy = text[start..end].to_vec();
    splice(text, end, end, &copy)
}

fn repeat_lines(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let l = lines(text);
    if l.is_empty() {
        return text.to_vec();
    }
    let (start, end) = l[rng.random_range(0..l.len())];
    let copy = text[start..end].repeat(rng.random_range(2..200));
    splice(text, end, end, &copy)
}

fn insert_bytes(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    const PIECES: [&[u8]; 12] = [
        b"\n",
        b"\0",
        b"\"",
        b"[",
        b"]",
        b"<",
        b">",
        b"=",
        b"\xff\xfe",
        b"{",
        b"}",
        b"\r\n",
    ];
    let at = rng.random_range(0..=text.len());
    let piece: Vec<u8> = if rng.random_bool(0.5) {
        PIECES[rng.random_range(0..PIECES.len())].to_vec()
    } else {
        (0..rng.random_range(1..16)).map(|_| rng.random()).collect()
    };
    splice(text, at, at, &piece)
}

fn truncate(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    text[..rng.random_range(0..=text.len())].to_vec()
}

/// Wraps the text between two elements in `<a>`…`</a>` nested up to tens of thousands deep.
fn nest(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let depth = [2, 30, 65, 1000, 30_000][rng.random_range(0..5)];
    let closes: Vec<usize> = text
        .windows(2)
        .enumerate()
        .filter(|(_, w)| w == b">\n")
        .map(|(i, _)| i + 2)
        .collect();
    if closes.is_empty() {
        return text.to_vec();
    }
    let at = closes[rng.random_range(0..closes.len())];
    let mut piece = b"<a>".repeat(depth);
    piece.extend(b"</a>".repeat(depth));
    splice(text, at, at, &piece)
}

/// Repeats a `<link …>…</link>` element (renamed each time) up to past the link cap, with a
/// fixed joint each, so the tree stays connected.
fn repeat_element(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let Ok(s) = std::str::from_utf8(text) else {
        return text.to_vec();
    };
    let Some(end) = s.rfind("</robot>") else {
        return text.to_vec();
    };
    let count = [3, 200, 1001][rng.random_range(0..3)];
    let mut extra = String::new();
    for i in 0..count {
        extra.push_str(&format!(
            "<link name=\"fz{i}\"><collision><geometry><sphere radius=\"0.01\"/></geometry>\
             </collision></link><joint name=\"fzj{i}\" type=\"fixed\"><parent link=\"trunk\"/>\
             <child link=\"fz{i}\"/></joint>\n"
        ));
    }
    splice(text, end, end, extra.as_bytes())
}

/// A safetensors file with a few edits: its JSON header mutated as text (shapes, offsets,
/// dtypes, metadata), its length prefix kept or broken, tensor bytes set to NaN, ±inf, huge or
/// subnormal float32 values, or the file cut or extended.
pub fn mutate_safetensors(seed: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for _ in 0..rng.random_range(1..=3) {
        bytes = match rng.random_range(0..6u32) {
            0 | 1 => mutate_header(&bytes, rng),
            2 | 3 => poke_float(&bytes, rng),
            4 => truncate(&bytes, rng),
            _ => {
                // A header length of random bytes (most far beyond the file).
                let mut b = bytes.clone();
                let n = b.len().min(8);
                b[..n].iter_mut().for_each(|x| *x = rng.random());
                b
            }
        };
    }
    bytes
}

fn header_span(bytes: &[u8]) -> Option<(usize, usize)> {
    let len = u64::from_le_bytes(bytes.get(..8)?.try_into().ok()?);
    let end = 8usize.checked_add(usize::try_from(len).ok()?)?;
    (end <= bytes.len()).then_some((8, end))
}

fn mutate_header(bytes: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let Some((start, end)) = header_span(bytes) else {
        return bytes.to_vec();
    };
    let Ok(header) = std::str::from_utf8(&bytes[start..end]) else {
        return bytes.to_vec();
    };
    let new_header = match rng.random_range(0..3u32) {
        0 => replace_string(header.as_bytes(), rng),
        _ => replace_number(header.as_bytes(), rng),
    };
    let mut out = Vec::with_capacity(bytes.len() + new_header.len());
    // Usually the length prefix follows the new header, so the parser reads it.
    let len = if rng.random_bool(0.9) {
        new_header.len() as u64
    } else {
        (end - start) as u64
    };
    out.extend_from_slice(&len.to_le_bytes());
    out.extend_from_slice(&new_header);
    out.extend_from_slice(&bytes[end..]);
    out
}

fn poke_float(bytes: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let Some((_, data)) = header_span(bytes) else {
        return bytes.to_vec();
    };
    let mut out = bytes.to_vec();
    if out.len() < data + 4 {
        return out;
    }
    let slots = (out.len() - data) / 4;
    let at = data + 4 * rng.random_range(0..slots);
    let value: f32 = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MAX,
        -f32::MAX,
        1e-45,
        1e30,
        0.0,
    ][rng.random_range(0..8)];
    out[at..at + 4].copy_from_slice(&value.to_le_bytes());
    out
}

/// A height file (`.npy` or PNG) with a few edits: a `.npy` header's dtype, shape or order
/// replaced (its length kept right, or not), a value set to NaN, ±inf or a huge one, a PNG's
/// size, bit depth or colour type rewritten (with a valid checksum, so the decoder reads it),
/// bytes inserted, or the file cut short.
pub fn mutate_height_file(seed: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for _ in 0..rng.random_range(1..=3) {
        bytes = match rng.random_range(0..6u32) {
            0 | 1 if bytes.starts_with(b"\x93NUMPY") => npy_header(&bytes, rng),
            0 | 1 => png_header(&bytes, rng),
            2 | 3 => poke_f64(&bytes, rng),
            4 => insert_bytes(&bytes, rng),
            _ => truncate(&bytes, rng),
        };
    }
    bytes
}

/// A version-1 `.npy` file with one header field replaced by an awkward value.
fn npy_header(bytes: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    const FIELDS: [(&str, &[&str]); 3] = [
        (
            "'descr': ",
            &[
                "'<f4'", "'>f8'", "'|u1'", "'<i8'", "'<f2'", "'|b1'", "'<U8'", "'<c16'", "'<f'",
                "'x'",
            ],
        ),
        (
            "'shape': ",
            &[
                "(3, 4)",
                "(0, 4)",
                "(1048577, 1)",
                "(1024, 1025)",
                "(7,)",
                "(2, 2, 2)",
                "(18446744073709551615, 2)",
                "(-1, 2)",
                "()",
                "(9, 7",
            ],
        ),
        ("'fortran_order': ", &["True", "False", "1", "None"]),
    ];
    let Some(len) = bytes
        .get(8..10)
        .map(|b| usize::from(u16::from_le_bytes([b[0], b[1]])))
    else {
        return bytes.to_vec();
    };
    let Some(header) = bytes
        .get(10..10 + len)
        .and_then(|h| std::str::from_utf8(h).ok())
    else {
        return bytes.to_vec();
    };
    let (tag, values) = FIELDS[rng.random_range(0..FIELDS.len())];
    let Some(start) = header.find(tag).map(|i| i + tag.len()) else {
        return bytes.to_vec();
    };
    let end = header[start..]
        .find(", '")
        .or_else(|| header[start..].find(", }"))
        .map_or(header.len(), |i| start + i);
    let value = values[rng.random_range(0..values.len())];
    let new = format!("{}{value}{}", &header[..start], &header[end..]);
    // Usually the length field follows the new header, so the parser reads it.
    let new_len = if rng.random_bool(0.9) { new.len() } else { len };
    let mut out = bytes[..8].to_vec();
    out.extend_from_slice(&u16::try_from(new_len).unwrap_or(u16::MAX).to_le_bytes());
    out.extend_from_slice(new.as_bytes());
    out.extend_from_slice(&bytes[10 + len..]);
    out
}

/// A PNG whose header chunk (IHDR) has its width, height, bit depth or colour type replaced,
/// its checksum recomputed.
fn png_header(bytes: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    // The signature (8), the chunk's length (4) and type (4), 13 bytes of data, its CRC (4).
    if bytes.len() < 33 || &bytes[12..16] != b"IHDR" {
        return bytes.to_vec();
    }
    let mut out = bytes.to_vec();
    match rng.random_range(0..4u32) {
        0 | 1 => {
            let at = 16 + 4 * rng.random_range(0..2usize);
            let size: u32 = [0, 1, 2, 1025, 1 << 20, 0x7fff_ffff, u32::MAX][rng.random_range(0..7)];
            out[at..at + 4].copy_from_slice(&size.to_be_bytes());
        }
        2 => out[24] = [1, 2, 4, 8, 16, 3, 0][rng.random_range(0..7)],
        _ => out[25] = [0, 2, 3, 4, 6, 1, 7][rng.random_range(0..7)],
    }
    let crc = crc32(&out[12..29]);
    out[29..33].copy_from_slice(&crc.to_be_bytes());
    out
}

/// The CRC-32 of PNG chunks (ISO 3309, reflected polynomial 0xEDB88320).
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = u32::MAX;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A file with one 8-byte slot past its first 64 bytes (a `.npy` file's values) set to an
/// awkward float64.
fn poke_f64(bytes: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut out = bytes.to_vec();
    if out.len() < 72 {
        return out;
    }
    let at = 64 + 8 * rng.random_range(0..(out.len() - 64) / 8);
    let value: f64 = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MAX,
        1e300,
        5e-324,
        101.0,
        -0.0,
    ][rng.random_range(0..8)];
    out[at..at + 8].copy_from_slice(&value.to_le_bytes());
    out
}

/// A ChaCha8 stream for case `case` of a run seeded with `seed`.
pub fn case_rng(seed: u64, case: u64) -> ChaCha8Rng {
    use rand::SeedableRng;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(case);
    rng
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_found_but_not_inside_names() {
        let spans = number_spans(b"lf_haa2 = -1.5e3, x = 4\n");
        assert_eq!(spans, vec![(10, 16), (22, 23)]);
    }

    #[test]
    fn png_checksums_are_the_standards() {
        // The CRC of an IEND chunk's type, as every PNG file ends with it.
        assert_eq!(crc32(b"IEND"), 0xAE42_6082);
    }

    #[test]
    fn a_seed_replays_its_mutation() {
        let seed = "a = 1\nb = \"x\"\n";
        let one = mutate_text(seed, Syntax::Toml, &mut case_rng(7, 3));
        let two = mutate_text(seed, Syntax::Toml, &mut case_rng(7, 3));
        assert_eq!(one, two);
    }
}
