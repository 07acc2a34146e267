//! Reading the files users give the project, every one through the same size-capped reader.
//!
//! A configuration, a robot profile, a URDF, a trained policy, a comparison ledger and the step
//! records `hyq plot` reads may come from anyone, and a path may name `/dev/zero`, a FIFO that
//! no one writes to or a file of gigabytes. Only a regular file is read ([`open`], the one rule
//! of every loader, the terrain's height files included): a FIFO would block its reader
//! forever and a device may never end. Each kind of file has a cap ([`FileKind`], one table:
//! [`KINDS`]) far above any real file of its kind; the reader refuses a file past it from its
//! size, stops one byte past it if the file grows while it is read, and says so, instead of
//! reading until memory runs out. Records are read line by line
//! ([`read_line`]), with a cap per line as well as on the whole file.
//!
//! What a parser would choke on is checked here too, before it runs: the nesting depth of an
//! XML text ([`check_xml_depth`]), which a recursive parser would follow until the stack
//! overflows (an abort that no error handling can catch, killing a Python interpreter).

use std::io::{self, BufRead, Read};
use std::path::Path;

/// A kind of user file and the largest such file read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FileKind {
    /// What the file is, in messages ("URDF", "robot profile").
    pub what: &'static str,
    /// The largest file read (bytes).
    pub max_bytes: u64,
    /// The longest line read (bytes), for files read line by line; `max_bytes` otherwise.
    pub max_line_bytes: u64,
}

const MIB: u64 = 1 << 20;

/// A TOML configuration (`--config`, Python's `config_file=`): 1 MiB, hundreds of times any
/// real configuration.
pub const CONFIG: FileKind = FileKind {
    what: "configuration",
    max_bytes: MIB,
    max_line_bytes: MIB,
};

/// A robot profile: 1 MiB, two hundred times the bundled ones.
pub const ROBOT_PROFILE: FileKind = FileKind {
    what: "robot profile",
    max_bytes: MIB,
    max_line_bytes: MIB,
};

/// A URDF: 8 MiB, a hundred and fifty times ANYmal C's (with its 79 links).
pub const URDF: FileKind = FileKind {
    what: "URDF",
    max_bytes: 8 * MIB,
    max_line_bytes: 8 * MIB,
};

/// A trained policy (safetensors): 256 MiB, 64 million float32 parameters, hundreds of times a
/// locomotion policy.
pub const POLICY: FileKind = FileKind {
    what: "policy",
    max_bytes: 256 * MIB,
    max_line_bytes: 256 * MIB,
};

/// A comparison ledger (TOML): 4 MiB, fifty times the bundled one.
pub const LEDGER: FileKind = FileKind {
    what: "ledger",
    max_bytes: 4 * MIB,
    max_line_bytes: 4 * MIB,
};

/// A JSONL file of step records (`hyq plot`): lines of at most 1 MiB (several hundred times a
/// step record), 4 GiB in all (millions of steps).
pub const RECORDS: FileKind = FileKind {
    what: "step record",
    max_bytes: 4096 * MIB,
    max_line_bytes: MIB,
};

/// A terrain's height file (`terrain.file`, `.npy` or PNG): a grid at the cap of
/// [`crate::terrain::MAX_GRID_POINTS`] heights in `f64`, plus 64 KiB for a header.
pub const HEIGHT_FILE: FileKind = FileKind {
    what: "height file",
    max_bytes: 8 * crate::terrain::MAX_GRID_POINTS as u64 + 65_536,
    max_line_bytes: 8 * crate::terrain::MAX_GRID_POINTS as u64 + 65_536,
};

/// Every kind of user file, as the README's "Bad input" table lists them.
pub const KINDS: [&FileKind; 7] = [
    &CONFIG,
    &ROBOT_PROFILE,
    &URDF,
    &POLICY,
    &LEDGER,
    &RECORDS,
    &HEIGHT_FILE,
];

/// A size in bytes as the messages give it: `8 MiB`, `4096 MiB`, `512 bytes`.
pub fn size_text(bytes: u64) -> String {
    if bytes >= MIB && bytes.is_multiple_of(MIB) {
        format!("{} MiB", bytes / MIB)
    } else {
        format!("{bytes} bytes")
    }
}

/// The error for a file of `kind` past its cap.
fn too_large(kind: &FileKind) -> io::Error {
    io::Error::new(
        io::ErrorKind::FileTooLarge,
        format!(
            "larger than {}, which no {} is (is it the right file?)",
            size_text(kind.max_bytes),
            kind.what
        ),
    )
}

/// Why a path that is not a regular file is refused, in words that follow the path.
pub const NOT_A_FILE: &str = "is not a regular file (a FIFO, device, socket or directory): \
                              only files are read, since a pipe would block its reader forever \
                              and a device may never end";

/// Opens a user's file for reading, refusing anything but a regular file ([`NOT_A_FILE`],
/// [`io::ErrorKind::InvalidInput`]), the one rule of every loader: a FIFO with no writer would
/// block `open()` forever, and a blocked `open()` cannot even be interrupted from Python. The
/// path is checked before it is opened, and the opened file again, opened without waiting for
/// a writer, so a FIFO swapped in between is refused too rather than waited on.
pub fn open(path: &Path) -> io::Result<std::fs::File> {
    let not_a_file = || io::Error::new(io::ErrorKind::InvalidInput, NOT_A_FILE);
    if !std::fs::metadata(path)?.is_file() {
        return Err(not_a_file());
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // For a regular file O_NONBLOCK changes nothing; for a FIFO it makes `open()` return
        // at once instead of waiting for a writer.
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path)?;
    if !file.metadata()?.is_file() {
        return Err(not_a_file());
    }
    Ok(file)
}

/// The bytes of a file of `kind`, reading at most one byte past its cap. Errors: the operating
/// system's (missing, no permission), [`NOT_A_FILE`] for anything but a regular file
/// ([`open`]), or [`io::ErrorKind::FileTooLarge`] with a message saying the cap.
pub fn read_bytes(path: &Path, kind: &FileKind) -> io::Result<Vec<u8>> {
    let file = open(path)?;
    if file.metadata()?.len() > kind.max_bytes {
        return Err(too_large(kind));
    }
    let mut bytes = Vec::new();
    file.take(kind.max_bytes + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > kind.max_bytes {
        return Err(too_large(kind));
    }
    Ok(bytes)
}

/// The text of a file of `kind` ([`read_bytes`], then UTF-8, or [`io::ErrorKind::InvalidData`]
/// saying where it is not).
pub fn read_text(path: &Path, kind: &FileKind) -> io::Result<String> {
    String::from_utf8(read_bytes(path, kind)?).map_err(|e| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("not UTF-8 text: {}", e.utf8_error()),
        )
    })
}

/// What [`read_line`] read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Line {
    /// The input has ended: nothing was read.
    End,
    /// A line, `ended` if it ends with a newline (else it is the input's unterminated last).
    Read {
        /// Whether the line ends with `\n`.
        ended: bool,
    },
    /// The line is longer than the kind's `max_line_bytes`; it was not read further.
    TooLong,
    /// The lines read so far, with this one, pass the kind's `max_bytes`.
    TooMuch,
}

/// Reads one line of a file of `kind` into `line` (cleared first), at most `max_line_bytes`
/// and one more, counting the bytes read in `total` (across calls) against `max_bytes`.
pub fn read_line(
    reader: &mut impl BufRead,
    kind: &FileKind,
    line: &mut Vec<u8>,
    total: &mut u64,
) -> io::Result<Line> {
    line.clear();
    let read = reader
        .take(kind.max_line_bytes + 1)
        .read_until(b'\n', line)?;
    if read == 0 {
        return Ok(Line::End);
    }
    *total += read as u64;
    let ended = line.last() == Some(&b'\n');
    if !ended && line.len() as u64 > kind.max_line_bytes {
        return Ok(Line::TooLong);
    }
    if *total > kind.max_bytes {
        return Ok(Line::TooMuch);
    }
    Ok(Line::Read { ended })
}

/// The deepest element nesting an XML robot description may have: a URDF needs 5 levels
/// (robot, link, collision, geometry, box), vendor extensions (`<gazebo>` plugins) a few more.
pub const XML_MAX_DEPTH: usize = 64;

/// Checks that no element of `text` is nested deeper than `max_depth`, before any parser reads
/// it: a recursive parser (RustyXML, serde's deserialisers) overflows the stack on a few
/// thousand levels, and a stack overflow aborts the process. Comments, CDATA sections,
/// processing instructions, declarations and quoted attribute values are skipped; the scan
/// never undercounts an element a parser would open (a malformed text may be overcounted, and
/// is refused by the parser anyway). Returns the reason, with the line, when it is too deep.
pub fn check_xml_depth(text: &str, max_depth: usize) -> Result<(), String> {
    let bytes = text.as_bytes();
    let mut depth = 0usize;
    let mut i = 0;
    let skip_past = |from: usize, end: &[u8]| -> usize {
        bytes[from..]
            .windows(end.len())
            .position(|w| w == end)
            .map_or(bytes.len(), |p| from + p + end.len())
    };
    while let Some(p) = bytes[i..].iter().position(|&b| b == b'<') {
        let start = i + p;
        let rest = &bytes[start..];
        if rest.starts_with(b"<!--") {
            i = skip_past(start + 4, b"-->");
        } else if rest.starts_with(b"<![CDATA[") {
            i = skip_past(start + 9, b"]]>");
        } else if rest.starts_with(b"<?") {
            i = skip_past(start + 2, b"?>");
        } else if rest.starts_with(b"<!") {
            i = skip_declaration(bytes, start + 2);
        } else if rest.starts_with(b"</") {
            depth = depth.saturating_sub(1);
            i = skip_past(start + 2, b">");
        } else {
            let (end, self_closing) = tag_end(bytes, start + 1);
            if !self_closing {
                depth += 1;
                if depth > max_depth {
                    let line = 1 + bytes[..start].iter().filter(|&&b| b == b'\n').count();
                    return Err(format!(
                        "elements are nested more than {max_depth} deep (line {line}); a robot \
                         description needs a handful of levels"
                    ));
                }
            }
            i = end;
        }
    }
    Ok(())
}

/// The index past the `>` closing the start tag whose name begins at `from`, skipping quoted
/// attribute values, and whether the tag closes itself (`/>`).
fn tag_end(bytes: &[u8], from: usize) -> (usize, bool) {
    let mut quote: Option<u8> = None;
    for (k, &b) in bytes.iter().enumerate().skip(from) {
        match (quote, b) {
            (Some(q), _) if b == q => quote = None,
            (Some(_), _) => {}
            (None, b'"' | b'\'') => quote = Some(b),
            (None, b'>') => return (k + 1, k > from && bytes[k - 1] == b'/'),
            _ => {}
        }
    }
    (bytes.len(), false)
}

/// The index past a `<!…>` declaration starting at `from` (after `<!`), its internal subset in
/// brackets and quoted strings included.
fn skip_declaration(bytes: &[u8], from: usize) -> usize {
    let mut quote: Option<u8> = None;
    let mut brackets = 0usize;
    for (k, &b) in bytes.iter().enumerate().skip(from) {
        match (quote, b) {
            (Some(q), _) if b == q => quote = None,
            (Some(_), _) => {}
            (None, b'"' | b'\'') => quote = Some(b),
            (None, b'[') => brackets += 1,
            (None, b']') => brackets = brackets.saturating_sub(1),
            (None, b'>') if brackets == 0 => return k + 1,
            _ => {}
        }
    }
    bytes.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nesting_is_counted_past_comments_quotes_and_self_closing_tags() {
        let ok = "<?xml version=\"1.0\"?><!DOCTYPE r [<!ENTITY a \"<b>\">]><robot name='a>b'>\
                  <!-- <x><x><x> --><link/><link><![CDATA[<y><y>]]></link></robot>";
        assert_eq!(check_xml_depth(ok, 2), Ok(()));
        assert!(check_xml_depth(ok, 1).is_err());
        let deep = format!("<robot>\n{}{}</robot>", "<a>".repeat(65), "</a>".repeat(65));
        let e = check_xml_depth(&deep, XML_MAX_DEPTH).expect_err("66 levels");
        assert!(e.contains("more than 64 deep (line 2)"), "{e}");
    }

    #[test]
    fn a_line_past_its_cap_is_not_read_further() {
        let kind = FileKind {
            what: "test",
            max_bytes: 20,
            max_line_bytes: 4,
        };
        let mut input = io::Cursor::new(b"abc\nabcdefgh\n".to_vec());
        let (mut line, mut total) = (Vec::new(), 0);
        let first = read_line(&mut input, &kind, &mut line, &mut total).expect("reads");
        assert_eq!(first, Line::Read { ended: true });
        let second = read_line(&mut input, &kind, &mut line, &mut total).expect("reads");
        assert_eq!((second, line.len()), (Line::TooLong, 5));
        let mut many = io::Cursor::new(b"abc\n".repeat(6));
        total = 0;
        let mut last = Line::End;
        for _ in 0..6 {
            last = read_line(&mut many, &kind, &mut line, &mut total).expect("reads");
        }
        assert_eq!(last, Line::TooMuch);
    }
}
