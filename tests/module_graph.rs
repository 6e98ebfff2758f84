//! No two modules of a crate import each other, directly or through others: the module import graph of every
//! crate of the workspace (and of this suite's support library) has no cycle.
//!
//! The graph is read from the sources: every module of a crate (from `lib.rs` through `mod name;` and inline
//! `mod name { … }` declarations), and in each module every `use` of a path inside the crate (`crate::…`,
//! `super::…`, `self::…`, or a child module's name) and every `crate::…`/`super::…`/`self::…` path in the
//! code. An edge goes from the module that writes the path to the module that *defines* what it names: a
//! re-export (`pub use`, of any visibility) is followed to where the item lives and is not itself an edge, so
//! a crate root that re-exports its modules' types does not make every module depend on the root. Declaring a
//! child module (`mod child;`) is not an import. Comments (doc links included) and string literals are not
//! read.
//!
//! `cargo modules` (crates.io) draws the same graph, but it builds rust-analyzer's crates, far too long for a
//! 2-core CI; this reader needs nothing but the standard library. How to run it: docs/architecture.md,
//! "Module graph".

use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::fs;
use std::path::{Path, PathBuf};

/// A token of Rust source, as far as module paths need: identifiers (keywords included), `::` and single
/// punctuation characters. Comments, literals and lifetimes are dropped.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Token {
    Ident(String),
    PathSep,
    Punct(char),
}

/// Splits `source` into [`Token`]s.
fn tokenize(source: &str) -> Vec<Token> {
    let chars: Vec<char> = source.chars().collect();
    let mut tokens = Vec::new();
    let mut i = 0;
    let at = |i: usize| chars.get(i).copied().unwrap_or('\0');
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c == '/' && at(i + 1) == '/' {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && at(i + 1) == '*' {
            // Block comments nest.
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if c == '"' {
            i = skip_string(&chars, i + 1);
        } else if c == '\'' {
            if at(i + 1) == '\\' {
                // An escaped character literal: the quote, the backslash and the escaped character, then up
                // to the closing quote (`'\u{…}'`).
                i += 3;
                while i < chars.len() && chars[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if at(i + 2) == '\'' {
                i += 3;
            } else {
                // A lifetime or label: the quote, then its name.
                i += 1;
                while at(i).is_alphanumeric() || at(i) == '_' {
                    i += 1;
                }
            }
        } else if c.is_ascii_digit() {
            while at(i).is_alphanumeric()
                || at(i) == '_'
                || (at(i) == '.' && at(i + 1).is_ascii_digit())
            {
                i += 1;
            }
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while at(i).is_alphanumeric() || at(i) == '_' {
                i += 1;
            }
            let word: String = chars[start..i].iter().collect();
            // Raw strings (`r"…"`, `r#"…"#`, `br…`), byte and C strings (`b"…"`, `c"…"`).
            let raw = matches!(word.as_str(), "r" | "br" | "cr");
            if raw && (at(i) == '"' || (at(i) == '#' && (at(i + 1) == '"' || at(i + 1) == '#'))) {
                let mut hashes = 0;
                while at(i) == '#' {
                    hashes += 1;
                    i += 1;
                }
                i += 1;
                loop {
                    if i >= chars.len() {
                        break;
                    }
                    if chars[i] == '"' && (1..=hashes).all(|k| at(i + k) == '#') {
                        i += 1 + hashes;
                        break;
                    }
                    i += 1;
                }
            } else if matches!(word.as_str(), "b" | "c") && at(i) == '"' {
                i = skip_string(&chars, i + 1);
            } else if word == "b" && at(i) == '\'' {
                i += 1;
                while i < chars.len() && chars[i] != '\'' {
                    i += if chars[i] == '\\' { 2 } else { 1 };
                }
                i += 1;
            } else {
                tokens.push(Token::Ident(word));
            }
        } else if c == ':' && at(i + 1) == ':' {
            tokens.push(Token::PathSep);
            i += 2;
        } else {
            tokens.push(Token::Punct(c));
            i += 1;
        }
    }
    tokens
}

/// The index just past the string literal whose contents start at `i`.
fn skip_string(chars: &[char], mut i: usize) -> usize {
    while i < chars.len() {
        match chars[i] {
            '\\' => i += 2,
            '"' => return i + 1,
            _ => i += 1,
        }
    }
    i
}

/// One `use` leaf: the path as written, and whether it ends in `*`, with the name it binds.
#[derive(Debug, Clone)]
struct UseLeaf {
    path: Vec<String>,
    glob: bool,
    /// The name it brings into scope (`None` for a glob or `_`).
    binds: Option<String>,
}

/// Parses a use tree starting at `tokens[*i]` with `prefix` already read, up to (not past) `;`, `,` or `}`.
fn parse_use_tree(tokens: &[Token], i: &mut usize, prefix: &[String], out: &mut Vec<UseLeaf>) {
    let mut path = prefix.to_vec();
    loop {
        match tokens.get(*i) {
            Some(Token::PathSep) => *i += 1,
            Some(Token::Ident(name)) if name != "as" => {
                path.push(name.clone());
                *i += 1;
            }
            Some(Token::Punct('*')) => {
                *i += 1;
                out.push(UseLeaf {
                    path,
                    glob: true,
                    binds: None,
                });
                return;
            }
            Some(Token::Punct('{')) => {
                *i += 1;
                loop {
                    match tokens.get(*i) {
                        Some(Token::Punct('}')) => {
                            *i += 1;
                            return;
                        }
                        Some(Token::Punct(',')) => *i += 1,
                        None => return,
                        Some(_) => parse_use_tree(tokens, i, &path, out),
                    }
                }
            }
            _ => break,
        }
    }
    // `self` inside a group names the group's prefix.
    if path.last().is_some_and(|s| s == "self") && path.len() > prefix.len() && !prefix.is_empty() {
        path.pop();
    }
    let mut binds = path.last().cloned();
    if tokens.get(*i) == Some(&Token::Ident("as".to_owned())) {
        binds = match tokens.get(*i + 1) {
            Some(Token::Ident(name)) => Some(name.clone()),
            _ => None,
        };
        *i += 2;
    }
    out.push(UseLeaf {
        path,
        glob: false,
        binds,
    });
}

/// A module of a crate as read from its source.
#[derive(Debug, Default)]
struct Module {
    /// Its path from the crate root (empty for the root).
    path: Vec<String>,
    /// Its declared child modules.
    children: BTreeSet<String>,
    /// Names bound by its `use` declarations (public or not) → the absolute path they stand for (`None`:
    /// outside the crate).
    aliases: BTreeMap<String, Option<Vec<String>>>,
    /// Names its items are declared with (types, functions, constants, …; methods too: an over-estimate is
    /// enough to tell where a glob re-export finds a name).
    items: BTreeSet<String>,
    /// Its public glob re-exports (absolute module paths).
    public_globs: Vec<Vec<String>>,
    /// Paths it depends on (absolute), with whether each is a glob: its private `use`s and in-code paths.
    uses: Vec<(Vec<String>, bool)>,
    /// Uses as written (relative to this module), resolved to absolute paths once every module is known.
    pending: Vec<(UseLeaf, bool)>,
}

/// A crate's module tree and import graph.
#[derive(Debug)]
struct Crate {
    modules: Vec<Module>,
    by_path: BTreeMap<Vec<String>, usize>,
}

impl Crate {
    /// Reads the crate whose root file is `root` (a `lib.rs`), following `mod name;` to files.
    fn read(root: &Path) -> Result<Self, String> {
        let mut krate = Self {
            modules: Vec::new(),
            by_path: BTreeMap::new(),
        };
        let mut files = vec![(root.to_path_buf(), Vec::new(), true)];
        while let Some((file, path, owns_dir)) = files.pop() {
            let source = fs::read_to_string(&file)
                .map_err(|e| format!("reading {}: {e}", file.display()))?;
            // The folder where this file's `mod name;` children live.
            let dir = if owns_dir {
                file.parent().map(Path::to_path_buf).unwrap_or_default()
            } else {
                let stem = file
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default();
                file.parent().map(|p| p.join(stem)).unwrap_or_default()
            };
            for (child_path, child_dir) in krate.parse_file(&source, &path, &dir) {
                let name = child_path.last().cloned().unwrap_or_default();
                let flat = child_dir.join(format!("{name}.rs"));
                let nested = child_dir.join(&name).join("mod.rs");
                if flat.is_file() {
                    files.push((flat, child_path, false));
                } else if nested.is_file() {
                    files.push((nested, child_path, true));
                } else {
                    return Err(format!(
                        "module {} declared in {} has no file",
                        child_path.join("::"),
                        file.display()
                    ));
                }
            }
        }
        krate.resolve_pending();
        Ok(krate)
    }

    /// The module of path `path`, created if new.
    fn module(&mut self, path: &[String]) -> usize {
        if let Some(&index) = self.by_path.get(path) {
            return index;
        }
        self.modules.push(Module {
            path: path.to_vec(),
            ..Module::default()
        });
        let index = self.modules.len() - 1;
        self.by_path.insert(path.to_vec(), index);
        if let Some((name, parent)) = path.split_last() {
            let parent = self.module(parent);
            self.modules[parent].children.insert(name.clone());
        }
        index
    }

    /// Reads one file, the module `path` (and its inline modules); returns the file modules it declares,
    /// each with the folder its file is in.
    fn parse_file(
        &mut self,
        source: &str,
        path: &[String],
        dir: &Path,
    ) -> Vec<(Vec<String>, PathBuf)> {
        let tokens = tokenize(source);
        let mut declared = Vec::new();
        // The open inline modules: (module path, folder of its children, brace depth it opened at).
        let mut stack: Vec<(Vec<String>, PathBuf, usize)> =
            vec![(path.to_vec(), dir.to_path_buf(), 0)];
        let mut depth = 0;
        let mut i = 0;
        let ident = |i: usize| match tokens.get(i) {
            Some(Token::Ident(name)) => Some(name.as_str()),
            _ => None,
        };
        while i < tokens.len() {
            let (current, current_dir, _) = stack.last().cloned().unwrap_or_default();
            let module = self.module(&current);
            match &tokens[i] {
                Token::Punct('{') => {
                    depth += 1;
                    i += 1;
                }
                Token::Punct('}') => {
                    if stack.len() > 1 && stack.last().is_some_and(|(_, _, d)| *d == depth) {
                        stack.pop();
                    }
                    depth -= 1;
                    i += 1;
                }
                Token::Ident(word) if word == "mod" && ident(i + 1).is_some() => {
                    let name = ident(i + 1).unwrap_or_default().to_owned();
                    let mut child = current.clone();
                    child.push(name.clone());
                    self.module(&child);
                    match tokens.get(i + 2) {
                        Some(Token::Punct(';')) => {
                            declared.push((child, current_dir.clone()));
                            i += 3;
                        }
                        Some(Token::Punct('{')) => {
                            depth += 1;
                            stack.push((child, current_dir.join(&name), depth));
                            i += 3;
                        }
                        _ => i += 2,
                    }
                }
                Token::Ident(word)
                    if matches!(
                        word.as_str(),
                        "struct" | "enum" | "union" | "trait" | "type" | "fn" | "const" | "static"
                    ) && ident(i + 1).is_some_and(|n| !matches!(n, "fn" | "mut" | "unsafe")) =>
                {
                    let name = ident(i + 1).unwrap_or_default().to_owned();
                    self.modules[module].items.insert(name);
                    i += 2;
                }
                Token::Ident(word) if word == "use" => {
                    let public = is_public(&tokens, i);
                    i += 1;
                    let mut leaves = Vec::new();
                    parse_use_tree(&tokens, &mut i, &[], &mut leaves);
                    for leaf in leaves {
                        self.modules[module].pending.push((leaf, public));
                    }
                }
                Token::Ident(word)
                    if matches!(word.as_str(), "crate" | "super" | "self")
                        && tokens.get(i + 1) == Some(&Token::PathSep)
                        && !is_visibility(&tokens, i) =>
                {
                    let mut segments = vec![word.clone()];
                    i += 1;
                    while tokens.get(i) == Some(&Token::PathSep) {
                        match ident(i + 1) {
                            Some(name) => {
                                segments.push(name.to_owned());
                                i += 2;
                            }
                            None => break,
                        }
                    }
                    let leaf = UseLeaf {
                        path: segments,
                        glob: false,
                        binds: None,
                    };
                    self.modules[module].pending.push((leaf, false));
                }
                _ => i += 1,
            }
        }
        declared
    }

    /// Turns every module's written uses into absolute paths: aliases, public globs and dependencies.
    fn resolve_pending(&mut self) {
        for index in 0..self.modules.len() {
            let pending = std::mem::take(&mut self.modules[index].pending);
            for (leaf, public) in pending {
                let absolute = self.absolute(index, &leaf.path);
                let module = &mut self.modules[index];
                if let Some(name) = &leaf.binds {
                    module.aliases.insert(name.clone(), absolute.clone());
                }
                let Some(absolute) = absolute else {
                    continue;
                };
                if public {
                    if leaf.glob {
                        module.public_globs.push(absolute);
                    }
                } else {
                    module.uses.push((absolute, leaf.glob));
                }
            }
        }
    }

    /// `path` as written in module `from`, from the crate root; `None` for a path outside the crate.
    fn absolute(&self, from: usize, path: &[String]) -> Option<Vec<String>> {
        let (first, rest) = path.split_first()?;
        let here = &self.modules[from].path;
        let mut base = match first.as_str() {
            "crate" => Vec::new(),
            "self" => here.clone(),
            "super" => here.split_last().map(|(_, p)| p.to_vec())?,
            name if self.modules[from].children.contains(name) => {
                let mut p = here.clone();
                p.push(name.to_owned());
                p
            }
            _ => return None,
        };
        for segment in rest {
            if segment == "super" {
                base.pop()?;
            } else {
                base.push(segment.clone());
            }
        }
        Some(base)
    }

    /// The module that defines what absolute path `path` names: through child modules, following
    /// re-exports; `None` if it leads outside the crate.
    fn defining_module(&self, path: &[String], hops: usize) -> Option<usize> {
        if hops > 32 {
            return None;
        }
        let mut current = *self.by_path.get(&Vec::new())?;
        for (k, segment) in path.iter().enumerate() {
            let module = &self.modules[current];
            if module.children.contains(segment) {
                let mut child = module.path.clone();
                child.push(segment.clone());
                current = *self.by_path.get(&child)?;
                continue;
            }
            let follow = |target: &[String]| {
                let mut full = target.to_vec();
                full.extend_from_slice(&path[k + 1..]);
                self.defining_module(&full, hops + 1)
            };
            if let Some(target) = module.aliases.get(segment) {
                return follow(target.as_ref()?);
            }
            for glob in &module.public_globs {
                let Some(m) = self.defining_module(glob, hops + 1) else {
                    continue;
                };
                let globbed = &self.modules[m];
                if globbed.children.contains(segment)
                    || globbed.aliases.contains_key(segment)
                    || globbed.items.contains(segment)
                {
                    let mut full = globbed.path.clone();
                    full.extend_from_slice(&path[k..]);
                    return self.defining_module(&full, hops + 1);
                }
            }
            // An item defined here.
            return Some(current);
        }
        Some(current)
    }

    /// The import graph: module → the modules it depends on (itself excluded).
    fn edges(&self) -> Vec<BTreeSet<usize>> {
        self.modules
            .iter()
            .enumerate()
            .map(|(index, module)| {
                let mut to = BTreeSet::new();
                for (path, glob) in &module.uses {
                    let Some(target) = self.defining_module(path, 0) else {
                        continue;
                    };
                    to.insert(target);
                    if *glob {
                        // A glob of a module that re-exports brings the re-exported items' modules too.
                        let globbed = &self.modules[target];
                        to.extend(
                            globbed
                                .public_globs
                                .iter()
                                .filter_map(|g| self.defining_module(g, 0)),
                        );
                    }
                }
                to.remove(&index);
                to
            })
            .collect()
    }

    /// A module's name for messages: `crate` for the root, else its path.
    fn name(&self, index: usize) -> String {
        let path = &self.modules[index].path;
        if path.is_empty() {
            "crate".to_owned()
        } else {
            path.join("::")
        }
    }

    /// Every import cycle, one per group of modules that reach each other: the shortest cycle through the
    /// group's first module, as `a → b → … → a`.
    fn cycles(&self) -> Vec<String> {
        let edges = self.edges();
        strongly_connected(&edges)
            .into_iter()
            .filter(|group| group.len() > 1)
            .filter_map(|group| {
                let start = *group.first()?;
                let path = shortest_cycle(&edges, &group, start)?;
                let mut names: Vec<String> = path.iter().map(|&m| self.name(m)).collect();
                names.push(self.name(start));
                let members: Vec<String> = group.iter().map(|&m| self.name(m)).collect();
                Some(format!(
                    "{} (modules that reach each other: {})",
                    names.join(" → "),
                    members.join(", ")
                ))
            })
            .collect()
    }
}

/// Whether the `use` at `tokens[i]` is a re-export: `pub use` or `pub(…) use`.
fn is_public(tokens: &[Token], i: usize) -> bool {
    let Some(before) = i.checked_sub(1).and_then(|b| tokens.get(b)) else {
        return false;
    };
    match before {
        Token::Ident(word) => word == "pub",
        Token::Punct(')') => {
            // Back to the matching `(`, then `pub`.
            let mut k = i - 1;
            while k > 0 && tokens[k] != Token::Punct('(') {
                k -= 1;
            }
            k > 0 && tokens[k - 1] == Token::Ident("pub".to_owned())
        }
        _ => false,
    }
}

/// Whether the path at `tokens[i]` is inside a visibility, `pub(in …)`.
fn is_visibility(tokens: &[Token], i: usize) -> bool {
    i >= 3
        && tokens[i - 1] == Token::Ident("in".to_owned())
        && tokens[i - 2] == Token::Punct('(')
        && tokens[i - 3] == Token::Ident("pub".to_owned())
}

/// Tarjan's strongly connected components of `edges`, each sorted.
fn strongly_connected(edges: &[BTreeSet<usize>]) -> Vec<Vec<usize>> {
    struct State<'a> {
        edges: &'a [BTreeSet<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        groups: Vec<Vec<usize>>,
    }
    fn visit(s: &mut State<'_>, v: usize) {
        s.index[v] = Some(s.next);
        s.low[v] = s.next;
        s.next += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        for &w in &s.edges[v] {
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(iw) if s.on_stack[w] => s.low[v] = s.low[v].min(iw),
                Some(_) => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut group = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack[w] = false;
                group.push(w);
                if w == v {
                    break;
                }
            }
            group.sort_unstable();
            s.groups.push(group);
        }
    }
    let n = edges.len();
    let mut state = State {
        edges,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        groups: Vec::new(),
    };
    for v in 0..n {
        if state.index[v].is_none() {
            visit(&mut state, v);
        }
    }
    state.groups.sort();
    state.groups
}

/// The shortest path `start → … → start` within `group` (breadth first), without the final `start`.
fn shortest_cycle(edges: &[BTreeSet<usize>], group: &[usize], start: usize) -> Option<Vec<usize>> {
    let mut came_from: BTreeMap<usize, usize> = BTreeMap::new();
    let mut queue = VecDeque::from([start]);
    while let Some(v) = queue.pop_front() {
        for &w in &edges[v] {
            if !group.contains(&w) {
                continue;
            }
            if w == start {
                let mut path = vec![v];
                let mut at = v;
                while at != start {
                    at = *came_from.get(&at)?;
                    path.push(at);
                }
                path.reverse();
                return Some(path);
            }
            if let std::collections::btree_map::Entry::Vacant(entry) = came_from.entry(w) {
                entry.insert(v);
                queue.push_back(w);
            }
        }
    }
    None
}

/// The workspace root (this package's manifest directory).
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The import cycles of the crate whose root file is `lib` (relative to the workspace root).
fn cycles_of(lib: &str) -> Vec<String> {
    let krate = Crate::read(&root().join(lib)).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        krate.modules.len() > 1,
        "{lib}: read {} module(s) only",
        krate.modules.len()
    );
    krate.cycles()
}

/// Asserts the crate at `lib` has no import cycle, naming every cycle it has.
fn assert_acyclic(lib: &str) {
    let cycles = cycles_of(lib);
    assert!(
        cycles.is_empty(),
        "{lib}: {} import cycle(s):\n  {}",
        cycles.len(),
        cycles.join("\n  ")
    );
}

#[test]
fn math_has_no_import_cycle() {
    assert_acyclic("crates/rebound-math/src/lib.rs");
}

#[test]
fn dynamics_has_no_import_cycle() {
    assert_acyclic("crates/rebound-dynamics/src/lib.rs");
}

#[test]
fn constraints_has_no_import_cycle() {
    assert_acyclic("crates/rebound-constraints/src/lib.rs");
}

#[test]
fn world_has_no_import_cycle() {
    assert_acyclic("crates/rebound-world/src/lib.rs");
}

#[test]
fn facade_has_no_import_cycle() {
    assert_acyclic("crates/rebound/src/lib.rs");
}

#[test]
fn suite_support_has_no_import_cycle() {
    assert_acyclic("tests/support/lib.rs");
}

#[test]
fn debug_has_no_import_cycle() {
    assert_acyclic("crates/rebound-debug/src/lib.rs");
}

#[test]
fn record_has_no_import_cycle() {
    assert_acyclic("crates/rebound-record/src/lib.rs");
}

#[test]
fn render_has_no_import_cycle() {
    assert_acyclic("crates/rebound-render/src/lib.rs");
}

#[test]
fn scene_has_no_import_cycle() {
    assert_acyclic("crates/rebound-scene/src/lib.rs");
}

#[test]
fn cli_has_no_import_cycle() {
    assert_acyclic("crates/rebound-cli/src/main.rs");
}

#[test]
fn bevy_plugin_has_no_import_cycle() {
    assert_acyclic("crates/rebound-bevy/src/lib.rs");
}

/// A crate written to a temporary folder: `files` are (path under `src/`, source).
fn temporary_crate(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "rebound-module-graph-{name}-{}",
        std::process::id()
    ));
    let _ = fs::remove_dir_all(&dir);
    for (path, source) in files {
        let file = dir.join(path);
        fs::create_dir_all(file.parent().expect("a file in a folder")).expect("temporary folder");
        fs::write(&file, source).expect("temporary file");
    }
    dir.join("lib.rs")
}

/// The reader finds a cycle through a re-export and an inline path, names it, and sees none once it is cut;
/// comments, strings, re-exports and child declarations make no edges.
#[test]
fn reader_finds_cycles_and_only_cycles() {
    let with_cycle = temporary_crate(
        "cycle",
        &[
            (
                "lib.rs",
                "//! use crate::c::X;\nmod a;\nmod b;\nmod c;\npub use a::A;\npub use c::{self as see, C};\n",
            ),
            ("a.rs", "use crate::b::B;\npub struct A(B);\n"),
            (
                "b.rs",
                "pub struct B;\nfn f() -> u32 { let _s = \"crate::a::A\"; crate::see::C::new() }\n",
            ),
            (
                "c.rs",
                "pub struct C;\nfn g(_: crate::A) {}\n#[cfg(test)]\nmod tests { use super::*; use crate::b::B; }\n",
            ),
        ],
    );
    let krate = Crate::read(&with_cycle).expect("readable");
    let cycles = krate.cycles();
    assert_eq!(cycles.len(), 1, "{cycles:?}");
    assert!(cycles[0].starts_with("a → b → c → a"), "{cycles:?}");

    let without = temporary_crate(
        "acyclic",
        &[
            (
                "lib.rs",
                "mod a;\nmod b;\npub use a::A;\npub use b::B;\n// crate::b::B\n",
            ),
            (
                "a.rs",
                "use crate::B;\npub struct A(B);\nmod inner { use super::A; }\n",
            ),
            (
                "b.rs",
                "pub struct B;\nconst S: &str = r#\"use crate::a::A;\"#;\n",
            ),
        ],
    );
    let krate = Crate::read(&without).expect("readable");
    assert_eq!(krate.cycles(), Vec::<String>::new());
    assert!(
        krate
            .by_path
            .contains_key(&vec!["a".to_owned(), "inner".to_owned()])
    );
}
