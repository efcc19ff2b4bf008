//! Numbered frame files: a printf-style pattern such as `in/%04d.png` names a sequence.

use std::path::{Path, PathBuf};

use crate::{IoError, Result};

/// A numbered file pattern: a folder, a name with one `%d` or `%0Nd` (N from 1 to 9) in it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FramePattern {
    pattern: String,
    folder: PathBuf,
    name_prefix: String,
    digits: Option<usize>,
    suffix: String,
}

impl FramePattern {
    /// Parses `pattern`; the error names it and says what a pattern looks like.
    pub fn parse(pattern: &str) -> Result<Self> {
        let bad = |what: &str| {
            IoError::format(
                Path::new(pattern),
                format!(
                    "{what}: a frame pattern holds one %d or %0Nd (N from 1 to 9) in the file name, e.g. frames/%04d.png"
                ),
            )
        };
        let percent = pattern.find('%').ok_or_else(|| bad("has no %d"))?;
        let (prefix, rest) = (&pattern[..percent], &pattern[percent + 1..]);
        let (digits, suffix) = match rest.strip_prefix('0') {
            Some(after_zero) => {
                let width =
                    after_zero.chars().next().and_then(|c| c.to_digit(10)).ok_or_else(|| bad("%0 needs a width"))?;
                let suffix = after_zero[1..].strip_prefix('d').ok_or_else(|| bad("%0N must be followed by d"))?;
                if width == 0 {
                    return Err(bad("the width of %0Nd must be 1 to 9"));
                }
                (Some(width as usize), suffix)
            }
            None => (None, rest.strip_prefix('d').ok_or_else(|| bad("% must be followed by d or 0Nd"))?),
        };
        if suffix.contains('%') {
            return Err(bad("has more than one %"));
        }
        if suffix.contains('/') || suffix.contains(std::path::MAIN_SEPARATOR) {
            return Err(bad("the number must be in the file name, not in a folder name"));
        }
        let split = prefix.rfind(['/', std::path::MAIN_SEPARATOR]);
        let (folder, name_prefix) = match split {
            Some(at) => (PathBuf::from(if at == 0 { "/" } else { &prefix[..at] }), prefix[at + 1..].to_string()),
            None => (PathBuf::from("."), prefix.to_string()),
        };
        Ok(Self { pattern: pattern.to_string(), folder, name_prefix, digits, suffix: suffix.to_string() })
    }

    /// The pattern as given.
    pub fn as_str(&self) -> &str {
        &self.pattern
    }

    /// The folder the files are in.
    pub fn folder(&self) -> &Path {
        &self.folder
    }

    /// The file of frame `number`.
    pub fn path(&self, number: u64) -> PathBuf {
        let digits = match self.digits {
            Some(width) => format!("{number:0width$}"),
            None => number.to_string(),
        };
        self.folder.join(format!("{}{digits}{}", self.name_prefix, self.suffix))
    }

    /// The frame number a file name stands for, when it matches.
    fn number_of(&self, name: &str) -> Option<u64> {
        let middle = name.strip_prefix(&self.name_prefix)?.strip_suffix(&self.suffix)?;
        if middle.is_empty() || middle.len() > 18 || !middle.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let number: u64 = middle.parse().ok()?;
        // The name must be the one `path` writes for its number: 7 is 0007 under %04d.
        (self.path(number).file_name()?.to_str()? == name).then_some(number)
    }

    /// The existing frames, by increasing number; an error when the folder cannot be read or no
    /// file matches.
    pub fn find(&self) -> Result<Vec<(u64, PathBuf)>> {
        let entries =
            std::fs::read_dir(&self.folder).map_err(|source| IoError::Io { path: self.folder.clone(), source })?;
        let mut frames: Vec<(u64, PathBuf)> = entries
            .filter_map(|entry| {
                let entry = entry.ok()?;
                let number = self.number_of(entry.file_name().to_str()?)?;
                Some((number, entry.path()))
            })
            .collect();
        if frames.is_empty() {
            return Err(IoError::format(
                Path::new(&self.pattern),
                format!("no file in {} matches the pattern (e.g. {})", self.folder.display(), self.path(1).display()),
            ));
        }
        frames.sort();
        Ok(frames)
    }

    /// [`find`](Self::find), refusing a gap in the numbering: a video's frames follow each other,
    /// and frames 2 and 50 taken as neighbours would be stylized as if nothing moved between them.
    pub fn find_consecutive(&self) -> Result<Vec<(u64, PathBuf)>> {
        let frames = self.find()?;
        if let Some(pair) = frames.windows(2).find(|pair| pair[1].0 != pair[0].0 + 1) {
            let (before, after) = (pair[0].0, pair[1].0);
            return Err(IoError::format(
                Path::new(&self.pattern),
                format!(
                    "the frames jump from {} to {} ({} numbers missing, e.g. {}); the frames must be numbered \
                     without gaps: renumber them, or move the other run of frames to its own folder",
                    before,
                    after,
                    after - before - 1,
                    self.path(before + 1).display()
                ),
            ));
        }
        Ok(frames)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_name_numbered_files_and_find_them_in_order() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["f0010.png", "f0002.png", "f0001.png", "f12.png", "f00003.png", "g0004.png", "f0005.jpg"] {
            std::fs::write(dir.path().join(name), b"x").unwrap();
        }
        let pattern = FramePattern::parse(&format!("{}/f%04d.png", dir.path().display())).unwrap();
        let found: Vec<u64> = pattern.find().unwrap().into_iter().map(|(n, _)| n).collect();
        assert_eq!(found, vec![1, 2, 10]);
        assert_eq!(pattern.path(7), dir.path().join("f0007.png"));
        let plain = FramePattern::parse(&format!("{}/f%d.png", dir.path().display())).unwrap();
        let found: Vec<u64> = plain.find().unwrap().into_iter().map(|(n, _)| n).collect();
        assert_eq!(found, vec![12]);
        for bad in ["frames.png", "f%x.png", "f%0d.png", "%04d/f.png", "f%d%d.png", "f%0.png"] {
            let error = FramePattern::parse(bad).unwrap_err().to_string();
            assert!(error.contains(bad) && error.contains("%0Nd"), "{error}");
        }
        let gap = pattern.find_consecutive().unwrap_err().to_string();
        assert!(
            gap.contains("jump from 2 to 10") && gap.contains("7 numbers missing") && gap.contains("f0003.png"),
            "{gap}"
        );
        std::fs::remove_file(dir.path().join("f0010.png")).unwrap();
        assert_eq!(pattern.find_consecutive().unwrap().len(), 2);
        let none = FramePattern::parse(&format!("{}/h%03d.png", dir.path().display())).unwrap();
        assert!(none.find().unwrap_err().to_string().contains("no file"));
    }
}
