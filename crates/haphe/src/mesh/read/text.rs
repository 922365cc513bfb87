//! The tokenizer of the text formats (OBJ, OFF, ASCII STL): physical lines with their
//! 1-based numbers, and the white-space separated tokens of a line or of a whole text.

/// Physical lines of a byte slice with their 1-based numbers (`\n` ends a line; a `\r`
/// before it is left in place and treated as white space).
#[derive(Clone)]
pub(super) struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Lines<'a> {
    /// The lines of `bytes`, the first numbered `first_line`.
    pub(super) fn new(bytes: &'a [u8], first_line: usize) -> Lines<'a> {
        Lines {
            bytes,
            pos: 0,
            line: first_line.saturating_sub(1),
        }
    }

    /// The next line and its number.
    pub(super) fn next_line(&mut self) -> Option<(usize, &'a [u8])> {
        if self.pos >= self.bytes.len() {
            return None;
        }
        let rest = &self.bytes[self.pos..];
        let len = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        self.pos += len + 1;
        self.line += 1;
        Some((self.line, &rest[..len]))
    }

    /// Whether every line has been read.
    pub(super) fn at_end(&self) -> bool {
        self.pos >= self.bytes.len()
    }

    /// The number of the last line read (0 before the first).
    pub(super) fn line(&self) -> usize {
        self.line
    }
}

/// White-space separated tokens of a line.
pub(super) fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
}

/// The tokens of a text, one after the other across lines, each with its line number.
#[derive(Clone)]
pub(super) struct Words<'a> {
    lines: Lines<'a>,
    /// What is left of the current line.
    rest: &'a [u8],
}

impl<'a> Words<'a> {
    /// The tokens of `bytes`, whose first line is numbered `first_line`.
    pub(super) fn new(bytes: &'a [u8], first_line: usize) -> Words<'a> {
        Words {
            lines: Lines::new(bytes, first_line),
            rest: &[],
        }
    }

    /// The next token and its line number.
    pub(super) fn next_word(&mut self) -> Option<(usize, &'a [u8])> {
        loop {
            let start = self.rest.iter().position(|b| !b.is_ascii_whitespace());
            if let Some(start) = start {
                let rest = &self.rest[start..];
                let len = rest
                    .iter()
                    .position(u8::is_ascii_whitespace)
                    .unwrap_or(rest.len());
                self.rest = &rest[len..];
                return Some((self.lines.line(), &rest[..len]));
            }
            let (_, line) = self.lines.next_line()?;
            self.rest = line;
        }
    }

    /// Whether the next token is `word` (without reading it).
    pub(super) fn peek_is(&self, word: &[u8]) -> bool {
        self.clone().next_word().is_some_and(|(_, w)| w == word)
    }

    /// The rest of the current line, skipped (a name after a keyword).
    pub(super) fn rest_of_line(&mut self) -> &'a [u8] {
        std::mem::take(&mut self.rest)
    }

    /// The line after the last one read: where a text that ends too early is cut.
    pub(super) fn end_line(&self) -> usize {
        self.lines.line() + 1
    }
}

/// Lossy text of a token, for error messages.
pub(super) fn show(token: &[u8]) -> String {
    String::from_utf8_lossy(token).into_owned()
}

pub(super) fn skip_ascii_whitespace(bytes: &[u8]) -> &[u8] {
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    &bytes[start..]
}

pub(super) fn starts_with_word(bytes: &[u8], word: &[u8]) -> bool {
    bytes.starts_with(word)
        && bytes
            .get(word.len())
            .is_none_or(|b| b.is_ascii_whitespace())
}
