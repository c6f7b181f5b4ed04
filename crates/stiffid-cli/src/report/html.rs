//! `report.html`: self-contained, figures inline as SVG, no external resources.

use super::content::compose;
pub use super::content::Writer;
use super::figures::Figure;
use super::tables::Table;
use stiffid::app::reproduce::document::GENERATOR;
use stiffid::app::reproduce::Report;

use stiffid::internal::view::page::{self as scene_page, escape};
use stiffid::internal::view::Scene;

/// Escaped text with `code spans` as `<code>`.
fn inline(text: &str) -> String {
    escape(text)
        .split('`')
        .enumerate()
        .map(|(i, part)| match i % 2 {
            1 => format!("<code>{part}</code>"),
            _ => part.to_string(),
        })
        .collect()
}

/// An HTML body being written; [`page`] wraps it into a document.
pub struct Html(String);

impl Writer for Html {
    fn heading(&mut self, level: usize, text: &str) {
        self.0 += &format!("<h{level}>{}</h{level}>\n", inline(text));
    }
    fn paragraph(&mut self, text: &str) {
        self.0 += &format!("<p>{}</p>\n", inline(text));
    }
    fn list(&mut self, items: &[String]) {
        self.0 += "<ul>\n";
        for item in items {
            self.0 += &format!("<li>{}</li>\n", inline(item));
        }
        self.0 += "</ul>\n";
    }
    fn table(&mut self, table: &Table) {
        self.0 += "<div class=\"scroll\"><table>\n<thead><tr>";
        for h in &table.header {
            self.0 += &format!("<th>{}</th>", inline(h));
        }
        self.0 += "</tr></thead>\n<tbody>\n";
        for row in &table.rows {
            self.0 += "<tr>";
            for cell in row {
                self.0 += &format!("<td>{}</td>", inline(cell));
            }
            self.0 += "</tr>\n";
        }
        self.0 += "</tbody></table></div>\n";
    }
    fn figure(&mut self, figure: &Figure) {
        let svg = figure.svg.trim_start_matches(|c| c != '<');
        let svg = svg
            .strip_prefix("<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
            .unwrap_or(svg);
        self.0 += &format!(
            "<figure id=\"{}\">\n{}\n<figcaption>{} <span class=\"files\">(figures/{}.svg{})</span></figcaption>\n</figure>\n",
            figure.name,
            svg.trim(),
            inline(&figure.caption),
            figure.name,
            if figure.png.is_some() { ", .png" } else { "" }
        );
    }
    fn scene(&mut self, scene: &Scene, glb: &str) {
        self.0 += &scene_page::fragment(scene, "scene");
        self.0 += &format!(
            "<p class=\"files\">The same scene as glTF binary for Blender, RoboDK and CAD viewers: {glb} (metres, a node per posture, a node per link).</p>\n"
        );
    }
}

const STYLE: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;max-width:1240px;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}
h1{font-size:1.6em}h2{margin-top:2em;border-bottom:1px solid #ccc;padding-bottom:.2em}
table{border-collapse:collapse;margin:1em 0;font-size:.9em}th,td{border:1px solid #ccc;padding:.3em .6em;text-align:left;vertical-align:top}
th{background:#f3f3f3}tbody tr:nth-child(even){background:#fafafa}.scroll{overflow-x:auto}
figure{margin:1.5em 0}figure svg{max-width:100%;height:auto;display:block}figcaption{font-size:.9em;color:#444;margin-top:.4em}
.files{color:#888}code{background:#f3f3f3;padding:0 .2em}";

/// A self-contained HTML page (figures inline, no external resources) titled `title`, marked as
/// written by `generator` (`<meta name="generator">`), with the body `body` writes.
pub fn page(title: &str, generator: &str, body: impl FnOnce(&mut dyn Writer)) -> String {
    let mut w = Html(String::new());
    body(&mut w);
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<meta name=\"generator\" content=\"{}\">\n<title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n{}<p class=\"files\">Written by stiffid {}.</p>\n</body>\n</html>\n",
        escape(generator),
        escape(title),
        w.0,
        env!("CARGO_PKG_VERSION")
    )
}

/// The text of `report.html`.
pub fn report(report: &Report, figures: &[Figure]) -> String {
    page(
        &format!("stiffid report: {}", report.study.setup.name()),
        GENERATOR,
        |w| compose(report, figures, w),
    )
}
