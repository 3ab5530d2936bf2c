//! The index page of a reports folder: every report below it (HTML pages, Markdown tables,
//! SVG pictures), grouped by folder, each with its title and the verdict line it opens with.

use super::html::STYLE;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// One report found below the folder.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct IndexEntry {
    /// Path relative to the folder, with `/` separators.
    pub path: String,
    /// The page's `<title>` (HTML), first `# ` heading (Markdown), or the file name.
    pub title: String,
    /// The verdict line it opens with (`<p class="verdict">`), when it has one.
    pub verdict: Option<String>,
}

/// Every `.html`, `.md` and `.svg` file below `dir` (not `dir/index.html` itself), sorted by
/// path.
///
/// # Errors
/// A folder that cannot be read.
pub fn index_entries(dir: &Path) -> std::io::Result<Vec<IndexEntry>> {
    let mut files: Vec<PathBuf> = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(folder) = stack.pop() {
        for entry in std::fs::read_dir(&folder)? {
            let path = entry?.path();
            if path.is_dir() {
                stack.push(path);
            } else if matches!(
                path.extension().and_then(|e| e.to_str()),
                Some("html" | "md" | "svg")
            ) && path != dir.join("index.html")
            {
                files.push(path);
            }
        }
    }
    files.sort();
    Ok(files
        .iter()
        .map(|path| {
            let relative = path.strip_prefix(dir).unwrap_or(path);
            let text = std::fs::read_to_string(path).unwrap_or_default();
            let name = relative
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let (title, verdict) = match path.extension().and_then(|e| e.to_str()) {
                Some("html") => (
                    between(&text, "<title>", "</title>").map(unescape),
                    between(&text, "<p class=\"verdict\">", "</p>")
                        .map(|v| unescape(&strip_tags(v))),
                ),
                Some("md") => (
                    text.lines()
                        .find_map(|l| l.strip_prefix("# "))
                        .map(str::to_owned),
                    None,
                ),
                _ => (None, None),
            };
            IndexEntry {
                path: relative
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy())
                    .collect::<Vec<_>>()
                    .join("/"),
                title: title.unwrap_or(name),
                verdict,
            }
        })
        .collect())
}

/// A self-contained index page linking `entries` (relative links), grouped by folder.
pub fn index_html(title: &str, entries: &[IndexEntry]) -> String {
    let mut html = format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><style>{STYLE}</style></head><body><h1>{t}</h1><p>{} reports; each accuracy page opens with its verdict, repeated here.</p>",
        entries.len(),
        t = escape(title)
    );
    let mut folder: Option<&str> = None;
    for e in entries {
        let here = e.path.rsplit_once('/').map_or("", |(f, _)| f);
        if folder != Some(here) {
            if folder.is_some() {
                html.push_str("</ul>");
            }
            let _ = write!(
                html,
                "<h2>{}</h2><ul>",
                escape(if here.is_empty() { "." } else { here })
            );
            folder = Some(here);
        }
        let _ = write!(
            html,
            "<li><a href=\"{}\">{}</a> <small>{}</small>",
            escape(&e.path),
            escape(&e.title),
            escape(&e.path)
        );
        if let Some(v) = &e.verdict {
            let _ = write!(html, "<br>{}", escape(v));
        }
        html.push_str("</li>");
    }
    if folder.is_some() {
        html.push_str("</ul>");
    }
    html.push_str("</body></html>\n");
    html
}

fn between<'a>(text: &'a str, start: &str, end: &str) -> Option<&'a str> {
    let from = text.find(start)? + start.len();
    let to = text[from..].find(end)? + from;
    Some(&text[from..to])
}

fn strip_tags(text: &str) -> String {
    let mut out = String::new();
    let mut inside = false;
    for c in text.chars() {
        match c {
            '<' => inside = true,
            '>' => inside = false,
            c if !inside => out.push(c),
            _ => {}
        }
    }
    out
}

fn unescape(text: &str) -> String {
    text.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&#39;", "'")
        .replace("&amp;", "&")
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
