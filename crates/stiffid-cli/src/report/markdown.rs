//! `report.md`: the report in Markdown, figures as links to their PNG files.

use super::content::{compose, Writer};
use super::figures::Figure;
use super::tables::Table;
use stiffid::app::reproduce::Report;
use stiffid::internal::view::Scene;

struct Markdown(String);

/// Text outside `code spans` with `&`, `<` and `>` as entities, so text from a setup (its name,
/// its description) can never become raw HTML in a Markdown renderer.
pub fn inline(text: &str) -> String {
    text.split('`')
        .enumerate()
        .map(|(i, part)| match i % 2 {
            1 => format!("`{part}`"),
            _ => part
                .replace('&', "&amp;")
                .replace('<', "&lt;")
                .replace('>', "&gt;"),
        })
        .collect()
}

fn cell(text: &str) -> String {
    inline(text).replace('|', "\\|")
}

impl Writer for Markdown {
    fn scene(&mut self, _scene: &Scene, glb: &str) {
        self.0 += &format!("The 3D scene: the HTML report, and {glb} (glTF binary, metres).\n\n");
    }
    fn heading(&mut self, level: usize, text: &str) {
        self.0 += &format!("{} {}\n\n", "#".repeat(level), inline(text));
    }
    fn paragraph(&mut self, text: &str) {
        self.0 += &format!("{}\n\n", inline(text));
    }
    fn list(&mut self, items: &[String]) {
        for item in items {
            self.0 += &format!("- {}\n", inline(item));
        }
        self.0 += "\n";
    }
    fn table(&mut self, table: &Table) {
        let row = |cells: &[String]| {
            format!(
                "| {} |\n",
                cells
                    .iter()
                    .map(|c| cell(c))
                    .collect::<Vec<_>>()
                    .join(" | ")
            )
        };
        self.0 += &row(&table.header);
        self.0 += &format!("|{}\n", "---|".repeat(table.header.len()));
        for r in &table.rows {
            self.0 += &row(r);
        }
        self.0 += "\n";
    }
    fn figure(&mut self, figure: &Figure) {
        self.0 += &format!(
            "![{}](figures/{}.png)\n\n*{}*\n\n",
            figure.name,
            figure.name,
            inline(&figure.caption)
        );
    }
}

/// The text of `report.md`.
pub fn report(report: &Report, figures: &[Figure]) -> String {
    let mut w = Markdown(String::new());
    compose(report, figures, &mut w);
    w.0
}
