//! The Rust blocks of the guide's chapters (docs/guide/*.md) that rustdoc does not run
//! (`rust,ignore`) are honest: each is either a verbatim copy of a region of a crate in
//! clients/ (or of the Bevy plugin's example) that CI compiles, or says why it is not
//! compiled. Every other ```rust block of a
//! chapter is a doc-test: src/lib.rs includes each chapter that has one (`guide_doc_tests`).
//!
//! In a chapter, the line before an ignored block is an HTML comment, either
//! `<!-- verbatim: PATH NAME -->` (the block equals the lines between `// guide: NAME` and
//! `// guide: end` in PATH, minus their common indentation) or `<!-- not compiled: WHY -->`.
//! Every region in the clients must be quoted somewhere, so that none is left behind.

use std::collections::BTreeSet;
use std::path::Path;

/// The guide's directory, relative to the crate root.
const GUIDE_DIR: &str = "docs/guide";

/// The files whose `// guide:` regions the guide quotes.
const SOURCES: &[&str] = &[
    "clients/glam-0.33/src/lib.rs",
    "clients/engines-wgpu/src/lib.rs",
    "clients/engines-macroquad/src/lib.rs",
    "bevy_ocean_fft/examples/sea.rs",
];

/// A fenced code block of a chapter: its info string, the closest non-blank line above its
/// opening fence, its content and the line it starts on (1-based).
struct Block<'a> {
    info: &'a str,
    above: &'a str,
    content: String,
    line: usize,
}

fn blocks(text: &str) -> Vec<Block<'_>> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut k = 0;
    while k < lines.len() {
        if let Some(info) = lines[k].strip_prefix("```") {
            let above = lines[..k].iter().rev().find(|l| !l.trim().is_empty());
            let end = (k + 1..lines.len())
                .find(|&e| lines[e].starts_with("```"))
                .unwrap_or_else(|| panic!("line {}: unclosed code block", k + 1));
            out.push(Block {
                info: info.trim(),
                above: above.map_or("", |l| l.trim()),
                content: lines[k + 1..end].iter().map(|l| format!("{l}\n")).collect(),
                line: k + 1,
            });
            k = end + 1;
        } else {
            k += 1;
        }
    }
    out
}

/// The lines between `// guide: NAME` and the next `// guide: end` of `source`, with their
/// common indentation removed.
fn region(source: &str, name: &str) -> Option<String> {
    let lines: Vec<&str> = source.lines().collect();
    let start = lines
        .iter()
        .position(|l| l.trim() == format!("// guide: {name}"))?;
    let end = start
        + lines[start..]
            .iter()
            .position(|l| l.trim() == "// guide: end")?;
    let body = &lines[start + 1..end];
    let indent = body
        .iter()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.len() - l.trim_start().len())
        .min()
        .unwrap_or(0);
    Some(
        body.iter()
            .map(|l| format!("{}\n", l.get(indent..).unwrap_or("")))
            .collect(),
    )
}

/// Every region name of `source`.
fn region_names(source: &str) -> Vec<String> {
    source
        .lines()
        .filter_map(|l| l.trim().strip_prefix("// guide: "))
        .filter(|name| *name != "end")
        .map(str::to_owned)
        .collect()
}

fn read(path: &str) -> String {
    let full = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("{}: {e}", full.display()))
}

/// Every chapter of the guide: its path relative to the crate root and its text, by name.
fn chapters() -> Vec<(String, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(GUIDE_DIR);
    let mut paths: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.expect("a directory entry").file_name())
        .filter_map(|name| name.to_str().map(str::to_owned))
        .filter(|name| name.ends_with(".md"))
        .map(|name| format!("{GUIDE_DIR}/{name}"))
        .collect();
    paths.sort();
    assert!(paths.len() > 5, "the guide's chapters are gone? {paths:?}");
    paths
        .into_iter()
        .map(|path| {
            let text = read(&path);
            (path, text)
        })
        .collect()
}

#[test]
fn ignored_guide_blocks_are_verbatim_copies_of_compiled_code_or_say_why_not() {
    let mut quoted = BTreeSet::new();
    let mut ignored = 0;
    for (chapter, text) in chapters() {
        check_ignored_blocks(&chapter, &text, &mut quoted, &mut ignored);
    }
    assert!(
        ignored >= 5,
        "the guide's engine section is gone? ({ignored} ignored blocks)"
    );
    for path in SOURCES {
        for name in region_names(&read(path)) {
            assert!(
                quoted.contains(&format!("{path} {name}")),
                "region `{name}` of {path} is quoted nowhere in the guide"
            );
        }
    }
}

/// Checks the `rust,ignore` blocks of one chapter, counting them in `ignored` and adding each
/// region they quote to `quoted`.
fn check_ignored_blocks(
    chapter: &str,
    text: &str,
    quoted: &mut BTreeSet<String>,
    ignored: &mut usize,
) {
    for block in blocks(text) {
        if !block.info.starts_with("rust") || !block.info.contains("ignore") {
            continue;
        }
        *ignored += 1;
        let marker = block
            .above
            .strip_prefix("<!--")
            .and_then(|m| m.strip_suffix("-->"))
            .map(str::trim)
            .unwrap_or_else(|| {
                panic!(
                    "{chapter} line {}: a `{}` block needs `<!-- verbatim: PATH NAME -->` or \
                     `<!-- not compiled: WHY -->` on the line before it",
                    block.line, block.info
                )
            });
        if let Some(why) = marker.strip_prefix("not compiled:") {
            assert!(
                why.trim().len() > 10,
                "{chapter} line {}: say why the block is not compiled",
                block.line
            );
        } else if let Some(reference) = marker.strip_prefix("verbatim:") {
            let (path, name) = reference
                .trim()
                .split_once(' ')
                .unwrap_or_else(|| panic!("{chapter} line {}: `verbatim: PATH NAME`", block.line));
            assert!(
                SOURCES.contains(&path),
                "{chapter} line {}: {path} is not in SOURCES",
                block.line
            );
            let source = read(path);
            let code = region(&source, name).unwrap_or_else(|| {
                panic!(
                    "{chapter} line {}: no region `// guide: {name}` in {path}",
                    block.line
                )
            });
            if block.content != code {
                let first = block
                    .content
                    .lines()
                    .zip(code.lines())
                    .position(|(a, b)| a != b)
                    .unwrap_or(block.content.lines().count().min(code.lines().count()));
                panic!(
                    "{chapter} line {}: the block differs from `{name}` in {path} from its line {} on \
                     (guide: {:?}, source: {:?}); copy the source into the guide",
                    block.line,
                    first + 1,
                    block.content.lines().nth(first),
                    code.lines().nth(first)
                );
            }
            quoted.insert(format!("{path} {name}"));
        } else {
            panic!("{chapter} line {}: unknown marker `{marker}`", block.line);
        }
    }
}

/// Every chapter with a Rust block rustdoc runs is included by src/lib.rs, so that its blocks
/// are doc-tests; a chapter without one is not (its include would test nothing).
#[test]
fn every_chapter_with_rust_blocks_is_a_doc_test() {
    let lib = read("src/lib.rs");
    for (chapter, text) in chapters() {
        let runs = blocks(&text)
            .iter()
            .any(|b| b.info.split(',').next() == Some("rust") && !b.info.contains("ignore"));
        let included = lib.contains(&format!("include_str!(\"../{chapter}\")"));
        assert_eq!(
            runs,
            included,
            "{chapter}: {} Rust blocks to run, {} by src/lib.rs (mod guide_doc_tests)",
            if runs { "has" } else { "has no" },
            if included { "included" } else { "not included" }
        );
    }
}

#[test]
fn the_parser_sees_what_it_should() {
    let text = "a\n\n<!-- verbatim: p n -->\n```rust,ignore\nfn f() {}\n```\n```text\nx\n```\n";
    let found = blocks(text);
    assert_eq!(found.len(), 2);
    assert_eq!(found[0].info, "rust,ignore");
    assert_eq!(found[0].above, "<!-- verbatim: p n -->");
    assert_eq!(found[0].content, "fn f() {}\n");
    assert_eq!(found[0].line, 4);
    assert_eq!(found[1].above, "```");
    let source = "x\n    // guide: n\n    fn f() {\n        1\n    }\n    // guide: end\n";
    assert_eq!(region(source, "n").unwrap(), "fn f() {\n    1\n}\n");
    assert_eq!(region_names(source), ["n"]);
    assert!(region(source, "m").is_none());
}
