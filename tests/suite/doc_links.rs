//! The front page and the user guide hold together: every relative link of README.md and of every page
//! under docs/ names a file that exists in the repository, and no page cites a file outside it (an absolute
//! path or one that climbs out of the checkout).

use crate::common::root;
use std::path::{Component, Path, PathBuf};

/// The targets of the inline markdown links `[text](target)` of `text`, without `#anchor`s; web links
/// (`scheme://`) and pure anchors are left out.
fn relative_links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("](") {
        rest = &rest[i + 2..];
        let Some(end) = rest.find(')') else { break };
        let target = rest[..end].split('#').next().unwrap_or("").trim();
        if !target.is_empty() && !target.contains("://") && !target.starts_with("mailto:") {
            out.push(target.to_string());
        }
        rest = &rest[end..];
    }
    out
}

/// The markdown pages checked: README.md and docs/*.md.
fn pages() -> Vec<PathBuf> {
    let mut v = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    v.extend(docs);
    v
}

/// `target` relative to the directory of `page`, normalised; None when it leaves the repository.
fn resolve(page: &Path, target: &str) -> Option<PathBuf> {
    if Path::new(target).is_absolute() {
        return None;
    }
    let mut p = page.parent().unwrap().strip_prefix(root()).unwrap().to_path_buf();
    for c in Path::new(target).components() {
        match c {
            Component::ParentDir if !p.pop() => return None,
            Component::ParentDir => {}
            Component::Normal(s) => p.push(s),
            _ => {}
        }
    }
    Some(root().join(p))
}

#[test]
fn every_relative_link_of_the_readme_and_the_guide_resolves_inside_the_repository() {
    let mut broken = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        for target in relative_links(&text) {
            match resolve(&page, &target) {
                Some(p) if p.exists() => {}
                Some(_) => broken.push(format!("{}: {target} does not exist", page.display())),
                None => broken.push(format!("{}: {target} is outside the repository", page.display())),
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_link_reader_finds_links_and_leaves_web_links_and_anchors_out() {
    let t = "a [x](docs/a.md#s) b [y](https://e.org/z) [z](#top) ![p](img/p.png) [w](../x.md)";
    assert_eq!(relative_links(t), ["docs/a.md", "img/p.png", "../x.md"]);
    let readme = root().join("README.md");
    assert_eq!(resolve(&readme, "docs/a.md"), Some(root().join("docs/a.md")));
    assert_eq!(resolve(&readme, "../outside.md"), None);
    assert_eq!(resolve(&readme, "/etc/passwd"), None);
}
