//! HTML text of a report: escaping, and the markdown the reports write ([`super::table::ToMarkdown`])
//! turned into HTML, so that the Markdown and the HTML form of a report hold the same content.
//!
//! The markdown is the subset the reports emit, line based: `#` headings, pipe tables (the rule line gives
//! each column's alignment; `\|` is a `|` inside a cell), `- ` bullet lists, fenced code blocks (the
//! scenario file as written), picture lines `![caption](path)` and paragraphs; inline code spans in
//! backticks. Every other character is text and is escaped. A level-2 heading opens a `<section>` (a page
//! of its own in print). The output is XHTML-compatible: every element is closed, empty elements are
//! written `<meta ... />`.

/// `text` with the five characters that are special in HTML text and attribute values replaced by their
/// entities (`&` first).
///
/// # Examples
/// ```
/// use stochvib::report::html::escape;
/// assert_eq!(escape(r#"<a href="x">Tom & 'Jerry'</a>"#), "&lt;a href=&quot;x&quot;&gt;Tom &amp; &#39;Jerry&#39;&lt;/a&gt;");
/// ```
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Escaped text with code spans: a pair of backticks encloses `<code>`; an unpaired backtick stays text.
fn inline(text: &str) -> String {
    let parts: Vec<&str> = text.split('`').collect();
    if parts.len().is_multiple_of(2) {
        return escape(text);
    }
    let mut out = String::new();
    for (i, p) in parts.iter().enumerate() {
        if i % 2 == 1 {
            out += &format!("<code>{}</code>", escape(p));
        } else {
            out += &escape(p);
        }
    }
    out
}

/// The cells of a pipe-table line (`| a | b \| c |` → `a`, `b | c`).
fn cells(line: &str) -> Vec<String> {
    let inner = line.trim().trim_start_matches('|');
    let inner = inner.strip_suffix('|').filter(|s| !s.ends_with('\\')).unwrap_or(inner);
    let mut out = vec![String::new()];
    let mut chars = inner.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'|') => out.last_mut().unwrap().push(chars.next().unwrap()),
            '|' => out.push(String::new()),
            c => out.last_mut().unwrap().push(c),
        }
    }
    out.into_iter().map(|c| c.trim().to_string()).collect()
}

/// A pipe table: the header row, the rule row (`---:` right-aligns a column) and the body rows.
fn table(lines: &[&str]) -> String {
    let numeric: Vec<bool> = lines
        .get(1)
        .map_or(vec![], |r| cells(r).iter().map(|c| c.ends_with(':')).collect());
    let row = |line: &str, tag: &str| {
        let tds: String = cells(line)
            .iter()
            .enumerate()
            .map(|(j, c)| {
                let class = if numeric.get(j) == Some(&true) {
                    " class=\"num\""
                } else {
                    ""
                };
                format!("<{tag}{class}>{}</{tag}>", inline(c))
            })
            .collect();
        format!("<tr>{tds}</tr>\n")
    };
    let mut out = format!("<table>\n<thead>\n{}</thead>\n<tbody>\n", row(lines[0], "th"));
    for l in lines.iter().skip(2) {
        out += &row(l, "td");
    }
    out + "</tbody>\n</table>\n"
}

/// The fence of a fenced block: the opening line's backticks (three or more).
fn fence(line: &str) -> Option<&str> {
    let n = line.chars().take_while(|c| *c == '`').count();
    (n >= 3).then(|| &line[..n])
}

/// A picture line `![caption](path)`: (caption, path).
fn picture(line: &str) -> Option<(&str, &str)> {
    let rest = line.trim().strip_prefix("![")?;
    let (caption, rest) = rest.split_once("](")?;
    Some((caption, rest.strip_suffix(')')?))
}

/// A heading line: (level, text).
fn heading(line: &str) -> Option<(usize, &str)> {
    let level = line.chars().take_while(|c| *c == '#').count();
    let text = line[level..].strip_prefix(' ')?;
    (1..=6).contains(&level).then_some((level, text))
}

/// What a line starts.
fn starts_block(line: &str) -> bool {
    line.trim().is_empty()
        || line.starts_with('|')
        || line.starts_with("- ")
        || line.starts_with("<!--")
        || fence(line).is_some()
        || heading(line).is_some()
        || picture(line).is_some()
}

/// The number of lines from `lines[0]` that satisfy `keep`.
fn run_of(lines: &[&str], keep: impl Fn(&str) -> bool) -> usize {
    lines.iter().take_while(|l| keep(l)).count()
}

/// Converts report markdown to HTML body text (see the module docs); `svg` gives the inline SVG of a
/// picture's path (`None`: the picture is linked with `<img>`, not inlined).
///
/// # Examples
/// ```
/// use stochvib::report::html::markdown_to_html;
/// let h = markdown_to_html("## Output `x`\n\n| a | b |\n|---|---:|\n| p&q | 1 |\n", &|_| None);
/// assert_eq!(h, "<section>\n<h2>Output <code>x</code></h2>\n<table>\n<thead>\n<tr><th>a</th><th class=\"num\">b</th></tr>\n\
/// </thead>\n<tbody>\n<tr><td>p&amp;q</td><td class=\"num\">1</td></tr>\n</tbody>\n</table>\n</section>\n");
/// ```
pub fn markdown_to_html(md: &str, svg: &dyn Fn(&str) -> Option<String>) -> String {
    let lines: Vec<&str> = md.lines().collect();
    let (mut out, mut i, mut open) = (String::new(), 0, false);
    while i < lines.len() {
        let (html, used) = block(&lines[i..], svg);
        if let Some((2, _)) = heading(lines[i]) {
            out += if open { "</section>\n<section>\n" } else { "<section>\n" };
            open = true;
        }
        out += &html;
        i += used;
    }
    if open {
        out += "</section>\n";
    }
    out
}

/// The HTML of the block that starts at `lines[0]` and the number of lines it takes.
fn block(lines: &[&str], svg: &dyn Fn(&str) -> Option<String>) -> (String, usize) {
    let l = lines[0];
    if l.trim().is_empty() || l.starts_with("<!--") {
        return (String::new(), 1);
    }
    if let Some(f) = fence(l) {
        let n = run_of(&lines[1..], |x| x.trim_end() != f);
        let body: Vec<String> = lines[1..1 + n].iter().map(|x| escape(x)).collect();
        return (format!("<pre><code>{}\n</code></pre>\n", body.join("\n")), n + 2);
    }
    if let Some((level, text)) = heading(l) {
        return (format!("<h{level}>{}</h{level}>\n", inline(text)), 1);
    }
    if let Some((caption, path)) = picture(l) {
        return (figure(caption, path, svg), 1);
    }
    if l.starts_with('|') {
        let n = run_of(lines, |x| x.starts_with('|'));
        return (table(&lines[..n]), n);
    }
    if l.starts_with("- ") {
        let n = run_of(lines, |x| x.starts_with("- "));
        let items: String = lines[..n]
            .iter()
            .map(|x| format!("<li>{}</li>\n", inline(&x[2..])))
            .collect();
        return (format!("<ul>\n{items}</ul>\n"), n);
    }
    let n = 1 + run_of(&lines[1..], |x| !starts_block(x));
    let text: Vec<String> = lines[..n].iter().map(|x| inline(x)).collect();
    (format!("<p>{}</p>\n", text.join("<br />\n")), n)
}

/// A picture with its caption: the SVG inline, else an `<img>` link.
fn figure(caption: &str, path: &str, svg: &dyn Fn(&str) -> Option<String>) -> String {
    let body = svg(path).unwrap_or_else(|| format!("<img src=\"{}\" alt=\"{}\" />", escape(path), escape(caption)));
    format!(
        "<figure>\n{body}\n<figcaption>{}</figcaption>\n</figure>\n",
        inline(caption)
    )
}

/// The style sheet of the HTML report: readable on screen, and in print one section a page with tables
/// and pictures never split.
pub const STYLE: &str = "
body { font-family: sans-serif; max-width: 60em; margin: 1em auto; padding: 0 1em; color: #111; line-height: 1.4; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #999; } h2, h3 { break-after: avoid; }
table { border-collapse: collapse; margin: 0.8em 0; break-inside: avoid; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 0.2em 0.5em; text-align: left; vertical-align: top; }
th { background: #eee; } td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
pre { background: #f6f6f6; border: 1px solid #ddd; padding: 0.6em; overflow-x: auto; font-size: 0.85em; }
code { font-family: monospace; }
figure { margin: 1em 0; break-inside: avoid; } figure svg { max-width: 100%; height: auto; }
figcaption { font-size: 0.9em; color: #444; }
@media print {
  body { max-width: none; margin: 0; }
  section { break-before: page; }
  pre { white-space: pre-wrap; overflow: visible; }
}
";

/// A whole HTML page: `title`, the style sheet and `body`; the first two lines mark it as a stochvib report
/// ([`PAGE_MARK`]).
pub fn page(title: &str, body: &str) -> String {
    format!(
        "{PAGE_MARK}\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\" />\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\" />\n\
         <meta name=\"generator\" content=\"stochvib {}\" />\n<title>{}</title>\n<style>{STYLE}</style>\n</head>\n\
         <body>\n{body}</body>\n</html>\n",
        env!("CARGO_PKG_VERSION"),
        escape(title)
    )
}

/// The beginning of every HTML report (how the output rule recognises one).
pub const PAGE_MARK: &str = "<!DOCTYPE html>\n<!-- stochvib report -->";
