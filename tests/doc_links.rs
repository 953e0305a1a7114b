//! Every relative link of the repository's documents (README.md, CHANGELOG.md, CONTRIBUTING.md
//! and every Markdown file under docs/) points to a file that exists, and every `#anchor` to a
//! heading of the file it names, with the anchors GitHub gives headings. Links to other sites
//! are not followed (the README links to none but the crate's own repository).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The documents whose links are checked, relative to the crate root.
fn documents() -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = ["README.md", "CHANGELOG.md", "CONTRIBUTING.md"]
        .iter()
        .map(PathBuf::from)
        .collect();
    let mut dirs = vec![PathBuf::from("docs")];
    while let Some(dir) = dirs.pop() {
        let full = root().join(&dir);
        for entry in std::fs::read_dir(&full).unwrap_or_else(|e| panic!("{}: {e}", full.display()))
        {
            let name = entry.expect("a directory entry").file_name();
            let path = dir.join(&name);
            if root().join(&path).is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The lines of `text` outside fenced code blocks, with their 1-based numbers.
fn prose_lines(text: &str) -> Vec<(usize, &str)> {
    let mut fenced = false;
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced {
            out.push((k + 1, line));
        }
    }
    out
}

/// `line` without its code spans (`` `a` `` and ``` ``a`b`` ```), whose brackets are not links.
fn without_code(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(start) = rest.find('`') {
        out.push_str(&rest[..start]);
        let ticks = rest[start..].chars().take_while(|&c| c == '`').count();
        let after = &rest[start + ticks..];
        let fence = "`".repeat(ticks);
        match after.find(&fence) {
            Some(end) => rest = &after[end + ticks..],
            None => {
                out.push_str(&rest[start..]);
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
}

/// The targets of the inline links and images `[text](target)` of one line of prose.
fn link_targets(line: &str) -> Vec<String> {
    let line = without_code(line);
    let mut out = Vec::new();
    let mut rest = line.as_str();
    while let Some(k) = rest.find("](") {
        let after = &rest[k + 2..];
        match after.find(')') {
            Some(end) => {
                out.push(after[..end].trim().to_string());
                rest = &after[end + 1..];
            }
            None => break,
        }
    }
    out
}

/// The anchor GitHub gives a heading: lower case, every character but letters, digits,
/// spaces, hyphens and underscores dropped, spaces turned into hyphens.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|&c| c.is_alphanumeric() || c == ' ' || c == '-' || c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of every heading of a Markdown text; repeated headings get `-1`, `-2`, … as
/// on GitHub.
fn anchors(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for (_, line) in prose_lines(text) {
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if hashes == 0 || hashes > 6 || !line[hashes..].starts_with(' ') {
            continue;
        }
        let base = slug(&line[hashes..]);
        let mut anchor = base.clone();
        let mut n = 0;
        while out.contains(&anchor) {
            n += 1;
            anchor = format!("{base}-{n}");
        }
        out.insert(anchor);
    }
    out
}

fn read(path: &Path) -> String {
    let full = root().join(path);
    std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("{}: {e}", full.display()))
}

#[test]
fn every_relative_link_and_anchor_of_the_documents_resolves() {
    let mut broken = Vec::new();
    let mut checked = 0;
    for document in documents() {
        let text = read(&document);
        let dir = document.parent().unwrap_or(Path::new(""));
        for (number, line) in prose_lines(&text) {
            for target in link_targets(line) {
                if target.contains("://") || target.starts_with("mailto:") {
                    continue;
                }
                checked += 1;
                let (file, anchor) = match target.split_once('#') {
                    Some((file, anchor)) => (file, Some(anchor)),
                    None => (target.as_str(), None),
                };
                let linked = if file.is_empty() {
                    document.clone()
                } else {
                    dir.join(file)
                };
                let where_ = format!("{}:{number}: `{target}`", document.display());
                if !root().join(&linked).exists() {
                    broken.push(format!("{where_}: no file {}", linked.display()));
                    continue;
                }
                if let Some(anchor) = anchor {
                    if linked.extension().is_none_or(|e| e != "md") {
                        broken.push(format!(
                            "{where_}: an anchor into a file that is not Markdown"
                        ));
                    } else if !anchors(&read(&linked)).contains(anchor) {
                        broken.push(format!(
                            "{where_}: no heading with the anchor #{anchor} in {}",
                            linked.display()
                        ));
                    }
                }
            }
        }
    }
    assert!(
        broken.is_empty(),
        "{} broken links:\n{}",
        broken.len(),
        broken.join("\n")
    );
    // The guide alone links its chapters to each other dozens of times.
    assert!(
        checked > 50,
        "only {checked} relative links found: is the parser blind?"
    );
}

/// The README must stand alone: its only links outside the repository go to the crate's own.
#[test]
fn the_readme_links_outside_the_repository_only_to_the_crate() {
    let text = read(Path::new("README.md"));
    for (number, line) in prose_lines(&text) {
        for target in link_targets(line) {
            if target.contains("://") {
                assert!(
                    target.starts_with("https://github.com/ocean-fft/ocean-fft"),
                    "README.md:{number}: a link outside the repository: {target}"
                );
            }
        }
    }
}

#[test]
fn the_parser_and_the_anchors_are_those_of_github() {
    assert_eq!(
        slug("The same bits on every machine: `Determinism::CrossPlatform`"),
        "the-same-bits-on-every-machine-determinismcrossplatform"
    );
    assert_eq!(
        slug("Engines: axes, units and textures"),
        "engines-axes-units-and-textures"
    );
    assert_eq!(
        slug("Reading the buffers with an engine's types"),
        "reading-the-buffers-with-an-engines-types"
    );
    assert_eq!(slug("`FoamConfig` reference"), "foamconfig-reference");
    let text = "# A\n\n## B c\n\n```rust\n# hidden\n#[derive(Debug)]\n```\n\n## B c\n";
    let found: Vec<String> = anchors(text).into_iter().collect();
    assert_eq!(found, ["a", "b-c", "b-c-1"]);
    assert_eq!(
        link_targets("see [x](a.md#b), `[no](link)` and ![i](img/p.png) [t](c)"),
        ["a.md#b", "img/p.png", "c"]
    );
    assert_eq!(without_code("a ``b`c`` d `e` f"), "a  d  f");
    assert_eq!(prose_lines("x\n```\n[a](b)\n```\ny"), [(1, "x"), (5, "y")]);
}
