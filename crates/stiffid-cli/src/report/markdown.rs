//! `report.md`: the report in Markdown, figures as links to their PNG files.

use super::content::{compose, Writer};
use super::figures::Figure;
use super::tables::Table;
use stiffid::study::Study;

struct Markdown(String);

fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

impl Writer for Markdown {
    fn heading(&mut self, level: usize, text: &str) {
        self.0 += &format!("{} {text}\n\n", "#".repeat(level));
    }
    fn paragraph(&mut self, text: &str) {
        self.0 += &format!("{text}\n\n");
    }
    fn list(&mut self, items: &[String]) {
        for item in items {
            self.0 += &format!("- {item}\n");
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
            figure.name, figure.name, figure.caption
        );
    }
}

/// The text of `report.md`.
pub fn report(study: &Study, figures: &[Figure]) -> String {
    let mut w = Markdown(String::new());
    compose(study, figures, &mut w);
    w.0
}
