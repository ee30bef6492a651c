//! The user docs stay user docs (issue 44). `docs/` holds what a user and a contributor
//! read, with current facts only; measurement diaries, issue notes and dated benchmark
//! output live in `docs/notes/` (the lab notebook), linked from one line of
//! `docs/README.md`. This test keeps it that way:
//!
//! - the Markdown of the user docs (every `docs/**/*.md` outside `docs/notes/`) stays
//!   under [`BUDGET_BYTES`];
//! - no user doc has a "continued (N)" heading or a heading with a date (`YYYY-MM-DD`):
//!   those are diary entries, and belong in `docs/notes/`;
//! - every relative Markdown link in `README.md` and `docs/**/*.md` (the notes included)
//!   points to a file or folder that exists, so a moved page leaves no dead link;
//! - `docs/README.md` links `docs/notes/`.
//!
//! Fenced code blocks and inline code spans are not read as headings or links.

use std::path::{Component, Path, PathBuf};

/// The budget for the user docs' Markdown, in bytes. Before issue 44 `docs/` held 444 KB
/// of Markdown in 37 files (282 KB three days earlier; 87 % of the growth was measurement
/// diaries). After the diaries moved to `docs/notes/`, the user pages were 323 KB in 27
/// files, and the generated scene-key reference (`docs/scene-keys.md`; about 30 KB, the
/// size of the user guide's key tables) joins them: about 355 KB. 380 KB (86 % of the
/// old total) leaves about 25 KB (7 %) for the pages to grow, and fails if a diary comes
/// back: issue 28's first five parts alone (`docs/notes/performance_history_28.md`) are
/// 40 KB. A budget near 60 % of the old total would have meant cutting the user guide
/// and the validation report, which are reference, not diary. Raise it only with a
/// reason written here; move a diary to `docs/notes/` instead.
const BUDGET_BYTES: u64 = 380_000;

/// Pages that other work of issue 44 generates and that may not be committed yet: a link
/// to one of these is accepted while the file is missing (and checked once it exists).
const PENDING: &[&str] = &["docs/scene-keys.md"];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .canonicalize()
        .unwrap()
}

fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            markdown_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "md") {
            out.push(p);
        }
    }
}

/// Every `docs/**/*.md`, and whether it is a user doc (outside `docs/notes/`).
fn docs() -> Vec<(PathBuf, bool)> {
    let root = repo();
    let notes = root.join("docs/notes");
    let mut files = Vec::new();
    markdown_files(&root.join("docs"), &mut files);
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let user = !p.starts_with(&notes);
            (p, user)
        })
        .collect()
}

fn user_docs() -> Vec<PathBuf> {
    let user: Vec<PathBuf> = docs()
        .into_iter()
        .filter(|(_, u)| *u)
        .map(|(p, _)| p)
        .collect();
    // a wrong folder would make every check below pass on nothing
    assert!(user.len() >= 20, "only {} user docs found", user.len());
    user
}

fn rel(p: &Path) -> String {
    p.strip_prefix(repo()).unwrap_or(p).display().to_string()
}

/// The lines of `text` outside fenced code blocks, numbered from 1, with inline code
/// spans blanked.
fn prose(text: &str) -> Vec<(usize, String)> {
    let mut fence: Option<&str> = None;
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let t = line.trim_start();
        let marker = if t.starts_with("```") {
            Some("```")
        } else if t.starts_with("~~~") {
            Some("~~~")
        } else {
            None
        };
        match (fence, marker) {
            (None, Some(m)) => fence = Some(m),
            (Some(f), Some(m)) if f == m => fence = None,
            (None, None) => out.push((k + 1, without_code_spans(line))),
            _ => {}
        }
    }
    out
}

fn without_code_spans(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut inside = false;
    for c in line.chars() {
        if c == '`' {
            inside = !inside;
            out.push(' ');
        } else {
            out.push(if inside { ' ' } else { c });
        }
    }
    out
}

/// The text of an ATX heading (`#` to `######` and a space), or `None`.
fn heading(line: &str) -> Option<&str> {
    let t = line.strip_prefix("   ").or_else(|| line.strip_prefix("  "));
    let t = t.or_else(|| line.strip_prefix(' ')).unwrap_or(line);
    let hashes = t.chars().take_while(|&c| c == '#').count();
    if !(1..=6).contains(&hashes) {
        return None;
    }
    let rest = &t[hashes..];
    (rest.is_empty() || rest.starts_with(' ')).then_some(rest.trim())
}

/// Whether `s` holds a date `YYYY-MM-DD`.
fn has_date(s: &str) -> bool {
    let b = s.as_bytes();
    b.windows(10).any(|w| {
        w.iter().enumerate().all(|(i, &c)| match i {
            4 | 7 => c == b'-',
            _ => c.is_ascii_digit(),
        })
    })
}

/// The targets of the inline links and images `[text](target "title")` in `line`.
fn link_targets(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (i, _) in line.match_indices("](") {
        let rest = &line[i + 2..];
        let Some(end) = rest.find(')') else { continue };
        let inner = rest[..end].trim();
        let target = inner
            .strip_prefix('<')
            .and_then(|t| t.split('>').next())
            .unwrap_or_else(|| inner.split_whitespace().next().unwrap_or(""));
        out.push(target.to_string());
    }
    out
}

/// `path` with `.` and `..` resolved lexically (the file may not exist).
fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

/// Where a relative link of `file` leads, or `None` for an external link or an anchor.
fn resolve(file: &Path, target: &str) -> Option<PathBuf> {
    let external = target.contains("://") || target.starts_with("mailto:");
    let path = target.split(['#', '?']).next().unwrap_or("");
    if external || path.is_empty() {
        return None;
    }
    let base = if path.starts_with('/') {
        repo()
    } else {
        file.parent().unwrap().to_path_buf()
    };
    Some(normalise(&base.join(path.trim_start_matches('/'))))
}

#[test]
fn user_docs_stay_under_their_size_budget() {
    let mut sizes: Vec<(u64, String)> = user_docs()
        .iter()
        .map(|p| (std::fs::metadata(p).unwrap().len(), rel(p)))
        .collect();
    let total: u64 = sizes.iter().map(|(s, _)| s).sum();
    let notes: u64 = docs()
        .iter()
        .filter(|(_, u)| !*u)
        .map(|(p, _)| std::fs::metadata(p).unwrap().len())
        .sum();
    println!(
        "user docs: {} files, {total} bytes (budget {BUDGET_BYTES}); docs/notes: {notes} bytes",
        sizes.len()
    );
    sizes.sort();
    sizes.reverse();
    assert!(
        total <= BUDGET_BYTES,
        "the user docs hold {total} bytes of Markdown, over the budget of {BUDGET_BYTES} \
         (host/tests/docs.rs): move measurement diaries and issue notes to docs/notes/. \
         Largest: {:?}",
        &sizes[..sizes.len().min(8)]
    );
}

#[test]
fn user_docs_have_no_diary_headings() {
    let mut found = Vec::new();
    for p in user_docs() {
        let text = std::fs::read_to_string(&p).unwrap();
        for (n, line) in prose(&text) {
            let Some(h) = heading(&line) else { continue };
            if h.to_lowercase().contains("continued (") || has_date(h) {
                found.push(format!("{}:{n}: {}", rel(&p), line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "diary headings (\"continued (N)\" or dated) in the user docs; they belong in \
         docs/notes/:\n{}",
        found.join("\n")
    );
}

#[test]
fn relative_links_point_to_files_that_exist() {
    let root = repo();
    let mut files = vec![root.join("README.md")];
    files.extend(docs().into_iter().map(|(p, _)| p));
    let pending: Vec<PathBuf> = PENDING.iter().map(|p| root.join(p)).collect();
    let mut checked = 0;
    let mut dead = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        for (n, line) in prose(&text) {
            for target in link_targets(&line) {
                let Some(to) = resolve(f, &target) else {
                    continue;
                };
                checked += 1;
                if !to.exists() && !pending.contains(&to) {
                    dead.push(format!("{}:{n}: ({target})", rel(f)));
                }
            }
        }
    }
    assert!(checked >= 200, "only {checked} relative links found");
    assert!(
        dead.is_empty(),
        "links to files that do not exist:\n{}",
        dead.join("\n")
    );
}

#[test]
fn the_docs_index_links_the_notes() {
    let index = repo().join("docs/README.md");
    let notes = repo().join("docs/notes");
    let text = std::fs::read_to_string(&index).unwrap();
    let links_notes = prose(&text).iter().any(|(_, line)| {
        link_targets(line)
            .iter()
            .filter_map(|t| resolve(&index, t))
            .any(|to| to.starts_with(&notes) && to.exists())
    });
    assert!(links_notes, "docs/README.md does not link docs/notes/");
}

#[test]
fn the_helpers_see_what_they_should() {
    assert_eq!(
        heading("## Issue 28, continued (6): x"),
        Some("Issue 28, continued (6): x")
    );
    assert_eq!(heading("#not a heading"), None);
    assert!(has_date("Measured 2026-12-05 (Xeon)"));
    assert!(!has_date("commit 18081b9, 2,208 particles"));
    assert_eq!(
        link_targets("see [a](b.md#x) and ![c](img/d.png \"t\") and [e](<f g.md>)"),
        ["b.md#x", "img/d.png", "f g.md"]
    );
    let lines = prose("a\n```sh\n# 2026-12-05 [x](nowhere.md)\n```\n`[y](z.md)` b");
    assert_eq!(lines.len(), 2);
    assert!(link_targets(&lines[1].1).is_empty());
}
