//! Frame lists in render-farm syntax: `1-100`, `1-3,5,7-20:2` (also `7-20x2`, Deadline's step).

use std::fmt;

/// A sorted list of distinct frame numbers, parsed from render-farm syntax.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameList(Vec<u32>);

/// Why a frame list did not parse; its message quotes the offending item.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameRangeError(String);

impl fmt::Display for FrameRangeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for FrameRangeError {}

impl FrameList {
    /// Most frames one list may hold.
    pub const MAX_FRAMES: usize = 1_000_000;
    /// Largest frame number: frame times stay exact in f64 and names stay short.
    pub const MAX_FRAME: u32 = 99_999_999;

    /// Parses comma-separated items, each `N`, `A-B` (A ≤ B, both included) or `A-B:S` /
    /// `A-BxS` (every S-th frame from A, S ≥ 1). Frames are whole numbers from 0 to
    /// [`MAX_FRAME`](Self::MAX_FRAME); spaces around items are allowed; overlapping items
    /// are merged.
    ///
    /// # Errors
    /// A [`FrameRangeError`] quoting the item that is empty, not a number, negative,
    /// reversed, with a step of 0, beyond [`MAX_FRAME`](Self::MAX_FRAME), or that makes the
    /// list longer than [`MAX_FRAMES`](Self::MAX_FRAMES).
    pub fn parse(text: &str) -> Result<FrameList, FrameRangeError> {
        let err = |item: &str, why: &str| FrameRangeError(format!("`{item}`: {why}"));
        if text.trim().is_empty() {
            return Err(FrameRangeError(
                "empty frame list (expected e.g. `1-100` or `1-3,5,7-20:2`)".into(),
            ));
        }
        let mut frames = Vec::new();
        for raw in text.split(',') {
            let item = raw.trim();
            if item.is_empty() {
                return Err(err(
                    raw,
                    "empty item (two commas in a row, or a trailing comma)",
                ));
            }
            if item.starts_with('-') {
                return Err(err(item, "frames are whole numbers ≥ 0"));
            }
            let (span, step) = match item.split_once([':', 'x']) {
                Some((span, step)) => {
                    let step = number(step.trim()).map_err(|why| err(item, &why))?;
                    if step == 0 {
                        return Err(err(item, "the step must be at least 1"));
                    }
                    (span.trim(), step)
                }
                None => (item, 1),
            };
            let (first, last) = match span.split_once('-') {
                Some((a, b)) => (
                    number(a.trim()).map_err(|why| err(item, &why))?,
                    number(b.trim()).map_err(|why| err(item, &why))?,
                ),
                None => {
                    if step != 1 {
                        return Err(err(item, "a step needs a range `A-B:S`"));
                    }
                    let n = number(span).map_err(|why| err(item, &why))?;
                    (n, n)
                }
            };
            if first > last {
                return Err(err(
                    item,
                    "the range is reversed (write the smaller frame first)",
                ));
            }
            let count = (last - first) / step + 1;
            if frames.len() + count as usize > Self::MAX_FRAMES {
                return Err(err(
                    item,
                    &format!("more than {} frames in the list", Self::MAX_FRAMES),
                ));
            }
            frames.extend((first..=last).step_by(step as usize));
        }
        frames.sort_unstable();
        frames.dedup();
        Ok(FrameList(frames))
    }

    /// The frames, ascending, each once.
    pub fn frames(&self) -> &[u32] {
        &self.0
    }
}

/// A frame number or step: digits only, at most [`FrameList::MAX_FRAME`].
fn number(text: &str) -> Result<u32, String> {
    if text.is_empty() {
        return Err("a number is missing".into());
    }
    if !text.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!("`{text}` is not a whole number ≥ 0"));
    }
    match text.parse::<u64>() {
        Ok(n) if n <= u64::from(FrameList::MAX_FRAME) => Ok(n as u32),
        _ => Err(format!(
            "`{text}` is beyond the last frame {}",
            FrameList::MAX_FRAME
        )),
    }
}

impl std::str::FromStr for FrameList {
    type Err = FrameRangeError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        FrameList::parse(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Vec<u32> {
        FrameList::parse(s).unwrap().frames().to_vec()
    }

    fn error(s: &str) -> String {
        FrameList::parse(s).unwrap_err().to_string()
    }

    #[test]
    fn plain_ranges_and_single_frames() {
        assert_eq!(parse("1-5"), [1, 2, 3, 4, 5]);
        assert_eq!(parse("7"), [7]);
        assert_eq!(parse("0-0"), [0]);
        assert_eq!(parse("1-100").len(), 100);
        assert_eq!(parse("1-100")[99], 100);
    }

    #[test]
    fn the_render_farm_example() {
        // 1-3, 5, then 7, 9, …, 19 (20 is not on the step).
        assert_eq!(
            parse("1-3,5,7-20:2"),
            [1, 2, 3, 5, 7, 9, 11, 13, 15, 17, 19]
        );
        // Deadline writes the step with `x`; spaces around items are fine.
        assert_eq!(parse(" 1-3 , 5 , 7-20x2 "), parse("1-3,5,7-20:2"));
        assert_eq!(parse("10-20:5"), [10, 15, 20]);
        assert_eq!(parse("10-10:3"), [10]);
    }

    #[test]
    fn overlaps_are_merged_and_sorted() {
        assert_eq!(parse("5-7,1-3,6,2"), [1, 2, 3, 5, 6, 7]);
    }

    #[test]
    fn errors_name_the_item() {
        assert!(error("").contains("empty frame list"));
        assert!(error("1,,2").contains("empty item"));
        assert!(error("1-3,").contains("empty item"));
        assert!(error("a-3").contains("`a` is not a whole number"));
        assert!(error("1.5").contains("`1.5` is not a whole number"));
        assert!(error("-5").contains("`-5`: frames are whole numbers ≥ 0"));
        assert!(error("10-1").contains("`10-1`: the range is reversed"));
        assert!(error("1-10:0").contains("`1-10:0`: the step must be at least 1"));
        assert!(error("1-10:").contains("a number is missing"));
        assert!(error("1-").contains("a number is missing"));
        assert!(error("5:2").contains("a step needs a range"));
        assert!(error("1-2-3").contains("`2-3` is not a whole number"));
        assert!(error("100000000").contains("beyond the last frame"));
        assert!(error("99999999999999999999999").contains("beyond the last frame"));
        assert!(error("0-2000000").contains("more than 1000000 frames"));
        // The largest list still parses.
        assert_eq!(parse("0-999999").len(), FrameList::MAX_FRAMES);
        assert_eq!(parse("99999999"), [FrameList::MAX_FRAME]);
    }
}
