//! The source layout of src/ (CONTRIBUTING.md, "Source layout"), checked:
//!
//! 1. no Rust file is longer than [`MAX_LINES`] lines;
//! 2. no circle of imports: no module uses a sibling module (another child of the same
//!    parent, file or folder) that uses it back, directly or around a longer circle. Every
//!    path `crate::…`, `super::…`, `self::…` or `child::…` of the non-test code counts, in a
//!    `use` or in an expression (and the `"crate::…"` paths of serde's attributes); a path
//!    through a re-export counts as a use of the module that defines the item. A module and
//!    its own children (a folder's `mod.rs` and the files in it) may use each other, as the
//!    module tree nests them;
//! 3. nothing below the crate root reaches an item through the crate root's re-exports
//!    (`crate::Spectrum`): it names the module that defines it, test code included.
//!
//! The tree checked is the crate's src/, or the one the environment variable
//! `OCEAN_FFT_LAYOUT_SRC` names (to run the checks on another checkout).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Most lines a file of src/ may have.
const MAX_LINES: usize = 600;

fn src() -> PathBuf {
    match std::env::var_os("OCEAN_FFT_LAYOUT_SRC") {
        Some(dir) => PathBuf::from(dir),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
    }
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut dirs = vec![dir.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        let entries = std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        for entry in entries {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// A token of Rust source once comments and literals are gone.
#[derive(Debug, Clone, PartialEq)]
enum Token {
    Ident(String),
    /// `::`
    PathSep,
    Punct(char),
    /// A string literal's contents (escapes left as written).
    Str(String),
}

/// The tokens of `text`: identifiers, `::`, punctuation and string literals, without comments
/// (doc comments included), char literals, numbers and lifetimes.
fn tokens(text: &str) -> Vec<Token> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    let ident_char = |c: char| c.is_alphanumeric() || c == '_';
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == '"' || ((c == 'r' || c == 'b') && starts_string(&chars, i)) {
            // Byte and raw prefixes, then the literal.
            let mut raw = false;
            while chars[i] != '"' && chars[i] != '#' {
                raw |= chars[i] == 'r';
                i += 1;
            }
            let mut hashes = 0;
            while chars[i] == '#' {
                hashes += 1;
                i += 1;
            }
            i += 1;
            let start = i;
            loop {
                if !raw && chars[i] == '\\' {
                    i += 2;
                } else if chars[i] == '"' && (0..hashes).all(|h| chars.get(i + 1 + h) == Some(&'#'))
                {
                    break;
                } else {
                    i += 1;
                }
            }
            out.push(Token::Str(chars[start..i].iter().collect()));
            i += 1 + hashes;
        } else if c == '\'' {
            if next == Some('\\') {
                // An escaped char literal.
                i += 2;
                while chars[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if chars.get(i + 2) == Some(&'\'') {
                i += 3;
            } else {
                // A lifetime or a label.
                i += 1;
                while i < chars.len() && ident_char(chars[i]) {
                    i += 1;
                }
            }
        } else if c.is_ascii_digit() {
            while i < chars.len() && (ident_char(chars[i]) || chars[i] == '.') {
                // Not a range's dots (`0..n`) nor a method call (`1.0.max(…)`).
                if chars[i] == '.' && !chars.get(i + 1).is_some_and(char::is_ascii_digit) {
                    break;
                }
                i += 1;
            }
        } else if ident_char(c) {
            let start = i;
            while i < chars.len() && ident_char(chars[i]) {
                i += 1;
            }
            out.push(Token::Ident(chars[start..i].iter().collect()));
        } else if c == ':' && next == Some(':') {
            out.push(Token::PathSep);
            i += 2;
        } else {
            if !c.is_whitespace() {
                out.push(Token::Punct(c));
            }
            i += 1;
        }
    }
    out
}

/// Whether a string literal with a `b`, `r` or `br` prefix starts at `i`.
fn starts_string(chars: &[char], i: usize) -> bool {
    if i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_') {
        return false;
    }
    let mut j = i;
    if chars[j] == 'b' {
        j += 1;
    }
    if chars.get(j) == Some(&'r') {
        j += 1;
        while chars.get(j) == Some(&'#') {
            j += 1;
        }
    }
    j > i && chars.get(j) == Some(&'"')
}

/// A path found in a module's code.
#[derive(Debug, Clone)]
struct Reference {
    /// The segments as written (`super`, `crate`, …).
    written: Vec<String>,
    /// The module the path is written in (its file's, or an inline module's).
    scope: Vec<String>,
    /// Whether it is test code (`#[cfg(test)]`).
    test: bool,
}

/// One module of the crate.
#[derive(Debug, Default)]
struct Module {
    /// The file it is in (inline modules: their file's), as `src/…`.
    file: PathBuf,
    /// Whether it is a file of its own (not an inline `mod x { … }`).
    is_file: bool,
    /// Whether it is test code (`#[cfg(test)]`, or inside such a module).
    test: bool,
    /// Names a `pub use` / `pub(crate) use` makes visible, with the absolute path they
    /// stand for (resolved later).
    reexports: BTreeMap<String, Vec<String>>,
    /// Paths of the code into the crate (files only; inline modules' paths are their file's).
    references: Vec<Reference>,
}

type Crate = BTreeMap<Vec<String>, Module>;

/// The module tree from src/lib.rs down, following `mod` declarations (and `#[path]`).
fn load(src: &Path) -> Crate {
    let mut modules = Crate::new();
    let mut pending = vec![(Vec::new(), src.join("lib.rs"), false)];
    while let Some((path, file, test)) = pending.pop() {
        let text =
            std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        // Where this file's child modules live: beside lib.rs and mod.rs, in a folder named
        // after the module otherwise.
        let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("");
        let dir = file.parent().expect("a file in a folder").to_path_buf();
        let children_dir = if name == "lib.rs" || name == "mod.rs" {
            dir.clone()
        } else {
            dir.join(name.trim_end_matches(".rs"))
        };
        let parsed = parse(&tokens(&text), &path, test);
        let shown = Path::new("src").join(file.strip_prefix(src).unwrap_or(&file));
        for (child, (child_test, child_path)) in &parsed.files {
            let mut child_module = path.clone();
            child_module.push(child.clone());
            let child_file = match child_path {
                Some(relative) => dir.join(relative),
                None => {
                    let flat = children_dir.join(format!("{child}.rs"));
                    if flat.exists() {
                        flat
                    } else {
                        children_dir.join(child).join("mod.rs")
                    }
                }
            };
            pending.push((child_module, child_file, *child_test));
        }
        for (inline, inline_test) in &parsed.inline {
            let entry = modules.entry(inline.clone()).or_default();
            entry.file = shown.clone();
            entry.test = *inline_test;
        }
        for (scope, name, target) in parsed.reexports {
            modules
                .entry(scope)
                .or_default()
                .reexports
                .insert(name, target);
        }
        let entry = modules.entry(path).or_default();
        entry.file = shown;
        entry.is_file = true;
        entry.test = test;
        entry.references = parsed.references;
    }
    modules
}

/// What [`parse`] finds in a file.
#[derive(Default)]
struct Parsed {
    /// Child modules in files of their own: name → (test code, `#[path]`).
    files: BTreeMap<String, (bool, Option<String>)>,
    /// Inline modules (absolute paths) and whether they are test code.
    inline: Vec<(Vec<String>, bool)>,
    /// `pub use` re-exports: (module, name, absolute path).
    reexports: Vec<(Vec<String>, String, Vec<String>)>,
    references: Vec<Reference>,
}

/// The absolute path of `written`, a path written in module `scope` (`None` for a path
/// outside the crate, or one that is not a module's: a local item, an enum's variants).
fn absolute(
    written: &[String],
    scope: &[String],
    children: &BTreeSet<Vec<String>>,
) -> Option<Vec<String>> {
    let mut segments = written.iter();
    let first = segments.next()?;
    let mut out: Vec<String> = match first.as_str() {
        "crate" | "$crate" => Vec::new(),
        "self" => scope.to_vec(),
        "super" => {
            let mut up = scope.to_vec();
            up.pop()?;
            up
        }
        child => {
            let mut inner = scope.to_vec();
            inner.push(child.to_owned());
            if !children.contains(&inner) {
                return None;
            }
            inner
        }
    };
    for segment in segments {
        if segment == "super" {
            out.pop()?;
        } else if segment != "self" {
            out.push(segment.clone());
        }
    }
    Some(out)
}

/// The segments of a string literal that is a path into the crate, as serde's attributes
/// name functions and types (`"crate::serde_impls::finite::k_min"`).
fn path_string(literal: &str) -> Option<Vec<String>> {
    let segments: Vec<String> = literal.split("::").map(str::to_owned).collect();
    let is_path = segments.len() > 1
        && (segments[0] == "crate" || segments[0] == "super")
        && segments
            .iter()
            .all(|s| !s.is_empty() && s.chars().all(|c| c.is_alphanumeric() || c == '_'));
    is_path.then_some(segments)
}

/// The child modules, inline modules, re-exports and paths of one file of module `module`.
fn parse(tokens: &[Token], module: &[String], test: bool) -> Parsed {
    let mut parsed = Parsed::default();
    // Open scopes: (module path, brace depth inside, test code). A scope is an inline module,
    // or a block of `#[cfg(test)]` code (its module's path, marked as test code).
    let mut scopes: Vec<(Vec<String>, usize, bool)> = vec![(module.to_vec(), 0, test)];
    // The child modules each scope declares (used after the whole file is read: a `use` may
    // come before its `mod`).
    let mut children: BTreeSet<Vec<String>> = BTreeSet::new();
    // (scope, test, public, path as written, alias)
    type Use = (Vec<String>, bool, bool, Vec<String>, Option<String>);
    let mut uses: Vec<Use> = Vec::new();
    let mut paths: Vec<(Vec<String>, bool, Vec<String>)> = Vec::new();
    let mut depth = 0;
    // The attributes before the next item: whether one says `cfg(test)`, and a `#[path]`.
    let mut attr_test = false;
    let mut attr_path: Option<String> = None;
    let mut i = 0;
    let ident = |i: usize| match tokens.get(i) {
        Some(Token::Ident(s)) => Some(s.as_str()),
        _ => None,
    };
    while i < tokens.len() {
        let (scope, _, scope_test) = scopes.last().expect("the file's module").clone();
        let test = scope_test || attr_test;
        match &tokens[i] {
            Token::Punct('#') => {
                // An attribute: `#[…]` or `#![…]`, its tokens up to the matching bracket.
                let mut j = i + 1;
                if tokens.get(j) == Some(&Token::Punct('!')) {
                    j += 1;
                }
                let start = j;
                let mut brackets = 0;
                while j < tokens.len() {
                    match &tokens[j] {
                        Token::Punct('[') => brackets += 1,
                        Token::Punct(']') => {
                            brackets -= 1;
                            if brackets == 0 {
                                break;
                            }
                        }
                        _ => {}
                    }
                    j += 1;
                }
                let inner = &tokens[start..j.min(tokens.len())];
                let has = |name: &str| inner.contains(&Token::Ident(name.to_owned()));
                if has("cfg") && has("test") && !has("not") {
                    attr_test = true;
                }
                if let (Some("path"), Some(Token::Str(file))) = (ident(start + 1), inner.get(3)) {
                    attr_path = Some(file.clone());
                }
                for token in inner {
                    if let Token::Str(literal) = token {
                        if let Some(segments) = path_string(literal) {
                            paths.push((scope.clone(), test, segments));
                        }
                    }
                }
                i = j + 1;
                continue;
            }
            Token::Ident(word) if word == "mod" => {
                if let Some(name) = ident(i + 1) {
                    let mut path = scope.clone();
                    path.push(name.to_owned());
                    children.insert(path.clone());
                    match tokens.get(i + 2) {
                        Some(Token::Punct(';')) => {
                            parsed
                                .files
                                .insert(name.to_owned(), (test, attr_path.take()));
                            i += 3;
                        }
                        Some(Token::Punct('{')) => {
                            depth += 1;
                            scopes.push((path.clone(), depth, test));
                            parsed.inline.push((path, test));
                            i += 3;
                        }
                        _ => i += 2,
                    }
                    attr_test = false;
                    attr_path = None;
                    continue;
                }
            }
            Token::Ident(word) if word == "use" => {
                let restricted = tokens.get(i.wrapping_sub(1)) == Some(&Token::Punct(')'))
                    && ident(i.wrapping_sub(4)) == Some("pub");
                let public = ident(i.wrapping_sub(1)) == Some("pub") || restricted;
                let mut j = i + 1;
                let mut trees = Vec::new();
                use_tree(tokens, &mut j, Vec::new(), &mut trees);
                for (path, alias) in trees {
                    uses.push((scope.clone(), test, public, path, alias));
                }
                attr_test = false;
                attr_path = None;
                i = j + 1;
                continue;
            }
            Token::Punct('{') => {
                depth += 1;
                if attr_test && !scope_test {
                    scopes.push((scope.clone(), depth, true));
                }
                attr_test = false;
            }
            Token::Punct('}') => {
                if scopes.len() > 1 && scopes.last().expect("a scope").1 == depth {
                    scopes.pop();
                }
                depth -= 1;
                attr_test = false;
            }
            Token::Punct(';') => attr_test = false,
            Token::Ident(word) => {
                // A path in an expression or a type: `crate::…`, `super::…`, `self::…`, or
                // one that starts with a child module's name (told apart once all are known).
                let after_sep = i > 0 && tokens[i - 1] == Token::PathSep;
                if !after_sep && tokens.get(i + 1) == Some(&Token::PathSep) {
                    let dollar = i > 0 && tokens[i - 1] == Token::Punct('$');
                    let first = if dollar && word == "crate" {
                        "$crate".to_owned()
                    } else {
                        word.clone()
                    };
                    let mut segments = vec![first];
                    let mut j = i + 1;
                    while tokens.get(j) == Some(&Token::PathSep) {
                        match ident(j + 1) {
                            Some(s) => segments.push(s.to_owned()),
                            None => break,
                        }
                        j += 2;
                    }
                    paths.push((scope.clone(), test, segments));
                    i = j;
                    continue;
                }
            }
            _ => {}
        }
        i += 1;
    }
    for (scope, test, public, written, alias) in uses {
        let Some(path) = absolute(&written, &scope, &children) else {
            continue;
        };
        if public {
            let name = alias.unwrap_or_else(|| path.last().cloned().unwrap_or_default());
            if name != "_" && name != "*" {
                parsed.reexports.push((scope.clone(), name, path.clone()));
            }
        }
        parsed.references.push(Reference {
            written,
            scope,
            test,
        });
    }
    for (scope, test, written) in paths {
        if absolute(&written, &scope, &children).is_some() {
            parsed.references.push(Reference {
                written,
                scope,
                test,
            });
        }
    }
    parsed
}

/// The paths of a use tree from token `*j` (just after `use`, or inside braces), each with
/// its alias, appended to `out`; `*j` ends on the tree's `;`, `,` or `}`.
fn use_tree(
    tokens: &[Token],
    j: &mut usize,
    prefix: Vec<String>,
    out: &mut Vec<(Vec<String>, Option<String>)>,
) {
    let mut path = prefix;
    loop {
        match tokens.get(*j) {
            Some(Token::Ident(s)) if s == "as" => {
                let alias = match tokens.get(*j + 1) {
                    Some(Token::Ident(a)) => Some(a.clone()),
                    _ => None,
                };
                out.push((path, alias));
                *j += 2;
                return;
            }
            Some(Token::Ident(s)) => {
                path.push(s.clone());
                *j += 1;
            }
            Some(Token::PathSep) => *j += 1,
            Some(Token::Punct('*')) => {
                path.push("*".to_owned());
                out.push((path, None));
                *j += 1;
                return;
            }
            Some(Token::Punct('{')) => {
                *j += 1;
                loop {
                    use_tree(tokens, j, path.clone(), out);
                    match tokens.get(*j) {
                        Some(Token::Punct(',')) => *j += 1,
                        _ => break,
                    }
                    if tokens.get(*j) == Some(&Token::Punct('}')) {
                        break;
                    }
                }
                // On the closing brace.
                *j += 1;
                return;
            }
            _ => {
                if !path.is_empty() {
                    out.push((path, None));
                }
                return;
            }
        }
    }
}

/// The module that defines what absolute path `path` names: the longest prefix that is a
/// module, through re-exports (`crate::cascade::CascadeConfig` is `cascade::config`'s).
fn defining_module(modules: &Crate, path: &[String], hops: usize) -> Vec<String> {
    let mut module: Vec<String> = Vec::new();
    for (k, segment) in path.iter().enumerate() {
        let mut inner = module.clone();
        inner.push(segment.clone());
        if modules.contains_key(&inner) {
            module = inner;
            continue;
        }
        if let Some(target) = modules.get(&module).and_then(|m| m.reexports.get(segment)) {
            if hops < 8 && target.as_slice() != path {
                let mut rest = target.clone();
                rest.extend_from_slice(&path[k + 1..]);
                return defining_module(modules, &rest, hops + 1);
            }
        }
        break;
    }
    module
}

/// The module of the file `module` is in (an inline module's file's).
fn file_module(modules: &Crate, module: &[String]) -> Vec<String> {
    let mut path = module.to_vec();
    while !path.is_empty() && !modules.get(&path).is_some_and(|m| m.is_file) {
        path.pop();
    }
    path
}

fn display(module: &[String]) -> String {
    if module.is_empty() {
        "crate".to_owned()
    } else {
        module.join("::")
    }
}

/// The files over [`MAX_LINES`] lines.
fn long_files(src: &Path) -> Vec<String> {
    rust_files(src)
        .iter()
        .filter_map(|file| {
            let text = std::fs::read_to_string(file).expect("a readable file");
            let lines = text.lines().count();
            let name = file.strip_prefix(src).unwrap_or(file).display();
            (lines > MAX_LINES).then(|| format!("src/{name}: {lines} lines (at most {MAX_LINES})"))
        })
        .collect()
}

/// Each import between sibling modules of the non-test code: (from, to) → an example (the
/// file and the path as written).
fn sibling_imports(modules: &Crate) -> BTreeMap<(Vec<String>, Vec<String>), String> {
    let mut edges = BTreeMap::new();
    let all: BTreeSet<Vec<String>> = modules.keys().cloned().collect();
    for (path, module) in modules {
        if !module.is_file || module.test {
            continue;
        }
        for reference in &module.references {
            let scope_test = modules.get(&reference.scope).is_some_and(|m| m.test);
            if reference.test || scope_test {
                continue;
            }
            let Some(target) = absolute(&reference.written, &reference.scope, &all) else {
                continue;
            };
            let to = file_module(modules, &defining_module(modules, &target, 0));
            let common = path.iter().zip(&to).take_while(|(a, b)| a == b).count();
            // The same module, or a module and one of its ancestors.
            if common == path.len() || common == to.len() {
                continue;
            }
            let from = path[..=common].to_vec();
            let to = to[..=common].to_vec();
            let example = format!(
                "{} uses {}",
                module.file.display(),
                reference.written.join("::")
            );
            edges.entry((from, to)).or_insert(example);
        }
    }
    edges
}

/// The circles of `edges`: each group of two or more modules that all reach each other
/// through imports, with every import between them.
fn circles(edges: &BTreeMap<(Vec<String>, Vec<String>), String>) -> Vec<String> {
    let mut next: BTreeMap<&Vec<String>, Vec<&Vec<String>>> = BTreeMap::new();
    for (from, to) in edges.keys() {
        next.entry(from).or_default().push(to);
    }
    let reach = |start: &Vec<String>| -> BTreeSet<Vec<String>> {
        let mut seen = BTreeSet::new();
        let mut stack = vec![start.clone()];
        while let Some(m) = stack.pop() {
            for &to in next.get(&m).map(Vec::as_slice).unwrap_or(&[]) {
                if seen.insert(to.clone()) {
                    stack.push(to.clone());
                }
            }
        }
        seen
    };
    let reached: BTreeMap<&Vec<String>, BTreeSet<Vec<String>>> =
        next.keys().map(|&m| (m, reach(m))).collect();
    let mut grouped: BTreeSet<Vec<String>> = BTreeSet::new();
    let mut out = Vec::new();
    for (&start, from_start) in &reached {
        if grouped.contains(start) || !from_start.contains(start) {
            continue;
        }
        // The modules that reach `start` and that `start` reaches.
        let group: BTreeSet<Vec<String>> = from_start
            .iter()
            .filter(|m| reached.get(m).is_some_and(|r| r.contains(start)))
            .cloned()
            .collect();
        let names: Vec<String> = group.iter().map(|m| display(m)).collect();
        let mut text = format!("import circle among {}:", names.join(", "));
        for ((from, to), example) in edges {
            if group.contains(from) && group.contains(to) {
                text += &format!("\n    {} -> {}: {example}", display(from), display(to));
            }
        }
        grouped.extend(group);
        out.push(text);
    }
    out
}

/// Paths below the crate root that go through the root's re-exports.
fn root_reexport_uses(modules: &Crate) -> Vec<String> {
    let root = &modules[&Vec::new()];
    let mut out = BTreeSet::new();
    for (path, module) in modules {
        if !module.is_file || path.is_empty() {
            continue;
        }
        for reference in &module.references {
            let [first, name, ..] = reference.written.as_slice() else {
                continue;
            };
            let top = vec![name.clone()];
            let through_root = (first == "crate" || first == "$crate")
                && root.reexports.contains_key(name)
                && !modules.contains_key(&top);
            if through_root {
                out.insert(format!(
                    "{} uses {}: name the module that defines {name}",
                    module.file.display(),
                    reference.written.join("::")
                ));
            }
        }
    }
    out.into_iter().collect()
}

#[test]
fn no_file_is_longer_than_600_lines() {
    let long = long_files(&src());
    assert!(long.is_empty(), "{}", long.join("\n"));
}

#[test]
fn no_sibling_modules_import_each_other() {
    let modules = load(&src());
    let found = circles(&sibling_imports(&modules));
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn nothing_below_the_root_uses_its_reexports() {
    let modules = load(&src());
    let found = root_reexport_uses(&modules);
    assert!(found.is_empty(), "{}", found.join("\n"));
}

/// The checks themselves: each finds what it looks for in a small tree of its own.
#[test]
fn the_checks_find_what_they_look_for() {
    let dir = std::env::temp_dir().join(format!("ocean-fft-layout-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("b")).unwrap();
    let files = [
        ("lib.rs", "mod a;\nmod b;\nmod c;\npub use a::Thing;\n"),
        // a uses b's item through b's re-export, b's child uses a: a circle a ↔ b. The
        // comment, the string and the test module would tie c in too if they counted.
        (
            "a.rs",
            "use crate::b::Other; // crate::c::Tested\npub struct Thing;\n\
             const S: &str = \"crate::c::Tested\";\n\
             #[cfg(test)]\nmod tests {\n    use crate::c::Tested;\n}\n",
        ),
        ("b/mod.rs", "mod inner;\npub(crate) use inner::Other;\n"),
        ("b/inner.rs", "pub struct Other(crate::a::Thing);\n"),
        // c names a through the root's re-export.
        ("c.rs", "pub struct Tested(crate::Thing);\n"),
    ];
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let modules = load(&dir);
    let found = circles(&sibling_imports(&modules));
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].starts_with("import circle among a, b:"),
        "{}",
        found[0]
    );
    assert!(
        found[0].contains("a -> b") && found[0].contains("b -> a"),
        "{}",
        found[0]
    );
    let reexports = root_reexport_uses(&modules);
    assert_eq!(reexports.len(), 1, "{reexports:?}");
    assert!(reexports[0].contains("crate::Thing"), "{}", reexports[0]);
    std::fs::write(
        dir.join("c.rs"),
        "pub struct Tested;\n".repeat(MAX_LINES + 1),
    )
    .unwrap();
    let long = long_files(&dir);
    assert_eq!(long.len(), 1, "{long:?}");
    assert!(long[0].contains("c.rs"), "{}", long[0]);
    std::fs::remove_dir_all(&dir).unwrap();
}
